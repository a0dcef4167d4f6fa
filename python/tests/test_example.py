"""examples/open3d_example.py: on the bundled model, its labels and colours are the module's;
on the tool's output, Open3D reads the tool's label field and the script's labels and colours
are the tool's. Needs Open3D (python3-open3d); the second also the tool
(PCL_NCUT_SEG_TOOL)."""
import os
import subprocess
import sys

import pytest

import numpy as np

import pcd
import pcl_ncut_seg

TOOL = os.environ.get("PCL_NCUT_SEG_TOOL")
HERE = os.path.dirname(os.path.abspath(__file__))
SOURCE = os.environ.get("PCL_NCUT_SEG_SOURCE_DIR", os.path.join(HERE, "..", ".."))
EXAMPLE = os.path.join(HERE, "..", "examples", "open3d_example.py")


def test_open3d_example_writes_the_modules_labels_and_colours(tmp_path):
    o3d = pytest.importorskip("open3d",
                              reason="Open3D is not importable (apt-get install python3-open3d)")
    source = os.path.join(SOURCE, "data", "armadillo.pcd")
    target = tmp_path / "out.pcd"
    run = subprocess.run([sys.executable, EXAMPLE, source, str(target), "segments=6", "k=12"],
                         check=True, capture_output=True, text=True, env=os.environ)
    expected = pcl_ncut_seg.segment(o3d.t.io.read_point_cloud(source), segments=6, k=12)
    assert f"{len(expected)} points" in run.stdout and "6 segments" in run.stdout
    assert f"wrote {target}" in run.stdout
    written = pcd.read_fields(target)
    assert np.array_equal(written["label"].reshape(-1), expected)
    rgb = written["rgb"].view("u4").reshape(-1)
    colours = np.stack([(rgb >> 16) & 255, (rgb >> 8) & 255, rgb & 255], axis=1)
    assert np.array_equal(colours, pcl_ncut_seg.segment_colors(expected))


def test_open3d_example_says_why_it_cannot_segment(tmp_path):
    pytest.importorskip("open3d", reason="Open3D is not importable (apt-get install python3-open3d)")
    run = subprocess.run([sys.executable, EXAMPLE, str(tmp_path / "missing.pcd"), "k=1"],
                         capture_output=True, text=True, env=os.environ)
    assert run.returncode != 0 and "missing.pcd" in run.stderr and "Traceback" not in run.stderr


@pytest.mark.skipif(not TOOL, reason="PCL_NCUT_SEG_TOOL is not set (no tools built)")
def test_open3d_example_agrees_with_the_tool(tmp_path):
    pytest.importorskip("open3d", reason="Open3D is not installed (apt-get install python3-open3d)")
    by_tool = tmp_path / "tool.pcd"
    subprocess.run([TOOL, os.path.join(SOURCE, "data", "armadillo.pcd"), str(by_tool),
                    "-binary", "-quiet", "-segments", "7"], check=True, stdout=subprocess.DEVNULL)
    by_script = tmp_path / "script.pcd"
    run = subprocess.run([sys.executable, EXAMPLE, str(by_tool), str(by_script), "segments=7"],
                         check=True, capture_output=True, text=True, env=os.environ)
    assert "7 segments" in run.stdout
    assert "8000 of 8000 points have the same label" in run.stdout
    tool, script = pcd.read_fields(by_tool), pcd.read_fields(by_script)
    assert (tool["label"] == script["label"]).all()
    assert (tool["rgb"].view("u4") & 0xFFFFFF == script["rgb"].view("u4") & 0xFFFFFF).all()
