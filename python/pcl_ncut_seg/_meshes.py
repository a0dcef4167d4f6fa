"""OFF and OBJ meshes without PCL, read as the pcl_ncut_seg tool reads them
(kit/surfaces/mesh_sampling.cpp), and the tool's points of a mesh: one per face, its area-weighted
centroid, computed in the same order of operations so that the points are the same floats."""
import numpy as np


class MeshError(ValueError):
    """A file that is not a mesh the tool can read."""


class Mesh:
    """vertices (V, 3) float32; triangles (T, 3) int64, the file's polygons fan-triangulated;
    face (T,): the polygon of the file each triangle comes from; num_faces: the file's faces."""

    def __init__(self, vertices, polygons):
        self.vertices = np.asarray(vertices, np.float32).reshape(-1, 3)
        triangles, face = [], []
        for f, polygon in enumerate(polygons):
            for i in range(1, len(polygon) - 1):
                triangles.append((polygon[0], polygon[i], polygon[i + 1]))
                face.append(f)
        self.triangles = np.array(triangles, np.int64).reshape(-1, 3)
        self.face = np.array(face, np.int64)
        self.num_faces = len(polygons)


def _lines(path):
    """(line number, tokens) of every line with tokens, '#' comments dropped."""
    with open(path, "rb") as f:
        text = f.read().decode("latin-1")
    for number, line in enumerate(text.split("\n"), 1):  # '\r' is a space, as for the tool
        tokens = line.split("#", 1)[0].split()
        if tokens:
            yield number, tokens


def _unsigned(token):
    digits = token[1:] if token.startswith("+") else token
    return int(digits) if digits.isascii() and digits.isdigit() else None


def _signed(token):
    digits = token[1:] if token[:1] in "+-" else token
    return int(token) if digits.isascii() and digits.isdigit() else None


def _floats(tokens):
    """float32 of number tokens, or None when one is not a number a float holds."""
    if any("_" in t for t in tokens):  # Python reads 1_0 as 10; the tool does not
        return None
    try:
        wide = np.array([float(t) for t in tokens], np.float64)
    except ValueError:
        return None
    with np.errstate(over="ignore"):
        narrow = wide.astype(np.float32)
    return None if np.any(np.isinf(narrow) & np.isfinite(wide)) else narrow


def _is_off_keyword(token):
    """OFF and its prefixed variants (COFF, NOFF, STOFF, ...): extra vertex values ignored."""
    return token.endswith("OFF") and all(c in "STCN" for c in token[:-3])


def read_off(path):
    """The mesh of an OFF file; MeshError with the line and the reason when it is malformed."""
    lines = _lines(path)
    number, tokens = next(lines, (0, None))
    if not tokens or not _is_off_keyword(tokens[0]):
        raise MeshError(f"line {number}: not an OFF file (no OFF header)")
    counts = tokens[1:] or next(lines, (number, None))[1]
    if not counts:
        raise MeshError(f"line {number}: missing vertex and face counts")
    num_vertices, num_faces = (_unsigned(t) for t in (counts + [""])[:2])
    if num_vertices is None or num_faces is None:
        raise MeshError(f"line {number}: bad vertex and face counts")
    vertices = []
    for v in range(num_vertices):
        number, tokens = next(lines, (number, None))
        if tokens is None:
            raise MeshError(f"line {number}: file ends before vertex {v}")
        xyz = _floats(tokens[:3]) if len(tokens) >= 3 else None
        if xyz is None:
            raise MeshError(f"line {number}: bad vertex {v}")
        vertices.append(xyz)
    polygons = []
    for f in range(num_faces):
        number, tokens = next(lines, (number, None))
        if tokens is None:
            raise MeshError(f"line {number}: file ends before face {f}")
        k = _unsigned(tokens[0])
        if k is None or k < 3 or len(tokens) < k + 1:
            raise MeshError(f"line {number}: bad face {f}")
        polygon = [_unsigned(t) for t in tokens[1:k + 1]]  # then a colour: ignored
        if any(i is None or i >= num_vertices for i in polygon):
            raise MeshError(f"line {number}: bad vertex index in face {f}")
        polygons.append(polygon)
    return Mesh(vertices, polygons)


def read_obj(path):
    """The mesh of a Wavefront OBJ file's "v" and "f" lines (a/t/n references, negative
    indices); MeshError with the line and the reason when it is malformed."""
    vertices, polygons = [], []
    for number, tokens in _lines(path):
        if tokens[0] == "v":
            xyz = _floats(tokens[1:4]) if len(tokens) >= 4 else None
            if xyz is None:
                raise MeshError(f"line {number}: bad vertex")
            vertices.append(xyz)
        elif tokens[0] == "f":
            if len(tokens) < 4:
                raise MeshError(f"line {number}: a face needs at least three vertices")
            polygon = []
            for token in tokens[1:]:
                index = _signed(token.split("/", 1)[0])
                if not index:
                    raise MeshError(f"line {number}: bad vertex index in face")
                index = index - 1 if index > 0 else len(vertices) + index  # < 0: from the end
                if not 0 <= index < len(vertices):
                    raise MeshError(f"line {number}: vertex index out of range in face")
                polygon.append(index)
            polygons.append(polygon)
    if not vertices and not polygons:
        raise MeshError("not an OBJ file (no vertices)")
    return Mesh(vertices, polygons)


def face_centroids(mesh):
    """One point per face of the file: its area-weighted centroid, the mean of its triangles'
    centroids when it has no area (float32, (F, 3)); the tool's faceCentroids()."""
    v = mesh.vertices.astype(np.float64)
    a, b, c = (v[mesh.triangles[:, i]] for i in range(3))
    u, w = b - a, c - a
    cross = np.stack([u[:, 1] * w[:, 2] - u[:, 2] * w[:, 1],
                      u[:, 2] * w[:, 0] - u[:, 0] * w[:, 2],
                      u[:, 0] * w[:, 1] - u[:, 1] * w[:, 0]], axis=1)
    area = 0.5 * np.sqrt(cross[:, 0] * cross[:, 0] + cross[:, 1] * cross[:, 1]
                         + cross[:, 2] * cross[:, 2])
    centroid = (a + b + c) / 3.0
    n = mesh.num_faces
    # np.add.at sums in the triangles' order, as the tool's loop does: the same rounding.
    weighted, plain, total = np.zeros((n, 3)), np.zeros((n, 3)), np.zeros(n)
    np.add.at(weighted, mesh.face, area[:, None] * centroid)
    np.add.at(plain, mesh.face, centroid)
    np.add.at(total, mesh.face, area)
    count = np.maximum(np.bincount(mesh.face, minlength=n), 1)
    with np.errstate(invalid="ignore", divide="ignore"):
        points = np.where((total > 0)[:, None], weighted / total[:, None], plain / count[:, None])
    return points.astype(np.float32)
