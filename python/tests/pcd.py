"""Minimal PCD files for the tests: write x y z as binary float32, read the binary or ASCII
files the pcl_ncut_seg tool writes (x y z rgb label)."""
import numpy as np

_TYPES = {("F", 4): "<f4", ("F", 8): "<f8", ("U", 1): "<u1", ("U", 2): "<u2", ("U", 4): "<u4",
          ("I", 1): "<i1", ("I", 2): "<i2", ("I", 4): "<i4"}


def write_xyz(path, points):
    points = np.ascontiguousarray(points, dtype="<f4")
    n = len(points)
    header = ("# .PCD v0.7 - Point Cloud Data file format\nVERSION 0.7\nFIELDS x y z\n"
              "SIZE 4 4 4\nTYPE F F F\nCOUNT 1 1 1\n"
              f"WIDTH {n}\nHEIGHT 1\nVIEWPOINT 0 0 0 1 0 0 0\nPOINTS {n}\nDATA binary\n")
    with open(path, "wb") as f:
        f.write(header.encode("ascii"))
        f.write(points.tobytes())


def read_fields(path):
    """{field: array} of a binary or ASCII PCD (counts of 1)."""
    with open(path, "rb") as f:
        data = f.read()
    header, pos = {}, 0
    while True:
        end = data.index(b"\n", pos)
        line = data[pos:end].decode("ascii").strip()
        pos = end + 1
        if not line or line.startswith("#"):
            continue
        key, *values = line.split()
        header[key] = values
        if key == "DATA":
            break
    fields, n = header["FIELDS"], int(header["POINTS"][0])
    dtype = np.dtype([(name, _TYPES[(t, int(s))])
                      for name, t, s in zip(fields, header["TYPE"], header["SIZE"])])
    kind = header["DATA"][0]
    if kind == "binary":
        records = np.frombuffer(data, dtype=dtype, count=n, offset=pos)
        return {name: records[name].copy() for name in fields}
    if kind == "ascii":
        rows = np.loadtxt(data[pos:].decode("ascii").splitlines(), dtype=np.float64, ndmin=2)
        return {name: rows[:, i].astype(dtype[name]) for i, name in enumerate(fields)}
    raise ValueError(f"{path}: DATA {kind} not supported")
