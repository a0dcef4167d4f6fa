"""Segmenter: every parameter by its name, re-cuts that keep the expensive stage."""
import numpy as np
import pytest

import pcl_ncut_seg
import shapes

TABLE = pcl_ncut_seg.parameter_table()

# Per parameter, a valid value other than its default (every row must have one).
OTHER = {
    "k": 11, "bridge_gap": None, "denoise": None, "irregular_sampling": None, "max_points": 1000, "single_view": False, "centrality_samples": 30, "centrality": "exact",
    "starts": 2, "crossing_fraction": 0.25, "area_fraction": 0.02,
    "height_fraction": 0.02, "crease_split": None, "cad": True,
    "ridge_angle": 6.0,
    "beta": 3.0, "alpha1": 1.5, "alpha2": 0.4, "normalize_width": False,
    "adjacency": "trees", "concavity": 2.0, "thickness": False, "flat_elongation": 0.2,
    "stopping": "threshold", "threshold": 0.2, "segments": 3,
    "max_segments": 4,
    "neck_bound": 0.3, "boundary_band": 0.1, "rim_merge": None,
    "threads": 1,
}


@pytest.fixture(scope="module")
def points():
    return shapes.limbs(2000, seed=5)


def test_every_parameter_is_an_attribute_of_its_name():
    seg = pcl_ncut_seg.Segmenter()
    names = [row["name"] for row in TABLE]
    assert sorted(seg.parameters) == sorted(names)
    assert set(OTHER) == set(names)
    for row in TABLE:
        name = row["name"]
        assert getattr(seg, name) == row["default"] == seg.get(name)
        assert row["help"] in getattr(pcl_ncut_seg.Segmenter, name).__doc__
    # Python types: None for off/auto, bool for switches, int, float, str for choices.
    assert seg.k == 10 and isinstance(seg.k, int)
    assert seg.threshold == 0.1 and isinstance(seg.threshold, float)
    assert seg.crossing_fraction == 0.3  # a float field, read back as the same decimal
    assert seg.centrality_samples is None
    assert seg.cad is False and seg.centrality == "fast"


def test_setting_each_parameter_by_attribute_and_keyword():
    for row in TABLE:
        name, value = row["name"], OTHER[row["name"]]
        seg = pcl_ncut_seg.Segmenter()
        setattr(seg, name, value)
        assert getattr(seg, name) == value, name
        assert pcl_ncut_seg.Segmenter(**{name: value}).get(name) == value
        if row["off"]:
            seg.set(**{name: None})
            assert getattr(seg, name) is None
            seg.set(**{name: row["off"]})
            assert getattr(seg, name) is None
    assert pcl_ncut_seg.Segmenter(segments=4).stopping == "count"  # as the tool's -segments


def test_parameters_given_back_as_keywords_set_the_same():
    for keywords in ({}, {"paper": True}, {"segments": 4}, {"stopping": "threshold"},
                     {"segments": 4, "stopping": "threshold"},
                     {"paper": True, "segments": 3, "threshold": 0.3}, dict(OTHER, cad=False)):
        seg = pcl_ncut_seg.Segmenter(**keywords)
        assert pcl_ncut_seg.Segmenter(**seg.parameters).parameters == seg.parameters
        assert eval(repr(seg), {"pcl_ncut_seg": pcl_ncut_seg}).parameters == seg.parameters
    for paper in (False, True):
        d = pcl_ncut_seg.default_parameters(paper=paper)
        assert pcl_ncut_seg.Segmenter(**d).parameters == d
        assert pcl_ncut_seg.Segmenter(paper=paper).parameters == d


def test_set_is_all_or_nothing_and_repr_shows_changes():
    seg = pcl_ncut_seg.Segmenter(k=12, threshold=0.2)
    before = seg.parameters
    with pytest.raises(ValueError):
        seg.set(threshold=0.3, k=1)
    with pytest.raises(ValueError):
        seg.k = 0
    assert seg.parameters == before
    assert repr(seg) == "pcl_ncut_seg.Segmenter(k=12, threshold=0.2)"
    seg.set(paper=False)
    assert seg.parameters == pcl_ncut_seg.default_parameters()
    seg = pcl_ncut_seg.Segmenter(threads=1)
    seg.set(paper=True)
    assert seg.threads == 1  # the presets leave the threads alone
    assert seg.centrality == "exact" and seg.stopping == "threshold"


def test_a_recut_keeps_the_expensive_stage(points):
    seg = pcl_ncut_seg.Segmenter()
    first = seg.segment(points)
    assert seg.analysis_count == 1
    assert seg.phase_times["knn"] > 0 and seg.phase_times["centrality"] > 0
    analysis = seg.get_centrality()
    # Every cut stage at once: similarity, stopping, boundary.
    cut = dict(beta=3.0, alpha1=1.5, threshold=0.05, segments=4, boundary_band=0.1)
    recut = seg.segment(**cut)
    assert seg.analysis_count == 1
    times = seg.phase_times
    assert times["knn"] == times["centrality"] == times["supernodes"] == times["refinement"] == 0
    assert times["hierarchy"] > 0
    # The intermediate results are those of the start whose segments were kept (several
    # starts, core/centrality/starts.h): as from scratch with the same parameters.
    fresh = pcl_ncut_seg.Segmenter()
    fresh.segment(points, **cut)
    assert np.array_equal(seg.get_centrality(), fresh.get_centrality())
    assert not np.array_equal(analysis, np.zeros_like(analysis))
    assert recut.max() == 4 and not np.array_equal(recut, first)
    # The same labels as from scratch.
    assert np.array_equal(recut, pcl_ncut_seg.segment(points, **cut))
    # An analysis parameter: the results are gone until the next segment(), which recomputes.
    seg.k = 12
    with pytest.raises(RuntimeError, match="call segment"):
        seg.get_labels()
    assert np.array_equal(seg.segment(), pcl_ncut_seg.segment(points, k=12, **cut))
    assert seg.analysis_count == 2 and seg.phase_times["knn"] > 0
    # New points: a new analysis.
    seg.segment(points[:1500])
    assert seg.analysis_count == 3 and seg.num_points == 1500


def test_which_parameters_recompute_the_analysis(points):
    # A change recomputes the expensive stage exactly when the table puts the parameter in an
    # analysis stage.
    small = points[:800]
    for row in TABLE:
        seg = pcl_ncut_seg.Segmenter(segments=3)
        seg.segment(small)
        seg.set(**{row["name"]: OTHER[row["name"]]})
        seg.segment()
        assert seg.analysis_count == (2 if row["analysis"] else 1), row["name"]


def test_the_noise_test_is_reported(points):
    clean = pcl_ncut_seg.Segmenter()
    clean.segment(points)
    assert clean.noise_test["residual_growth"] > 2.0
    assert clean.noise_test["projected"] is False
    # Noise of half a point spacing per coordinate (spacing from the nearest neighbours).
    rng = np.random.default_rng(5)
    sample = points[rng.choice(len(points), 300, replace=False)]
    d2 = ((sample[:, None, :] - points[None, :, :]) ** 2).sum(-1)
    d2[d2 == 0] = np.inf
    spacing = float(np.sqrt(d2.min(1)).mean())
    noisy = pcl_ncut_seg.Segmenter()
    noisy.segment(points + rng.normal(0.0, 0.5 * spacing, points.shape))
    assert noisy.noise_test["residual_growth"] < 2.0
    assert noisy.noise_test["projected"] is True
    off = pcl_ncut_seg.Segmenter(denoise=None, irregular_sampling=None)
    off.segment(points)
    assert off.noise_test == {"residual_growth": 0.0, "projected": False,
                              "sampling_irregularity": 0.0, "irregular": False}
    # The points are drawn at random: irregular, so the centrality was averaged once (the
    # test is on by default, at 0.3); with a bound above their irregularity, they count as even.
    assert clean.noise_test["sampling_irregularity"] > 0.3
    assert clean.noise_test["irregular"] is True
    lenient = pcl_ncut_seg.Segmenter(irregular_sampling=0.6)
    lenient.segment(points)
    assert lenient.noise_test["sampling_irregularity"] == clean.noise_test["sampling_irregularity"]
    assert lenient.noise_test["irregular"] is False


def disc_view(noise=0.0005, seed=7):
    """What a depth camera 1 m in front of a tilted flat disc sees: (120, 160, 3), NaN off it."""
    rows, cols = np.mgrid[0:120, 0:160]
    u, v = (cols - 80 + 0.5) / 150.0, (rows - 60 + 0.5) / 150.0
    z = 1.0 / (1.0 - 0.3 * v)  # the plane z = 1 + 0.3 y along the ray (u, v, 1)
    on = np.hypot(u * z, v * z) <= 0.25
    z = z + np.random.default_rng(seed).normal(0.0, noise, z.shape)
    image = np.stack([u * z, v * z, z], axis=-1).astype(np.float32)
    image[~on] = np.nan
    return image


def test_an_image_of_points_is_an_organized_view():
    image = disc_view()
    seg = pcl_ncut_seg.Segmenter(threads=2)
    labels = seg.segment(image)
    assert labels.shape == image.shape[:2]
    assert (labels[np.isnan(image[..., 0])] == 0).all()
    assert (labels[~np.isnan(image[..., 0])] > 0).all()
    merged = labels.max()
    # On the image it joins the pieces the view's rim cut the flat disc into.
    unmerged = pcl_ncut_seg.Segmenter(threads=2, rim_merge=None).segment(image)
    assert unmerged.max() > 1 and merged == 1
    # The same points as a list are one view from the sensor origin (0, 0, 0): merged too.
    points = image.reshape(-1, 3)
    listed = pcl_ncut_seg.Segmenter(threads=2).segment(points)
    unmerged_list = pcl_ncut_seg.Segmenter(threads=2, rim_merge=None).segment(points)
    assert unmerged_list.max() > 1 and listed.max() == 1
    # A closed surface in front of the origin is no view from it (its back is seen through
    # its front): nothing merges.
    i = np.arange(3000) + 0.5
    z = 1.0 - 2.0 * i / 3000
    a = np.pi * (3.0 - np.sqrt(5.0)) * i
    r = np.sqrt(1.0 - z * z)
    ball = (0.2 * np.stack([r * np.cos(a), r * np.sin(a), z], 1) + [0.0, 0.0, 1.0]).astype(np.float32)
    assert np.array_equal(pcl_ncut_seg.Segmenter(threads=2).segment(ball),
                          pcl_ncut_seg.Segmenter(threads=2, rim_merge=None).segment(ball))


def test_a_badly_shaped_image_is_refused():
    with pytest.raises(ValueError, match=r"\(H, W, 3\)"):
        pcl_ncut_seg.segment(np.zeros((4, 5, 2), np.float32))


def test_the_view_test_is_reported():
    # The near side of a ball as a camera 1 unit in front of its centre sees it (one point per
    # ray of a grid), handed over as numpy points with no sensor position.
    u, v = np.meshgrid(np.linspace(-0.35, 0.35, 90), np.linspace(-0.35, 0.35, 90))
    rays = np.stack([u.ravel(), v.ravel(), np.ones(u.size)], axis=1)
    rays /= np.linalg.norm(rays, axis=1, keepdims=True)
    b = rays[:, 2]  # the ray's component towards the centre (0, 0, 1)
    disc = b * b - 1.0 + 0.3**2
    hit = disc > 0
    t = b[hit] - np.sqrt(disc[hit])
    cap = rays[hit] * t[:, None]
    cap -= cap.mean(axis=0)  # in its own frame: the origin says nothing of the camera
    seg = pcl_ncut_seg.Segmenter()
    seg.segment(cap)
    view = seg.view_test
    assert view["view"] is True and view["origin_estimated"] is True
    assert view["rim_points"] > 0
    # The sensor was found in front of the cap, towards the camera (-z from its points).
    assert view["origin"][2] < 0
    # Given where the camera was (the cap's frame moved it to minus the mean), it is taken.
    camera = -(rays[hit] * t[:, None]).mean(axis=0)
    seg.segment(cap, sensor_origin=camera)
    given = seg.view_test
    assert given["view"] is True and given["origin_estimated"] is False
    assert np.allclose(given["origin"], camera - cap.mean(axis=0), atol=1e-4)
    # Points of the last call: no sensor_origin without them.
    with pytest.raises(ValueError, match="sensor_origin without points"):
        seg.segment(sensor_origin=camera)
    # A closed surface (a sphere on a Fibonacci lattice) is no view.
    i = np.arange(4000) + 0.5
    z = 1 - 2 * i / 4000
    phi = np.pi * (1 + 5**0.5) * i
    r = np.sqrt(1 - z * z)
    ball = pcl_ncut_seg.Segmenter()
    ball.segment(np.stack([r * np.cos(phi), r * np.sin(phi), z], axis=1))
    assert ball.view_test["view"] is False
