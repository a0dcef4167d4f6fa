"""pcl_ncut_seg.segment(): labels, dtypes, NaN rows, parameters by name."""
import numpy as np
import pytest

import pcl_ncut_seg
import shapes


@pytest.fixture(scope="module")
def points():
    return shapes.limbs(3000, seed=1)


@pytest.fixture(scope="module")
def labels(points):
    return pcl_ncut_seg.segment(points)


def test_labels_are_int32_one_per_point_numbered_by_first_point(points, labels):
    assert labels.dtype == np.int32 and labels.shape == (len(points),)
    t = labels.max()
    assert labels.min() == 1  # every finite point is in a segment
    assert sorted(set(labels.tolist())) == list(range(1, t + 1))
    _, first = np.unique(labels, return_index=True)
    assert np.all(np.diff(first) > 0)  # segment s + 1 starts after segment s


def test_the_ball_and_its_four_limbs(points):
    # Asked for five segments, it finds the parts: each limb's outer half (beyond |x| or
    # |y| = 1.3) in a segment of its own.
    five = pcl_ncut_seg.segment(points, segments=5)
    assert five.max() == 5
    tips = [points[:, 0] > 1.3, points[:, 0] < -1.3, points[:, 1] > 1.3, points[:, 1] < -1.3]
    tip_labels = [np.bincount(five[t]).argmax() for t in tips]
    assert len(set(tip_labels)) == 4
    for t, s in zip(tips, tip_labels):
        assert np.mean(five[t] == s) > 0.95


def test_float32_and_float64_give_the_same_labels(points, labels):
    as32 = points.astype(np.float32)
    assert np.array_equal(pcl_ncut_seg.segment(as32), pcl_ncut_seg.segment(as32.astype(np.float64)))
    # float64 input is rounded to float32 as PCL stores it.
    assert np.array_equal(pcl_ncut_seg.segment(as32), labels)


def test_any_layout_and_array_like(points, labels):
    fortran = np.asfortranarray(points)
    strided = np.repeat(points, 2, axis=0)[::2]
    big_endian = points.astype(">f8")
    for same in (fortran, strided, big_endian, points.tolist()):
        assert np.array_equal(pcl_ncut_seg.segment(same), labels)


def test_nan_rows_get_0_and_leave_the_others_as_without_them(points):
    with_nan, bad = shapes.with_nan_rows(points)
    got = pcl_ncut_seg.segment(with_nan)
    assert np.all(got[bad] == 0)
    assert np.all(got[~bad] > 0)
    assert np.array_equal(got[~bad], pcl_ncut_seg.segment(with_nan[~bad]))


def test_deterministic_and_independent_of_threads(points, labels):
    assert np.array_equal(pcl_ncut_seg.segment(points), labels)
    assert np.array_equal(pcl_ncut_seg.segment(points, threads=1), labels)


def test_parameters_by_name(points):
    three = pcl_ncut_seg.segment(points, segments=3)
    assert three.max() == 3
    # Attributes set one by one are the keywords.
    a = pcl_ncut_seg.segment(points, segments=4, crease_split=0.5, boundary_band=0.1)
    seg = pcl_ncut_seg.Segmenter()
    seg.segments, seg.crease_split, seg.boundary_band = 4, 0.5, 0.1
    assert np.array_equal(seg.segment(points), a)
    # None, False and the off word are the same.
    c = pcl_ncut_seg.segment(points, boundary_band=None, normalize_width=False)
    d = pcl_ncut_seg.segment(points, boundary_band="off", normalize_width="off")
    assert np.array_equal(c, d)
    # Strings as the tool's flags take them, numpy scalars as Python numbers.
    e = pcl_ncut_seg.segment(points, k="12", threshold="0.2", segments=np.int64(3))
    f = pcl_ncut_seg.segment(points, k=np.int32(12), threshold=np.float64(0.2), segments=3)
    assert np.array_equal(e, f)


def test_paper_true_is_the_papers_settings(points):
    paper = pcl_ncut_seg.default_parameters(paper=True)
    assert paper["centrality"] == "exact" and paper["denoise"] is None
    assert pcl_ncut_seg.Segmenter(paper=True).parameters == paper
    by_paper = pcl_ncut_seg.segment(points, paper=True)
    # The same values one by one.
    assert np.array_equal(pcl_ncut_seg.segment(points, **paper), by_paper)
    assert not np.array_equal(by_paper, pcl_ncut_seg.segment(points))
    # Other keywords apply on top of the preset, in any position.
    assert np.array_equal(pcl_ncut_seg.segment(points, threshold=0.05, paper=True),
                          pcl_ncut_seg.segment(points, **dict(paper, threshold=0.05)))


def test_shorthand_exact(points):
    assert np.array_equal(pcl_ncut_seg.segment(points, exact=True),
                          pcl_ncut_seg.segment(points, centrality="exact"))


def test_one_point_and_fewer_points_than_k():
    with pytest.warns(RuntimeWarning, match="using 0 neighbours"):
        assert pcl_ncut_seg.segment(np.zeros((1, 3))).tolist() == [1]
    few = np.array([[0, 0, 0], [1, 0, 0], [0, 1, 0], [0, 0, 1]], np.float32)
    with pytest.warns(RuntimeWarning, match="neighbours instead of 10"):
        got = pcl_ncut_seg.segment(few)
    assert got.shape == (4,) and got.min() >= 1
