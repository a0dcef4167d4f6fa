"""PCD files without PCL: read the x y z of an ASCII, binary or binary_compressed PCD (as
pcl::io::loadPCDFile reads them for the pcl_ncut_seg tool), and write the tool's output, a
binary PCD with x y z rgb label, byte for byte as the tool writes it."""
import mmap

import numpy as np

from ._clouds import segment_colors

_TYPES = {("F", 4): "f4", ("F", 8): "f8", ("U", 1): "u1", ("U", 2): "u2", ("U", 4): "u4",
          ("U", 8): "u8", ("I", 1): "i1", ("I", 2): "i2", ("I", 4): "i4", ("I", 8): "i8"}
DEFAULT_VIEWPOINT = (0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0)  # at the origin, not turned
_MAX_HEADER_LINES = 64  # a PCD header has about 11 lines; binary junk has no end of line


class PcdError(ValueError):
    """A file that is not a PCD the tool can read."""


def read_pcd(path):
    """read_pcd(path) -> (points, viewpoint)

    The x, y, z of a PCD as float32, (N, 3), or (H, W, 3) for an organized cloud (HEIGHT > 1),
    and its VIEWPOINT (tx ty tz qw qx qy qz: the sensor origin, then its orientation). Raises
    PcdError with the reason for a file the tool cannot read either.
    """
    with open(path, "rb") as f:
        data = f.read()
    header, start = _read_header(data)
    fields = _fields(header)
    width, height = _integer(header, "WIDTH"), _integer(header, "HEIGHT", 1)
    n = _integer(header, "POINTS", width * height)
    if n != width * height:
        raise PcdError(f"not a valid PCD file: POINTS {n} is not WIDTH x HEIGHT "
                       f"({width} x {height})")
    for name in "xyz":
        if name not in fields:
            raise PcdError(f"has no {name} field: need points with x, y and z")
    if n == 0:
        raise PcdError("contains no points")
    kind = header["DATA"][0].lower() if header.get("DATA") else ""
    dtype = np.dtype([(name, t) for name, t in fields.items()])
    if kind == "ascii":
        records = _ascii_records(data[start:], dtype, n)
    elif kind == "binary":
        records = _binary_records(data[start:], dtype, n)
    elif kind == "binary_compressed":
        records = _compressed_records(data[start:], dtype, n)
    else:
        raise PcdError(f"not a valid PCD file: DATA {kind or 'missing'}")
    xyz = np.stack([records[c].astype(np.float32) for c in "xyz"], axis=-1)
    return (xyz.reshape(height, width, 3) if height > 1 else xyz), _viewpoint(header)


def _read_header(data):
    """{KEY: [values]} of the header and the offset of the data after the DATA line."""
    header, pos = {}, 0
    for _ in range(_MAX_HEADER_LINES):
        end = data.find(b"\n", pos)
        if end < 0:
            break
        try:
            line = data[pos:end].decode("ascii").strip()
        except UnicodeDecodeError:
            break
        pos = end + 1
        if not line or line.startswith("#"):
            continue
        key, *values = line.split()
        header["FIELDS" if key.upper() == "COLUMNS" else key.upper()] = values
        if key.upper() == "DATA":
            return header, pos
    raise PcdError("not a valid PCD file")


def _viewpoint(header):
    values = header.get("VIEWPOINT", DEFAULT_VIEWPOINT)
    try:
        viewpoint = tuple(float(np.float32(v)) for v in values)
    except ValueError:
        viewpoint = ()
    if len(viewpoint) != 7:
        raise PcdError(f"not a valid PCD file: bad VIEWPOINT {' '.join(values)}")
    return viewpoint


def _integer(header, key, default=None):
    values = header.get(key)
    if not values:
        if default is None:
            raise PcdError(f"not a valid PCD file: no {key}")
        return default
    try:
        value = int(values[0])
    except ValueError:
        raise PcdError(f"not a valid PCD file: bad {key} {values[0]}") from None
    if value < 0:
        raise PcdError(f"not a valid PCD file: bad {key} {value}")
    return value


def _fields(header):
    """{name: numpy type} of the header's fields ('_' padding kept, under unique names)."""
    names, sizes, types = header.get("FIELDS"), header.get("SIZE"), header.get("TYPE")
    counts = header.get("COUNT", ["1"] * len(names or []))
    if not names or not (len(names) == len(sizes or []) == len(types or []) == len(counts)):
        raise PcdError("not a valid PCD file: FIELDS, SIZE, TYPE and COUNT do not match")
    fields = {}
    for i, (name, size, kind, count) in enumerate(zip(names, sizes, types, counts)):
        try:
            base, count = _TYPES[(kind.upper(), int(size))], int(count)
        except (KeyError, ValueError):
            raise PcdError(f"not a valid PCD file: field {name} has TYPE {kind} "
                           f"SIZE {size} COUNT {count}") from None
        if count < 1:
            raise PcdError(f"not a valid PCD file: field {name} has COUNT {count}")
        key = f"_{i}" if name == "_" or name in fields else name
        fields[key] = f"<{base}" if count == 1 else (f"<{base}", count)
    return fields


def _ascii_records(text, dtype, n):
    # PCL skips blank lines and reads the first values of each line (as many as the fields).
    lines = [line.split() for line in text.decode("ascii", "replace").splitlines()]
    rows = [line for line in lines if line]
    if len(rows) < n:
        raise PcdError(f"not a valid PCD file: {len(rows)} of {n} points")
    width = sum(int(np.prod(dtype[name].shape or 1)) for name in dtype.names)
    try:
        values = np.array([[float(v) for v in row[:width]] for row in rows[:n]], np.float64)
    except ValueError as error:
        raise PcdError(f"not a valid PCD file: {error}") from None
    if values.shape != (n, width):
        raise PcdError("not a valid PCD file: a point has too few values")
    columns = {}
    for name in dtype.names:
        count = int(np.prod(dtype[name].shape or 1))
        columns[name], values = values[:, 0], values[:, count:]
    return columns


def _binary_records(body, dtype, n):
    if len(body) < dtype.itemsize * n:
        raise PcdError(f"not a valid PCD file: the data ends after "
                       f"{len(body) // dtype.itemsize} of {n} points")
    return np.frombuffer(body, dtype=dtype, count=n)


def _compressed_records(body, dtype, n):
    """binary_compressed: LZF of the fields one after the other (all x, then all y, ...)."""
    if len(body) < 8:
        raise PcdError("not a valid PCD file: no compressed data")
    compressed, size = np.frombuffer(body, "<u4", count=2)
    if size != dtype.itemsize * n or len(body) < 8 + compressed:
        raise PcdError("not a valid PCD file: the compressed data is cut short or does not "
                       "hold the points")
    raw = lzf_decompress(body[8:8 + int(compressed)], int(size))
    columns, offset = {}, 0
    for name in dtype.names:
        field = np.dtype(dtype[name])
        columns[name] = np.frombuffer(raw, field, count=n, offset=offset)
        offset += field.itemsize * n
    return columns


def lzf_decompress(data, size):
    """LZF (liblzf's format, as PCL writes it) of data into size bytes; PcdError when corrupt."""
    out, i, n = bytearray(), 0, len(data)
    try:
        while i < n:
            control = data[i]
            i += 1
            if control < 32:  # a literal run of control + 1 bytes
                out += data[i:i + control + 1]
                i += control + 1
                continue
            length = control >> 5  # a back reference: length - 2, then the distance - 1
            if length == 7:
                length += data[i]
                i += 1
            length += 2
            distance = ((control & 0x1F) << 8) + data[i] + 1
            i += 1
            start = len(out) - distance
            if start < 0:
                raise IndexError
            chunk = out[start:start + length]  # overlapping: the last `distance` bytes repeat
            out += (chunk * (length // len(chunk) + 1))[:length]
    except IndexError:
        raise PcdError("not a valid PCD file: corrupt compressed data") from None
    if len(out) != size or i != n:
        raise PcdError("not a valid PCD file: corrupt compressed data")
    return bytes(out)


def labelled_pcd(points, labels, viewpoint=DEFAULT_VIEWPOINT):
    """The bytes of the tool's output for points ((N, 3) or (H, W, 3) float32) and their labels:
    a binary PCD with x y z rgb label (the rgb of segment_colors() packed as PCL packs it) and
    the input's VIEWPOINT."""
    xyz = np.asarray(points, np.float32)
    height, width = (xyz.shape[0], xyz.shape[1]) if xyz.ndim == 3 else (1, len(xyz))
    labels = np.asarray(labels).reshape(-1).astype("<u4")
    colors = segment_colors(labels).astype(np.uint32)
    records = np.empty(len(labels), np.dtype([("xyz", "<f4", 3), ("rgb", "<u4"),
                                              ("label", "<u4")]))
    records["xyz"] = xyz.reshape(-1, 3)
    records["rgb"] = (colors[:, 0] << 16) | (colors[:, 1] << 8) | colors[:, 2]
    records["label"] = labels
    viewpoint = " ".join(_pcl_number(v) for v in viewpoint)
    header = ("# .PCD v0.7 - Point Cloud Data file format\nVERSION 0.7\n"
              "FIELDS x y z rgb label\nSIZE 4 4 4 4 4\nTYPE F F F F U\nCOUNT 1 1 1 1 1\n"
              f"WIDTH {width}\nHEIGHT {height}\nVIEWPOINT {viewpoint}\n"
              f"POINTS {len(labels)}\nDATA binary\n")
    header = header.encode("ascii")
    # PCL's writeBinary leaves the file a page longer than its data, zeros after the points;
    # the same padding makes the output the tool's byte for byte.
    padding = mmap.PAGESIZE - len(header) % mmap.PAGESIZE
    return header + records.tobytes() + bytes(padding)


def _pcl_number(value):
    """A number as PCL writes the VIEWPOINT (an ostream's default: 6 significant digits)."""
    return f"{float(value):g}"
