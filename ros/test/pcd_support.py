"""pcl_ncut_seg rostests on real views: the shared data, the mesh sampler's depth views, the
command-line tool's labels, and PCD files read and written in plain Python (no numpy).

The programs and the data come from the environment ctest gives the tests
(ros/test/CMakeLists.txt): PCL_NCUT_SEG_TOOL, PCL_NCUT_SEG_SAMPLE_MESH, PCL_NCUT_SEG_SHARED_DATA.
"""
import math
import os
import struct
import subprocess

from sensor_msgs.msg import PointCloud2, PointField
from std_msgs.msg import Header

IDENTITY_POSE = (0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0)  # PCD VIEWPOINT: tx ty tz qw qx qy qz
_TYPES = {("F", 4): "f", ("F", 8): "d", ("U", 4): "I", ("I", 4): "i", ("U", 1): "B"}


def shared_data():
    """The shared data directory, or None when it is absent (the tests then skip)."""
    path = os.environ.get("PCL_NCUT_SEG_SHARED_DATA", "")
    return path if path and os.path.isdir(path) else None


class Pcd:
    """A PCD file's points: fields, width x height, the VIEWPOINT pose and one tuple per point."""

    def __init__(self, fields, width, height, viewpoint, points):
        self.fields, self.width, self.height = fields, width, height
        self.viewpoint, self.points = viewpoint, points

    def column(self, name):
        i = self.fields.index(name)
        return [p[i] for p in self.points]


def read_pcd(path):
    """A binary (uncompressed) PCD, as the tool and the mesh sampler write them."""
    with open(path, "rb") as f:
        head = {}
        while True:
            line = f.readline().decode("ascii").strip()
            if not line or line.startswith("#"):
                continue
            key, _, value = line.partition(" ")
            head[key] = value.split()
            if key == "DATA":
                break
        assert head["DATA"] == ["binary"], "%s: DATA %s" % (path, head["DATA"])
        fields = head["FIELDS"]
        counts = [int(c) for c in head.get("COUNT", ["1"] * len(fields))]
        assert counts == [1] * len(fields), counts
        codes = "".join(_TYPES[(t, int(s))] for t, s in zip(head["TYPE"], head["SIZE"]))
        width, height = int(head["WIDTH"][0]), int(head["HEIGHT"][0])
        record = struct.Struct("<" + codes)
        data = f.read(record.size * width * height)
    viewpoint = tuple(float(v) for v in head.get("VIEWPOINT", IDENTITY_POSE))
    return Pcd(fields, width, height, viewpoint, list(record.iter_unpack(data)))


def write_pcd(path, xyz, width, height=1, viewpoint=IDENTITY_POSE):
    """x y z as FLOAT32, binary; xyz a list of (x, y, z)."""
    head = ("# .PCD v0.7 - Point Cloud Data file format\nVERSION 0.7\nFIELDS x y z\n"
            "SIZE 4 4 4\nTYPE F F F\nCOUNT 1 1 1\nWIDTH %d\nHEIGHT %d\nVIEWPOINT %s\n"
            "POINTS %d\nDATA binary\n" % (width, height, " ".join(repr(v) for v in viewpoint),
                                          width * height))
    with open(path, "wb") as f:
        f.write(head.encode("ascii"))
        f.write(pack_xyz(xyz))


def pack_xyz(xyz):
    return struct.pack("<%df" % (3 * len(xyz)), *(c for p in xyz for c in p))


def float32(xyz):
    """The points as FLOAT32 holds them."""
    flat = struct.unpack("<%df" % (3 * len(xyz)), pack_xyz(xyz))
    return list(zip(flat[0::3], flat[1::3], flat[2::3]))


def rotate(q, v):
    """v rotated by the unit quaternion q = (w, x, y, z)."""
    w, x, y, z = q
    # v + 2 w (u x v) + 2 u x (u x v), u = (x, y, z)
    c = (y * v[2] - z * v[1], z * v[0] - x * v[2], x * v[1] - y * v[0])
    cc = (y * c[2] - z * c[1], z * c[0] - x * c[2], x * c[1] - y * c[0])
    return tuple(v[i] + 2 * w * c[i] + 2 * cc[i] for i in range(3))


def to_frame(xyz, pose, inverse=False):
    """Points moved by pose (tx ty tz qw qx qy qz: frame -> parent), or into the pose's frame
    with inverse; NaN stays NaN."""
    t, q = pose[:3], pose[3:]
    out = []
    for p in xyz:
        if not all(map(math.isfinite, p)):
            out.append(p)
        elif inverse:
            d = (p[0] - t[0], p[1] - t[1], p[2] - t[2])
            out.append(rotate((q[0], -q[1], -q[2], -q[3]), d))
        else:
            r = rotate(q, p)
            out.append((r[0] + t[0], r[1] + t[1], r[2] + t[2]))
    return out


def camera_view(model, seed, resolution, workdir):
    """The mesh sampler's depth view of a shared model, moved into its camera's frame (as a
    depth camera's driver publishes it): (path of its PCD, its Pcd; VIEWPOINT identity). The
    sampler writes the points in the mesh's frame with the camera's pose as VIEWPOINT."""
    raw = os.path.join(workdir, "%s_%d_mesh_frame.pcd" % (model, seed))
    subprocess.run([os.environ["PCL_NCUT_SEG_SAMPLE_MESH"],
                    os.path.join(shared_data(), "models", model + ".off"), raw, "-view",
                    str(seed), "-resolution", resolution],
                   check=True, stdout=subprocess.DEVNULL)
    mesh = read_pcd(raw)
    xyz = float32(to_frame(mesh.points, mesh.viewpoint, inverse=True))
    path = os.path.join(workdir, "%s_%d.pcd" % (model, seed))
    write_pcd(path, xyz, mesh.width, mesh.height)
    return path, read_pcd(path)


def cli_labels(path, workdir, *flags):
    """The command-line tool's labels for the PCD (binary x y z rgb label out), and its Pcd."""
    out = os.path.join(workdir, os.path.basename(path)[:-4] + "_labels.pcd")
    subprocess.run([os.environ["PCL_NCUT_SEG_TOOL"], path, out, "-quiet"] + list(flags),
                   check=True, stdout=subprocess.DEVNULL)
    labelled = read_pcd(out)
    return labelled.column("label"), labelled


def cloud_msg(xyz, stamp, frame, width=None, height=1):
    """A PointCloud2 of x y z FLOAT32 (organized width x height if given), packed at once."""
    msg = PointCloud2(header=Header(stamp=stamp, frame_id=frame))
    msg.width, msg.height = (width, height) if width is not None else (len(xyz), 1)
    msg.fields = [PointField(n, 4 * i, PointField.FLOAT32, 1) for i, n in enumerate("xyz")]
    msg.point_step, msg.row_step = 12, 12 * msg.width
    msg.data = pack_xyz(xyz)
    msg.is_dense = all(math.isfinite(c) for p in xyz for c in p)
    return msg


def finite(xyz):
    return [p for p in xyz if all(math.isfinite(c) for c in p)]


def output_labels(msg):
    """The label of each point of the node's labelled cloud (x y z rgb label, 20 bytes a point)."""
    assert [(f.name, f.offset) for f in msg.fields] == \
        [("x", 0), ("y", 4), ("z", 8), ("rgb", 12), ("label", 16)], msg.fields
    assert msg.point_step == 20 and msg.row_step == 20 * msg.width, (msg.point_step, msg.row_step)
    return list(memoryview(bytes(msg.data)).cast("I")[4::5])


def agreement(a, b):
    """The fraction of points with the same label."""
    return sum(x == y for x, y in zip(a, b)) / max(len(a), 1)
