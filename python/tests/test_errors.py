"""Bad input raises ValueError with the library's reason; nothing changes."""
import re

import numpy as np
import pytest

import pcl_ncut_seg
import shapes

RANGE = {row["name"]: row["range"] for row in pcl_ncut_seg.parameter_table()}
GOOD = shapes.limbs(500, seed=1)


@pytest.mark.parametrize("shape", [(10, 2), (10, 4), (30,), (10, 3, 1), ()])
def test_wrong_shape(shape):
    with pytest.raises(ValueError, match=re.escape(f"of shape {np.zeros(shape).shape}")):
        pcl_ncut_seg.segment(np.zeros(shape))


@pytest.mark.parametrize("dtype", [np.int64, np.int32, np.float16, np.complex128, bool, object])
def test_wrong_dtype(dtype):
    points = np.zeros((10, 3), dtype=dtype)
    with pytest.raises(ValueError, match=r"points must be an \(N, 3\) or \(H, W, 3\) array of "
                       rf"float32 or float64, got {np.dtype(dtype).name} of shape \(10, 3\)"):
        pcl_ncut_seg.segment(points)


def test_lists_of_ints_and_ragged_lists():
    with pytest.raises(ValueError, match="got int64"):
        pcl_ncut_seg.segment([[0, 0, 0], [1, 1, 1]])
    with pytest.raises(ValueError):
        pcl_ncut_seg.segment([[0.0, 0.0, 0.0], [1.0, 1.0]])


def test_no_finite_point():
    # The library's reason: its PCL_ERROR line, without the "[pcl::...]" prefix.
    for points in (np.zeros((0, 3)), np.full((20, 3), np.nan), np.full((5, 3), np.inf)):
        with pytest.raises(ValueError, match="^the input has no finite point.$"):
            pcl_ncut_seg.segment(points)


@pytest.mark.parametrize("name,value,shown", [
    ("k", 1, "1"), ("k", 2.5, "2.5"), ("k", None, "None"), ("k", "ten", "ten"),
    ("threshold", -0.1, "-0.1"), ("threshold", float("nan"), "nan"),
    ("threshold", float("inf"), "inf"), ("boundary_band", 1.5, "1.5"), ("crease_split", 0, "0"),
    ("boundary_band", True, "on"), ("centrality_samples", 0, "0"), ("threads", -1, "-1"),
    ("crossing_fraction", 2, "2"), ("segments", 0, "0"),
])
def test_value_out_of_range(name, value, shown):
    row = next(r for r in pcl_ncut_seg.parameter_table() if r["name"] == name)
    why = f"{row['name']} must be {row['range']}, got '{shown}'"
    with pytest.raises(ValueError, match=f"^{re.escape(why)}$"):
        pcl_ncut_seg.segment(GOOD, **{name: value})


def test_words():
    with pytest.raises(ValueError, match="^stopping must be one of threshold, short_cut, "
                       "count, got 'gap'$"):
        pcl_ncut_seg.segment(GOOD, stopping="gap")
    with pytest.raises(ValueError, match="^cad must be on or off, got 'yes'$"):
        pcl_ncut_seg.segment(GOOD, cad="yes")
    with pytest.raises(ValueError, match="^paper must be True or False"):
        pcl_ncut_seg.segment(GOOD, paper=1)
    with pytest.raises(ValueError, match="^exact takes True only"):
        pcl_ncut_seg.segment(GOOD, exact=False)


def test_unknown_names_suggest_close_ones():
    with pytest.raises(ValueError, match="^unknown parameter 'thresold'; did you mean "
                       "'threshold'$"):
        pcl_ncut_seg.segment(GOOD, thresold=0.1)
    with pytest.raises(ValueError, match="^unknown parameter 'qqq'$"):
        pcl_ncut_seg.Segmenter(qqq=1)
    with pytest.raises(ValueError, match="unknown parameter"):
        pcl_ncut_seg.Segmenter().get("qqq")


def test_one_name_per_parameter():
    # The spellings of older releases are unknown names, as keywords and in get().
    for old in ("crease", "min_fraction", "cen_samples", "band", "neck"):
        with pytest.raises(ValueError, match=f"^unknown parameter '{old}'"):
            pcl_ncut_seg.segment(GOOD, **{old: 0.5})
        with pytest.raises(ValueError, match=f"^unknown parameter '{old}'"):
            pcl_ncut_seg.Segmenter().get(old)
    assert all("aliases" not in row for row in pcl_ncut_seg.parameter_table())


def test_a_failed_call_changes_nothing():
    seg = pcl_ncut_seg.Segmenter(segments=3)
    labels = seg.segment(GOOD)
    params = seg.parameters
    with pytest.raises(ValueError):
        seg.segment(GOOD[:100], k=1)  # a bad parameter: neither points nor parameters taken
    with pytest.raises(ValueError):
        seg.segment(np.zeros((4, 2)), k=12)  # bad points: the same
    assert seg.parameters == params and seg.num_points == len(GOOD)
    assert np.array_equal(seg.get_labels(), labels)
    assert np.array_equal(seg.segment(), labels) and seg.analysis_count == 1


def test_results_before_a_result():
    seg = pcl_ncut_seg.Segmenter()
    with pytest.raises(ValueError, match="no points"):
        seg.segment()
    for get in (seg.get_labels, seg.get_centrality, seg.get_hierarchy, lambda: seg.phase_times):
        with pytest.raises(RuntimeError, match="no result"):
            get()
    with pytest.raises(ValueError, match="no finite point"):
        seg.segment(np.full((3, 3), np.nan))
    with pytest.raises(RuntimeError, match="no result"):
        seg.get_labels()


@pytest.mark.parametrize("origin, reason", [
    ((0.0, 1.0), "3 numbers"),
    ([[0.0, 0.0, 1.0]], "3 numbers"),
    (("a", "b", "c"), "3 numbers"),
    ((0.0, float("nan"), 1.0), "finite"),
    ((0.0, 0.0, float("inf")), "finite"),
])
def test_bad_sensor_origin(origin, reason):
    seg = pcl_ncut_seg.Segmenter(segments=3)
    first = seg.segment(GOOD)
    with pytest.raises(ValueError, match=reason):
        seg.segment(GOOD, sensor_origin=origin)
    assert np.array_equal(seg.get_labels(), first)  # the failed call changed nothing
