#!/usr/bin/env python3
"""Segment a point cloud read with Open3D's tensor API (its points, and its normals when it has
some) and write it back with a `label` field and a colour per segment.

    python3 open3d_example.py INPUT [OUTPUT] [name=value ...] [--show]

INPUT is anything o3d.t.io.read_point_cloud reads (.pcd, .ply, ...); OUTPUT defaults to
<input name>_py_segments.pcd. name=value pairs are parameters of pcl_ncut_seg by the tool's
flag names (segments=6, k=12, paper=True, ...). If INPUT already has a `label` field (the
pcl_ncut_seg tool's output, say), the script also says how many points got the same label.
"""
import os
import sys

import numpy as np
import open3d as o3d

import pcl_ncut_seg


def parse_parameters(pairs):
    """name=value strings as keywords: the module reads the text as the tool's flags do."""
    params = {}
    for pair in pairs:
        name, sep, value = pair.partition("=")
        if not sep:
            sys.exit(f"expected name=value, got {pair!r}")
        params[name] = {"True": True, "False": False, "None": None}.get(value, value)
    return params


def main(argv):
    show = "--show" in argv
    args = [a for a in argv if a != "--show"]
    files = [a for a in args if "=" not in a]
    if not files or len(files) > 2:
        sys.exit(__doc__)
    source = files[0]
    target = files[1] if len(files) > 1 else (
        os.path.splitext(os.path.basename(source))[0] + "_py_segments.pcd")

    cloud = o3d.t.io.read_point_cloud(source)
    try:
        seg = pcl_ncut_seg.Segmenter(**parse_parameters([a for a in args if "=" in a]))
        labels = seg.segment(cloud)  # its positions, and its normals when it has some
    except ValueError as error:
        sys.exit(f"{source}: {error}")

    t = seg.num_segments
    print(f"{source}: {seg.num_points} points, {seg.num_supernodes} supernodes, "
          f"{seg.num_refined_supernodes} after refinement, {t} segments "
          f"in {seg.phase_times['total']:.3f} s")
    sizes = np.bincount(labels, minlength=t + 1)
    print("points per segment:", " ".join(f"{s}:{sizes[s]}" for s in range(1, t + 1)))
    if "label" in cloud.point:
        before = cloud.point["label"].numpy().reshape(-1).astype(np.int64)
        same = int(np.sum(before == labels))
        print(f"the input's label field: {same} of {len(labels)} points have the same label")

    cloud.point["label"] = o3d.core.Tensor(labels.astype(np.uint32).reshape(-1, 1))
    # uint8 colours, as the library's getColoredCloud() (pcl_ncut_seg.colorize(cloud, labels)
    # would give float ones)
    cloud.point.colors = o3d.core.Tensor(pcl_ncut_seg.segment_colors(labels))
    if not o3d.t.io.write_point_cloud(target, cloud):
        sys.exit(f"could not write {target}")
    print(f"wrote {target} (label field and a colour per segment)")
    if show:
        legacy = pcl_ncut_seg.colorize(cloud.to_legacy(), labels)
        o3d.visualization.draw_geometries([legacy], window_name=target)


if __name__ == "__main__":
    main(sys.argv[1:])
