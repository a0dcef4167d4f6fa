"""PLY files without PCL: the vertices (x, y, z) and faces of an ASCII or binary PLY, as
pcl::PLYReader gives them to the pcl_ncut_seg tool (a PLY with faces is a mesh, one without a
point cloud)."""
import numpy as np

_TYPES = {"char": "i1", "int8": "i1", "uchar": "u1", "uint8": "u1", "short": "i2",
          "int16": "i2", "ushort": "u2", "uint16": "u2", "int": "i4", "int32": "i4",
          "uint": "u4", "uint32": "u4", "float": "f4", "float32": "f4", "double": "f8",
          "float64": "f8"}
_FORMATS = {"ascii": None, "binary_little_endian": "<", "binary_big_endian": ">"}
_FACE_LISTS = ("vertex_indices", "vertex_index")
_MAX_HEADER_BYTES = 1 << 20


class PlyError(ValueError):
    """A file that is not a PLY the tool can read."""


class _Element:
    def __init__(self, name, count):
        self.name, self.count, self.properties = name, count, []  # (name, type, list count type)


def read_ply(path):
    """read_ply(path) -> (vertices, polygons)

    vertices: float32 (V, 3); polygons: a list of vertex index lists, None when the file has
    no faces (a point cloud). Raises PlyError with the reason for a file that is not a PLY.
    """
    with open(path, "rb") as f:
        data = f.read()
    elements, byte_order, start = _read_header(data)
    body = _AsciiBody(data[start:]) if byte_order is None else _BinaryBody(data, start, byte_order)
    vertices, polygons = None, None
    for element in elements:
        if element.name == "vertex":
            vertices = _vertices(element, body.scalars(element))
        elif element.name == "face" and any(p[0] in _FACE_LISTS for p in element.properties):
            polygons = body.lists(element)
        else:
            body.skip(element)
        if vertices is not None and polygons is not None:
            break
    if vertices is None:
        raise PlyError("not a valid PLY file: no vertex element")
    return vertices, (polygons or None)


def _read_header(data):
    end = data.find(b"end_header", 0, _MAX_HEADER_BYTES)
    if not data.startswith(b"ply") or end < 0:
        raise PlyError("not a valid PLY file")
    newline = data.find(b"\n", end)
    start = len(data) if newline < 0 else newline + 1
    elements, byte_order = [], "missing"
    for line in data[:end].decode("latin-1").split("\n")[1:]:
        words = line.split()
        if not words or words[0] in ("comment", "obj_info"):
            continue
        if words[0] == "format" and len(words) >= 2 and words[1] in _FORMATS:
            byte_order = _FORMATS[words[1]]
        elif words[0] == "element" and len(words) == 3 and words[2].isdigit():
            elements.append(_Element(words[1], int(words[2])))
        elif (words[0] == "property" and elements and len(words) == 5 and words[1] == "list"
              and words[2] in _TYPES and words[3] in _TYPES):
            elements[-1].properties.append((words[4], _TYPES[words[3]], _TYPES[words[2]]))
        elif words[0] == "property" and elements and len(words) == 3 and words[1] in _TYPES:
            elements[-1].properties.append((words[2], _TYPES[words[1]], None))
        else:
            raise PlyError(f"not a valid PLY file: bad header line '{line.strip()}'")
    if byte_order == "missing":
        raise PlyError("not a valid PLY file: no format line")
    return elements, byte_order, start


def _vertices(element, columns):
    for name in "xyz":
        if name not in columns:
            raise PlyError(f"has no {name} field: need points with x, y and z")
    return np.stack([np.asarray(columns[c], np.float32) for c in "xyz"], axis=1)


class _AsciiBody:
    """The tokens of an ASCII body, read element by element."""

    def __init__(self, body):
        self.tokens, self.pos = body.decode("latin-1").split(), 0

    def _take(self, n):
        if self.pos + n > len(self.tokens):
            raise PlyError("not a valid PLY file: the data ends early")
        taken = self.tokens[self.pos:self.pos + n]
        self.pos += n
        return taken

    def _number(self, token):
        try:
            return float(token)
        except ValueError:
            raise PlyError(f"not a valid PLY file: bad number '{token}'") from None

    def scalars(self, element):
        if any(p[2] for p in element.properties):
            rows = [self._row(element) for _ in range(element.count)]
            return {p[0]: [row[i] for row in rows] for i, p in enumerate(element.properties)}
        width = len(element.properties)
        values = np.array([self._number(t) for t in self._take(width * element.count)])
        values = values.reshape(element.count, width)
        return {p[0]: values[:, i] for i, p in enumerate(element.properties)}

    def _row(self, element):
        row = []
        for _, _, count_type in element.properties:
            if count_type:
                n = int(self._number(self._take(1)[0]))
                row.append([int(self._number(t)) for t in self._take(n)])
            else:
                row.append(self._number(self._take(1)[0]))
        return row

    def lists(self, element):
        index = next(i for i, p in enumerate(element.properties) if p[0] in _FACE_LISTS)
        return [self._row(element)[index] for _ in range(element.count)]

    def skip(self, element):
        for _ in range(element.count):
            self._row(element)


class _BinaryBody:
    """A binary body, read element by element from an offset."""

    def __init__(self, data, start, byte_order):
        self.data, self.pos, self.order = data, start, byte_order

    def _read(self, dtype, count=1):
        dtype = np.dtype(dtype).newbyteorder(self.order)
        if self.pos + dtype.itemsize * count > len(self.data):
            raise PlyError("not a valid PLY file: the data ends early")
        values = np.frombuffer(self.data, dtype, count=count, offset=self.pos)
        self.pos += dtype.itemsize * count
        return values

    def scalars(self, element):
        if any(p[2] for p in element.properties):
            rows = [self._row(element) for _ in range(element.count)]
            return {p[0]: [row[i] for row in rows] for i, p in enumerate(element.properties)}
        dtype = np.dtype([(p[0], p[1]) for p in element.properties])
        records = self._read(dtype, element.count)
        return {name: records[name] for name in dtype.names}

    def _row(self, element):
        row = []
        for _, value_type, count_type in element.properties:
            if count_type:
                n = int(self._read(count_type)[0])
                row.append(self._read(value_type, n).tolist())
            else:
                row.append(self._read(value_type)[0])
        return row

    def lists(self, element):
        index = next(i for i, p in enumerate(element.properties) if p[0] in _FACE_LISTS)
        if len(element.properties) == 1 and element.count:
            polygons = self._same_size_lists(element)
            if polygons is not None:
                return polygons
        return [self._row(element)[index] for _ in range(element.count)]

    def _same_size_lists(self, element):
        """The faces of an element of one list whose lists all have the first one's size (a
        triangle mesh: read at once, not face by face); None when they do not."""
        _, value_type, count_type = element.properties[0]
        k = int(self._read(count_type)[0])
        self.pos -= np.dtype(count_type).itemsize
        dtype = np.dtype([("n", count_type), ("v", value_type, (k,))])
        if self.pos + dtype.itemsize * element.count > len(self.data):
            return None
        records = np.frombuffer(self.data, dtype.newbyteorder(self.order), element.count,
                                self.pos)
        if np.any(records["n"] != k):
            return None
        self.pos += dtype.itemsize * element.count
        return records["v"].astype(np.int64).tolist()

    def skip(self, element):
        if not any(p[2] for p in element.properties):
            self._read(np.dtype([(p[0], p[1]) for p in element.properties]), element.count)
            return
        for _ in range(element.count):
            self._row(element)
