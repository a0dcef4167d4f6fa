#!/usr/bin/python3
"""Writes the seed inputs of test/fuzz/corpus_read for fuzz_read (the fuzzer adds its own beside
them): small pieces of the shared clouds and meshes (../shared/data: PCL's test clouds, BSD-3;
CGAL's example meshes, CC0; the Stanford bunny, public domain) in every form the reader takes.
Each seed is one byte that chooses the format (0 .pcd, 1 .ply, 2 .npy, 3 .off, 4 .obj), then
the file.

    /usr/bin/python3 test/fuzz/make_read_corpus.py [shared data directory]
"""
import hashlib
import io
import os
import shutil
import struct
import subprocess
import sys
import tempfile

import numpy as np

HERE = os.path.join(os.path.dirname(os.path.abspath(__file__)), "corpus_read")
PCD, PLY, NPY, OFF, OBJ = range(5)


def pcd_points(path, n):
    """The first n rows of an ascii PCD's data and its FIELDS."""
    with open(path, "rb") as f:
        lines = f.read().decode("ascii").splitlines()
    fields = next(l.split()[1:] for l in lines if l.startswith("FIELDS"))
    start = next(i for i, l in enumerate(lines) if l.startswith("DATA")) + 1
    return fields, np.array([[float(v) for v in l.split()] for l in lines[start:start + n]],
                            np.float32)


def lzf_literals(data):
    """LZF of data as literal runs only: valid LZF that PCL's lzfDecompress reads."""
    out = bytearray()
    for i in range(0, len(data), 32):
        chunk = data[i:i + 32]
        out += bytes([len(chunk) - 1]) + chunk
    return bytes(out)


def pcd(fields, values, data, height=1):
    n = len(values)
    header = (f"# .PCD v0.7 - Point Cloud Data file format\nVERSION 0.7\nFIELDS {' '.join(fields)}\n"
              f"SIZE {' '.join('4' for _ in fields)}\nTYPE {' '.join('F' for _ in fields)}\n"
              f"COUNT {' '.join('1' for _ in fields)}\nWIDTH {n // height}\nHEIGHT {height}\n"
              f"VIEWPOINT 0 0 0 1 0 0 0\nPOINTS {n}\nDATA {data}\n").encode()
    if data == "ascii":
        return header + "".join(" ".join(f"{v:g}" for v in row) + "\n"
                                for row in values).encode()
    raw = values.astype("<f4")
    if data == "binary":
        return header + raw.tobytes()
    columns = raw.T.copy().tobytes()  # binary_compressed: field after field
    block = lzf_literals(columns)
    return header + struct.pack("<II", len(block), len(columns)) + block


def pcl_compressed(ascii_pcd):
    """The cloud as PCL's own writer compresses it (real LZF back references), when PCL's tools
    are installed."""
    tool = shutil.which("pcl_convert_pcd_ascii_binary")
    if not tool:
        return None
    with tempfile.TemporaryDirectory() as d:
        src, dst = os.path.join(d, "in.pcd"), os.path.join(d, "out.pcd")
        with open(src, "wb") as f:
            f.write(ascii_pcd)
        subprocess.run([tool, src, dst, "2"], check=True, capture_output=True)
        with open(dst, "rb") as f:
            return f.read()


def ply(vertices, faces, form):
    order = {"binary_little_endian": "<", "binary_big_endian": ">"}.get(form)
    header = f"ply\nformat {form} 1.0\ncomment seed\nelement vertex {len(vertices)}\n"
    header += "property float x\nproperty float y\nproperty float z\n"
    if faces is not None:
        header += f"element face {len(faces)}\nproperty list uchar int vertex_indices\n"
    header += "end_header\n"
    body = io.BytesIO()
    for v in vertices:
        body.write((" ".join(f"{c:g}" for c in v) + "\n").encode() if order is None
                   else struct.pack(order + "3f", *v))
    for f in faces if faces is not None else []:
        body.write((f"{len(f)} " + " ".join(map(str, f)) + "\n").encode() if order is None
                   else struct.pack(f"{order}B{len(f)}i", len(f), *f))
    return header.encode() + body.getvalue()


def npy(array, fortran=False):
    out = io.BytesIO()
    np.save(out, np.asfortranarray(array) if fortran else array, allow_pickle=False)
    return out.getvalue()


def off_piece(path, num_faces):
    """The first faces of an OFF mesh and the vertices they use, renumbered."""
    with open(path) as f:
        tokens = [l.split() for l in f if l.strip() and not l.startswith("#")]
    counts = tokens[0][1:] if len(tokens[0]) > 1 else tokens[1]
    first = 1 if len(tokens[0]) > 1 else 2
    nv = int(counts[0])
    vertices = [list(map(float, t[:3])) for t in tokens[first:first + nv]]
    faces = [list(map(int, t[1:1 + int(t[0])])) for t in tokens[first + nv:first + nv + num_faces]]
    used = sorted({i for f in faces for i in f})
    index = {v: i for i, v in enumerate(used)}
    return [vertices[v] for v in used], [[index[i] for i in f] for f in faces]


def off(vertices, faces):
    text = f"OFF\n{len(vertices)} {len(faces)} 0\n"
    text += "".join(" ".join(f"{c:g}" for c in v) + "\n" for v in vertices)
    return (text + "".join(f"{len(f)} " + " ".join(map(str, f)) + "\n" for f in faces)).encode()


def obj(vertices, faces):
    text = "# seed\n" + "".join("v " + " ".join(f"{c:g}" for c in v) + "\n" for v in vertices)
    return (text + "".join("f " + " ".join(str(i + 1) for i in f) + "\n" for f in faces)).encode()


def seeds(data):
    fields, bun0 = pcd_points(os.path.join(data, "pcl", "bun0.pcd"), 24)
    _, bunny = pcd_points(os.path.join(data, "pcl", "bunny.pcd"), 30)
    vertices, faces = off_piece(os.path.join(data, "models", "cgal-cube-meshed.off"), 24)
    yield PCD, pcd(fields, bun0, "ascii")
    yield PCD, pcd(fields, bun0, "binary")
    yield PCD, pcd(fields, bun0, "binary_compressed")
    yield PCD, pcd(["x", "y", "z"], bunny, "binary", height=5)
    compressed = pcl_compressed(pcd(fields, bun0, "ascii"))
    if compressed:
        yield PCD, compressed
    for form in ("ascii", "binary_little_endian", "binary_big_endian"):
        yield PLY, ply(bunny, None, form)
        yield PLY, ply(np.array(vertices, np.float32), faces, form)
    yield NPY, npy(bunny)
    yield NPY, npy(bunny.astype(np.float64).reshape(5, 6, 3), fortran=True)
    yield NPY, npy((bunny * 1000).astype(">i4"))
    yield OFF, off(vertices, faces)
    yield OBJ, obj(vertices, faces)


def main():
    data = sys.argv[1] if len(sys.argv) > 1 else os.path.join(
        os.path.dirname(os.path.abspath(__file__)), "..", "..", "..", "shared", "data")
    if not os.path.isdir(os.path.join(data, "pcl")):
        sys.exit(f"make_read_corpus: no shared data in {data}")
    os.makedirs(HERE, exist_ok=True)
    for kind, body in seeds(data):
        seed = bytes([kind]) + body
        name = hashlib.sha1(seed).hexdigest()
        with open(os.path.join(HERE, name), "wb") as f:
            f.write(seed)
        print(f"{name}: {len(seed)} bytes")


if __name__ == "__main__":
    main()
