"""The module's labels against the pcl_ncut_seg tool's on the same points: the same C++ class
behind both, reached through a PCD file on one side and a numpy array on the other.

Runs when PCL_NCUT_SEG_TOOL names the tool (CTest sets it when the tools are built)."""
import os
import subprocess

import numpy as np
import pytest

import pcd
import pcl_ncut_seg
import shapes

TOOL = os.environ.get("PCL_NCUT_SEG_TOOL")
SOURCE = os.environ.get("PCL_NCUT_SEG_SOURCE_DIR",
                        os.path.join(os.path.dirname(__file__), "..", ".."))
pytestmark = pytest.mark.skipif(not TOOL, reason="PCL_NCUT_SEG_TOOL is not set (no tools built)")


def tool_labels(tmp_path, input_path, flags):
    out = tmp_path / "out.pcd"
    subprocess.run([TOOL, str(input_path), str(out), "-binary", "-quiet", *flags], check=True,
                   stdout=subprocess.DEVNULL)
    return pcd.read_fields(out)


# (keywords of the module, flags of the tool)
CASES = [
    ({}, []),
    ({"k": 12, "segments": 3}, ["-k", "12", "-segments", "3"]),
    ({"paper": True, "threshold": 0.05}, ["-paper", "-threshold", "0.05"]),
    ({"crease_split": 0.5, "neck_bound": 0.3}, ["-crease_split", "0.5", "-neck_bound", "0.3"]),
]


@pytest.fixture(scope="module")
def cloud(tmp_path_factory):
    """The limbs with NaN rows, as float32 (what the PCD holds) and written to a PCD."""
    points, bad = shapes.with_nan_rows(shapes.limbs(2500, seed=2))
    points = points.astype(np.float32)
    path = tmp_path_factory.mktemp("tool") / "limbs.pcd"
    pcd.write_xyz(path, points)
    return points, bad, path


@pytest.mark.parametrize("keywords,flags", CASES, ids=["defaults", "k12_segments3", "paper",
                                                      "crease_split"])
def test_same_labels_as_the_tool(tmp_path, cloud, keywords, flags):
    points, bad, path = cloud
    expected = tool_labels(tmp_path, path, flags)["label"].astype(np.int32)
    assert expected.shape == (len(points),)
    assert np.all(expected[bad] == 0) and expected.max() >= 2
    assert np.array_equal(pcl_ncut_seg.segment(points, **keywords), expected)
    assert np.array_equal(pcl_ncut_seg.segment(points.astype(np.float64), **keywords), expected)
    seg = pcl_ncut_seg.Segmenter(**keywords)
    assert np.array_equal(seg.segment(points), expected)


def test_same_labels_as_the_tool_on_the_bundled_hand(tmp_path):
    # The tool reads the model (binary_compressed PCD) and writes its points with the labels.
    got = tool_labels(tmp_path, os.path.join(SOURCE, "data", "hand.pcd"), ["-segments", "6"])
    points = np.stack([got["x"], got["y"], got["z"]], axis=1)
    labels = pcl_ncut_seg.segment(points, segments=6)
    assert labels.max() == 6
    assert np.array_equal(labels, got["label"].astype(np.int32))
