"""The tool's output for the batch front end: a binary PCD with x y z rgb label, byte for byte
as the pcl_ncut_seg tool writes it. (Files are read by the compiled module, read_file().)"""
import mmap

import numpy as np

from ._clouds import segment_colors

DEFAULT_VIEWPOINT = (0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0)  # at the origin, not turned


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
