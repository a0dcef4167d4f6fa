"""The intermediate results as numpy arrays: shapes, types and how they fit together."""
import numpy as np
import pytest

import pcl_ncut_seg
import shapes


@pytest.fixture(scope="module")
def run():
    points, bad = shapes.with_nan_rows(shapes.limbs(2500, seed=4))
    # No boundary refinement: every point then has its supernode's segment.
    seg = pcl_ncut_seg.Segmenter(segments=5, boundary_band=None)
    labels = seg.segment(points)
    return seg, points, bad, labels


def test_counts(run):
    seg, points, bad, labels = run
    assert seg.num_points == len(points)
    assert seg.num_segments == labels.max() == 5
    assert seg.num_supernodes >= seg.num_refined_supernodes >= seg.num_segments
    assert np.array_equal(seg.get_labels(), labels)


def test_centrality(run):
    seg, points, bad, _ = run
    f = seg.get_centrality()
    assert f.dtype == np.float32 and f.shape == (len(points),)
    assert np.all(np.isnan(f[bad])) and np.all(np.isfinite(f[~bad])) and np.all(f[~bad] > 0)
    # The limbs' tips are the most central-far points: f grows away from the ball.
    r = np.linalg.norm(points[~bad], axis=1)
    assert np.corrcoef(r, f[~bad])[0, 1] > 0.8


def test_supernodes_maxima_and_saddles(run):
    seg, points, bad, _ = run
    for refined, count in ((False, seg.num_supernodes), (True, seg.num_refined_supernodes)):
        s = seg.get_supernode_labels(refined)
        assert s.dtype == np.int32 and s.shape == (len(points),)
        assert np.all(s[bad] == -1)
        assert set(s[~bad].tolist()) == set(range(count))
    assert np.array_equal(seg.get_supernode_labels(), seg.get_supernode_labels(True))
    maxima, saddles = seg.get_local_maxima(), seg.get_saddles()
    assert maxima.dtype == saddles.dtype == np.int64
    # Each supernode starts at a local maximum of f or at a saddle (Sec. 4.2).
    raw = seg.get_supernode_labels(False)
    origins = np.concatenate([maxima, saddles])
    assert sorted(raw[origins].tolist()) == list(range(seg.num_supernodes))
    f = seg.get_centrality()
    assert np.all(~bad[origins])
    assert all(f[raw == raw[i]].max() == f[i] for i in maxima)  # the top of its supernode


def test_hierarchy(run):
    seg, _, _, _ = run
    h = seg.get_hierarchy()
    l, t = seg.num_refined_supernodes, seg.num_segments
    m = len(h["parent"])
    assert m == 2 * t - 1  # a binary tree with t leaves
    for key in ("parent", "left", "right", "segment"):
        assert h[key].dtype == np.int32 and h[key].shape == (m,)
    assert h["ncut"].dtype == np.float64 and h["vertices"].shape == (m, 2 * l)
    assert h["parent"][0] == -1 and np.all(h["vertices"][0])
    inner = h["left"] >= 0
    assert np.all(h["right"][inner] >= 0) and np.all(h["right"][~inner] == -1)
    for node in np.flatnonzero(inner):
        left, right = h["left"][node], h["right"][node]
        assert h["parent"][left] == h["parent"][right] == node
        # The children split the node's vertices, at the NCut the node records.
        assert np.array_equal(h["vertices"][left] | h["vertices"][right], h["vertices"][node])
        assert not np.any(h["vertices"][left] & h["vertices"][right])
        assert 0 <= h["ncut"][node] < 2
    assert sorted(h["segment"][~inner].tolist()) == list(range(1, t + 1))
    assert np.all(h["segment"][inner] == 0)


def test_supernode_segments_give_the_labels_without_boundary_refinement(run):
    seg, _, bad, labels = run
    per_supernode = seg.get_supernode_segments()
    assert per_supernode.dtype == np.int32 and per_supernode.shape == (seg.num_refined_supernodes,)
    s = seg.get_supernode_labels()
    assert np.array_equal(per_supernode[s[~bad]], labels[~bad])
    # The hierarchy's leaves hold the member vertices (columns l + i) of their supernodes.
    h, l = seg.get_hierarchy(), seg.num_refined_supernodes
    for node in np.flatnonzero(h["left"] < 0):
        members = np.flatnonzero(h["vertices"][node][l:])
        assert np.all(per_supernode[members] == h["segment"][node])


def test_supernode_graph(run):
    seg, _, _, _ = run
    g = seg.get_supernode_graph()
    l = seg.num_refined_supernodes
    assert g["num_vertices"] == 2 * l
    e = len(g["weights"])
    assert g["edges"].shape == (e, 2) and g["edges"].dtype == np.int64 and e >= l
    assert g["edges"].min() >= 0 and g["edges"].max() < 2 * l
    assert np.all(g["weights"] > 0)
