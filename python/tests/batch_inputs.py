"""A folder of small inputs for the batch tests: every format and encoding the tool reads
(PCD ascii, binary, binary_compressed, organized, with a VIEWPOINT; PLY ascii, binary little
and big endian, points and meshes; OFF; OBJ; .npy), and broken ones with the words of their
error."""
import os
import struct

import numpy as np

import pcd
import shapes

# name -> words the table's error must hold
BAD = {
    "broken/empty.pcd": "not a valid PCD file",
    "broken/truncated.pcd": "not a valid PCD file",
    "broken/truncated.ply": "not a valid PLY file",
    "broken/no_faces.off": "mesh without faces",
    "broken/no_faces.obj": "mesh without faces",
    "broken/all_nan.pcd": "no point with finite coordinates",
    "broken/all_nan.npy": "no point with finite coordinates",
    "broken/not_a_ply.ply": "not a valid PLY file",
    "broken/flat.npy": "(N, 3) or (H, W, 3)",
}


def make(folder):
    """Write the inputs under folder; returns (good names, bad names), relative paths."""
    good = []

    def add(name, write, *args):
        path = os.path.join(folder, name)
        os.makedirs(os.path.dirname(path), exist_ok=True)
        write(path, *args)
        good.append(name)

    for i in range(8):
        add(f"pcd/binary_{i}.pcd", pcd.write_xyz, _limbs(300 + 40 * i, i))
    for i in range(4):
        add(f"pcd/ascii_{i}.pcd", write_pcd_ascii, _limbs(320 + 30 * i, 10 + i))
    for i in range(3):
        add(f"pcd/compressed_{i}.pcd", write_pcd_compressed, _limbs(350 + 50 * i, 20 + i))
    for i in range(2):
        add(f"pcd/nan_rows_{i}.pcd", pcd.write_xyz, shapes.with_nan_rows(_limbs(400, 30 + i))[0])
    add("pcd/fields.pcd", write_pcd_fields, _limbs(380, 40))
    add("views/organized.pcd", write_pcd_view, _view(24, 20), (0, 0, 0))
    add("views/moved.pcd", write_pcd_view, _view(22, 18) + [0.5, -1.0, 2.0], (0.5, -1.0, 2.0))
    for i in range(2):
        add(f"ply/ascii_{i}.ply", write_ply, _limbs(330, 50 + i), None, "ascii")
    for i in range(2):
        add(f"ply/little_{i}.ply", write_ply, _limbs(360, 60 + i), None, "binary_little_endian")
    add("ply/big.ply", write_ply, _limbs(340, 70), None, "binary_big_endian")
    for i, form in enumerate(("binary_little_endian", "ascii", "binary_big_endian")):
        add(f"ply/mesh_{i}.ply", write_ply, *_capsule(12 + 2 * i, 8, triangles=i != 1), form)
    for i in range(4):
        add(f"meshes/capsule_{i}.off", write_off, *_capsule(10 + 2 * i, 8, triangles=i % 2 == 0))
    for i in range(3):
        add(f"meshes/tube_{i}.obj", write_obj, *_capsule(11 + 2 * i, 9, triangles=i == 1))
    add("meshes/same_stem.off", write_off, *_capsule(12, 8, triangles=True))
    add("meshes/same_stem.ply", write_ply, *_capsule(13, 8, triangles=True),
        "binary_little_endian")
    for i, dtype in enumerate((np.float32, np.float64, np.float64)):
        add(f"arrays/points_{i}.npy", _save, _limbs(310 + 30 * i, 80 + i).astype(dtype))
    add("arrays/image.npy", _save, _view(20, 16).astype(np.float32))
    _write_bad(folder)
    return sorted(good), sorted(BAD)


def _limbs(n, seed):
    return shapes.limbs(n, seed=seed).astype(np.float32)


def _save(path, array):
    np.save(path, array)


def _view(width, height):
    """An organized (H, W, 3) depth image of a ball from the origin, NaN off the ball."""
    u, v = np.meshgrid(np.linspace(-0.5, 0.5, width), np.linspace(-0.4, 0.4, height))
    rays = np.stack([u, v, np.ones_like(u)], axis=-1)
    rays /= np.linalg.norm(rays, axis=-1, keepdims=True)
    centre, radius = np.array([0.0, 0.0, 4.0]), 1.5
    b = rays @ centre
    disc = b * b - (centre @ centre - radius * radius)
    with np.errstate(invalid="ignore"):
        t = b - np.sqrt(disc)
    points = rays * t[..., None]
    points[disc < 0] = np.nan
    return points.astype(np.float32)


def _capsule(rings, sectors, triangles):
    """A closed tube with capped ends (quads, or triangles), as vertices and polygons."""
    vertices, polygons = [], []
    for r in range(rings):
        z = 3.0 * r / (rings - 1)
        radius = 0.5 + 0.3 * np.sin(np.pi * r / (rings - 1))
        for s in range(sectors):
            phi = 2 * np.pi * s / sectors
            vertices.append((radius * np.cos(phi), radius * np.sin(phi), z))
    vertices += [(0.0, 0.0, -0.4), (0.0, 0.0, 3.4)]
    bottom, top = len(vertices) - 2, len(vertices) - 1
    for r in range(rings - 1):
        for s in range(sectors):
            a, b = r * sectors + s, r * sectors + (s + 1) % sectors
            quad = [a, b, b + sectors, a + sectors]
            polygons += [quad[:3], [quad[0], quad[2], quad[3]]] if triangles else [quad]
    last = (rings - 1) * sectors
    for s in range(sectors):
        polygons.append([bottom, (s + 1) % sectors, s])
        polygons.append([top, last + s, last + (s + 1) % sectors])
    return np.array(vertices, np.float32), polygons


def _header(points, fields="x y z", size="4 4 4", kind="F F F", count="1 1 1",
            viewpoint=(0, 0, 0), data="binary"):
    height, width = points.shape[:2] if points.ndim == 3 else (1, len(points))
    return (f"# .PCD v0.7 - Point Cloud Data file format\nVERSION 0.7\nFIELDS {fields}\n"
            f"SIZE {size}\nTYPE {kind}\nCOUNT {count}\nWIDTH {width}\nHEIGHT {height}\n"
            f"VIEWPOINT {' '.join(map(str, viewpoint))} 1 0 0 0\n"
            f"POINTS {width * height}\nDATA {data}\n").encode("ascii")


def write_pcd_ascii(path, points):
    rows = "\n".join(" ".join(repr(float(v)) for v in p) for p in points)
    with open(path, "wb") as f:
        f.write(_header(points, data="ascii") + rows.encode("ascii") + b"\n")


def write_pcd_view(path, points, origin):
    with open(path, "wb") as f:
        f.write(_header(points, viewpoint=origin) + points.astype("<f4").tobytes())


def write_pcd_fields(path, points):
    """x y z among other fields: a normal of COUNT 3, an rgb, and padding."""
    n = len(points)
    records = np.zeros(n, [("x", "<f4"), ("y", "<f4"), ("z", "<f4"), ("normal", "<f4", 3),
                           ("rgb", "<u4"), ("_", "u1", 4)])
    records["x"], records["y"], records["z"] = points.T
    records["normal"] = 1.0
    records["rgb"] = 0x336699
    header = _header(points, "x y z normal rgb _", "4 4 4 4 4 1", "F F F F U U", "1 1 1 3 1 4")
    with open(path, "wb") as f:
        f.write(header + records.tobytes())


def write_pcd_compressed(path, points):
    """binary_compressed with an LZF stream of literal runs and back references."""
    raw = np.ascontiguousarray(points.astype("<f4").T).tobytes()  # all x, all y, all z
    packed = lzf_compress(raw)
    with open(path, "wb") as f:
        f.write(_header(points, data="binary_compressed")
                + struct.pack("<II", len(packed), len(raw)) + packed)


def lzf_compress(data):
    """A plain LZF compressor: a back reference for any 3 bytes seen within 8 KiB."""
    out, literal, seen, i = bytearray(), bytearray(), {}, 0

    def flush():
        for k in range(0, len(literal), 32):
            chunk = literal[k:k + 32]
            out.append(len(chunk) - 1)
            out.extend(chunk)
        literal.clear()

    while i < len(data):
        key, ref = data[i:i + 3], seen.get(data[i:i + 3], -1)
        seen[key] = i
        if len(key) == 3 and ref >= 0 and i - ref - 1 < 8192:
            length = 3
            while (i + length < len(data) and length < 264
                   and data[ref + length] == data[i + length]):
                length += 1
            flush()
            distance, code = i - ref - 1, length - 2
            if code < 7:
                out.append((code << 5) | (distance >> 8))
            else:
                out += bytes([(7 << 5) | (distance >> 8), code - 7])
            out.append(distance & 0xFF)
            i += length
        else:
            literal.append(data[i])
            i += 1
    flush()
    return bytes(out)


def write_ply(path, vertices, polygons, form):
    order = {"binary_little_endian": "<", "binary_big_endian": ">"}.get(form)
    head = (f"ply\nformat {form} 1.0\ncomment made by the batch tests\n"
            f"element vertex {len(vertices)}\nproperty float x\nproperty float y\n"
            "property float z\n")
    if polygons is not None:
        head += f"element face {len(polygons)}\nproperty list uchar int vertex_indices\n"
    head += "end_header\n"
    with open(path, "wb") as f:
        f.write(head.encode("ascii"))
        if order is None:
            f.write("".join(f"{x!r} {y!r} {z!r}\n" for x, y, z in vertices.tolist()).encode())
            for p in polygons or []:
                f.write((" ".join(map(str, [len(p)] + list(p))) + "\n").encode())
            return
        f.write(vertices.astype(order + "f4").tobytes())
        for p in polygons or []:
            f.write(struct.pack(f"{order}B{len(p)}i", len(p), *p))


def write_off(path, vertices, polygons):
    with open(path, "w") as f:
        f.write(f"OFF\n# a comment\n{len(vertices)} {len(polygons)} 0\n")
        f.writelines(f"{x!r} {y!r} {z!r}\n" for x, y, z in vertices.tolist())
        f.writelines(" ".join(map(str, [len(p)] + list(p))) + "\n" for p in polygons)


def write_obj(path, vertices, polygons):
    """v lines, then faces as v/vt/vn references, every other one with negative indices."""
    with open(path, "w") as f:
        f.write("# made by the batch tests\no capsule\n")
        f.writelines(f"v {x!r} {y!r} {z!r}\n" for x, y, z in vertices.tolist())
        f.write("vn 0 0 1\n")
        n = len(vertices)
        for k, p in enumerate(polygons):
            refs = [f"{i + 1}//1" if k % 2 else str(i - n) for i in p]
            f.write("f " + " ".join(refs) + "\n")


def _write_bad(folder):
    def path(name):
        full = os.path.join(folder, name)
        os.makedirs(os.path.dirname(full), exist_ok=True)
        return full

    open(path("broken/empty.pcd"), "wb").close()
    pcd.write_xyz(path("broken/truncated.pcd"), _limbs(500, 90))
    with open(path("broken/truncated.pcd"), "r+b") as f:
        f.truncate(f.seek(0, 2) - 1000)
    write_ply(path("broken/truncated.ply"), _limbs(300, 91), None, "binary_little_endian")
    with open(path("broken/truncated.ply"), "r+b") as f:
        f.truncate(f.seek(0, 2) - 100)
    vertices, _ = _capsule(10, 8, True)
    write_off(path("broken/no_faces.off"), vertices, [])
    write_obj(path("broken/no_faces.obj"), vertices, [])
    pcd.write_xyz(path("broken/all_nan.pcd"), np.full((200, 3), np.nan, np.float32))
    np.save(path("broken/all_nan.npy"), np.full((200, 3), np.nan))
    with open(path("broken/not_a_ply.ply"), "wb") as f:
        f.write(b"solid cube\nfacet normal 0 0 1\nendsolid\n")
    np.save(path("broken/flat.npy"), np.zeros((100, 2)))
