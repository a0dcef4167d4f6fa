"""The package as a user meets it: its version, its names, what help() shows, what it takes
(anything with __array__, normals) and what it refuses."""
import os
import pydoc
import re

import numpy as np
import pytest

import pcl_ncut_seg
import shapes

SOURCE = os.environ.get("PCL_NCUT_SEG_SOURCE_DIR",
                        os.path.join(os.path.dirname(__file__), "..", ".."))


@pytest.fixture(scope="module")
def points():
    return shapes.limbs(1500, seed=5)


def test_version_is_the_cmake_projects():
    with open(os.path.join(SOURCE, "CMakeLists.txt"), encoding="utf-8") as f:
        version = re.search(r"project\(\s*pcl_ncut_seg\s+VERSION\s+([0-9.]+)", f.read()).group(1)
    assert pcl_ncut_seg.__version__ == version


def test_all_names_exist_and_are_documented():
    for name in pcl_ncut_seg.__all__:
        obj = getattr(pcl_ncut_seg, name)
        if callable(obj):
            assert len((obj.__doc__ or "").strip()) > 40, name


def test_help_shows_the_docstrings_and_every_parameter():
    text = pydoc.render_doc(pcl_ncut_seg, renderer=pydoc.plaintext)
    for words in ("Open3D", "colorize(cloud, labels)", "normals: an array of the points' shape"):
        assert words in text
    seg_text = pydoc.render_doc(pcl_ncut_seg.Segmenter, renderer=pydoc.plaintext)
    for row in pcl_ncut_seg.parameter_table():
        # each parameter is an attribute whose help is the table's line
        doc = getattr(pcl_ncut_seg.Segmenter, row["name"]).__doc__
        assert doc.startswith(row["help"]) and row["range"] in doc, row["name"]
        assert f"\n |  {row['name']}\n" in seg_text, row["name"]


def test_anything_with_array_is_taken(points):
    class Wrapped:
        def __init__(self, a):
            self.a = a

        def __array__(self, dtype=None):
            return self.a if dtype is None else self.a.astype(dtype)

    expected = pcl_ncut_seg.segment(points, segments=3)
    assert np.array_equal(pcl_ncut_seg.segment(Wrapped(points), segments=3), expected)
    assert np.array_equal(pcl_ncut_seg.segment(points.tolist(), segments=3), expected)
    seg = pcl_ncut_seg.Segmenter(segments=3)
    assert np.array_equal(seg.segment(Wrapped(points)), expected)
    normals = np.full(points.shape, np.nan)
    assert np.array_equal(pcl_ncut_seg.segment(points, normals=Wrapped(normals), segments=3),
                          expected)


def test_bad_normals_raise_value_error(points):
    with pytest.raises(ValueError, match=r"normals must have the shape of the points, "
                                         r"\(1500, 3\), got \(1499, 3\)"):
        pcl_ncut_seg.segment(points, normals=points[1:])
    with pytest.raises(ValueError, match=r"normals must be an \(N, 3\) or \(H, W, 3\) array "
                                         r"of float32 or float64, got int64"):
        pcl_ncut_seg.segment(points, normals=np.ones(points.shape, np.int64))
    seg = pcl_ncut_seg.Segmenter()
    seg.segment(points)
    with pytest.raises(ValueError, match="normals without points"):
        seg.segment(normals=points)
    with pytest.raises(ValueError, match="points must be"):
        pcl_ncut_seg.segment(object())


def test_segment_colors():
    labels = np.array([0, 1, 2, 1, 9], np.int32)
    rgb = pcl_ncut_seg.segment_colors(labels)
    assert rgb.dtype == np.uint8 and rgb.shape == (5, 3)
    assert (rgb[0] == 0).all() and (rgb[1] == rgb[3]).all()
    assert len({tuple(c) for c in rgb[1:]}) == 3 and rgb[1:].max() > 200
    assert pcl_ncut_seg.segment_colors(labels.reshape(5, 1)).shape == (5, 3)
    with pytest.raises(ValueError, match=">= 0"):
        pcl_ncut_seg.segment_colors([1, -1])
    with pytest.raises(ValueError, match="integers"):
        pcl_ncut_seg.segment_colors([0.5])
