"""The points of a file as the pcl_ncut_seg tool reads them (kit/cli/input.cpp): a point
cloud (.pcd, .ply), a mesh as one point per face centroid (.off, .obj, .ply with faces), and
numpy's .npy arrays ((N, 3) or an organized (H, W, 3)). The batch front end reads its inputs
here, so that its labels are the tool's."""
import os

import numpy as np

from ._meshes import Mesh, MeshError, face_centroids, read_obj, read_off
from ._pcd import DEFAULT_VIEWPOINT, PcdError, read_pcd
from ._ply import PlyError, read_ply

EXTENSIONS = (".pcd", ".ply", ".off", ".obj", ".npy")


class InputError(ValueError):
    """A file whose points cannot be read; the message says why, in one line."""


class Cloud:
    """points: float32, (N, 3) or (H, W, 3); viewpoint: the PCD's VIEWPOINT (tx ty tz qw qx qy
    qz), the sensor origin first; faces: the mesh's faces, None for a point cloud."""

    def __init__(self, points, viewpoint=DEFAULT_VIEWPOINT, faces=None):
        self.points, self.viewpoint, self.faces = points, tuple(viewpoint), faces

    @property
    def sensor_origin(self):
        return self.viewpoint[:3]


def read_cloud(path):
    """The Cloud of a file; InputError when the tool could not segment it either."""
    path = os.fspath(path)
    ext = os.path.splitext(path)[1].lower()
    if ext not in EXTENSIONS:
        raise InputError(f"not a {', '.join(EXTENSIONS[:-1])} or {EXTENSIONS[-1]} file")
    if os.path.isdir(path) or (os.path.exists(path) and not os.path.isfile(path)):
        raise InputError("not a regular file")
    try:
        cloud = _READERS[ext](path)
    except (PcdError, PlyError, MeshError) as error:
        raise InputError(_reason(ext, error)) from None
    except OSError as error:
        raise InputError(f"cannot read: {error.strerror}") from None
    points = cloud.points.reshape(-1, 3)
    if len(points) == 0:
        raise InputError("contains no points")
    if not np.isfinite(points).all(axis=1).any():
        raise InputError("contains no point with finite coordinates")
    return cloud


def _reason(ext, error):
    """The tool's words: a mesh's reason is 'cannot read' plus where in the file."""
    text = str(error)
    return f"cannot read: {text}" if ext in (".off", ".obj") else text


def _read_pcd(path):
    points, viewpoint = read_pcd(path)
    return Cloud(points, viewpoint)


def _read_ply(path):
    vertices, polygons = read_ply(path)
    if polygons is None:
        return Cloud(vertices)
    if len(vertices) == 0:
        raise InputError("contains no points")
    for f, polygon in enumerate(polygons):
        if any(not 0 <= i < len(vertices) for i in polygon):
            raise InputError(f"cannot read: face {f} refers to a vertex that does not exist")
    return _mesh_cloud(Mesh(vertices, polygons))


def _read_mesh(reader):
    return lambda path: _mesh_cloud(reader(path))


def _mesh_cloud(mesh):
    if len(mesh.triangles) == 0:
        raise InputError("is a mesh without faces (polygons of three or more vertices)")
    return Cloud(face_centroids(mesh), faces=mesh.num_faces)


def _read_npy(path):
    try:
        array = np.load(path, allow_pickle=False)
    except ValueError as error:  # not an .npy, or one of objects
        raise InputError(f"not a valid .npy file: {error}") from None
    if array.dtype.kind not in "fiu" or array.ndim not in (2, 3) or array.shape[-1] != 3:
        raise InputError(f"an .npy of points must be (N, 3) or (H, W, 3) numbers, got "
                         f"{array.dtype.name} of shape {array.shape}")
    # float32, as a PCD holds them: the labels are those of the tool on the PCD written.
    return Cloud(array.astype(np.float32))


_READERS = {".pcd": _read_pcd, ".ply": _read_ply, ".off": _read_mesh(read_off),
            ".obj": _read_mesh(read_obj), ".npy": _read_npy}
