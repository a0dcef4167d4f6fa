"""examples/open3d_example.py on the tool's output: Open3D reads the tool's label field, the
script's labels and colours are the tool's. Runs when Open3D (python3-open3d) is installed
and PCL_NCUT_SEG_TOOL names the tool."""
import os
import subprocess
import sys

import pytest

import pcd

TOOL = os.environ.get("PCL_NCUT_SEG_TOOL")
HERE = os.path.dirname(os.path.abspath(__file__))
SOURCE = os.environ.get("PCL_NCUT_SEG_SOURCE_DIR", os.path.join(HERE, "..", ".."))
EXAMPLE = os.path.join(HERE, "..", "examples", "open3d_example.py")


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
