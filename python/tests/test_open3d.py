"""Open3D clouds in (legacy and tensor, with their normals), colours out. Skipped, saying why,
only when open3d cannot be imported (apt-get install python3-open3d)."""
import numpy as np
import pytest

import pcl_ncut_seg
import shapes

o3d = pytest.importorskip(
    "open3d", reason="Open3D is not importable (apt-get install python3-open3d)")


@pytest.fixture(scope="module")
def points():
    return shapes.limbs(2000, seed=3)


@pytest.fixture(scope="module")
def wrong_normals(points):
    """Unit normals pointing anywhere: CAD mode reads them (so its segments change)."""
    n = np.random.default_rng(4).normal(size=points.shape)
    return n / np.linalg.norm(n, axis=1)[:, None]


def legacy(points, normals=None):
    cloud = o3d.geometry.PointCloud(o3d.utility.Vector3dVector(points))
    if normals is not None:
        cloud.normals = o3d.utility.Vector3dVector(normals)
    return cloud


def tensor(points, normals=None, dtype=np.float32):
    cloud = o3d.t.geometry.PointCloud(o3d.core.Tensor(points.astype(dtype)))
    if normals is not None:
        cloud.point.normals = o3d.core.Tensor(normals.astype(dtype))
    return cloud


def test_legacy_and_tensor_clouds_give_the_labels_of_their_points(points):
    expected = pcl_ncut_seg.segment(points, segments=5)
    assert expected.max() == 5
    assert np.array_equal(pcl_ncut_seg.segment(legacy(points), segments=5), expected)
    # float32 positions: the labels of the float32 array (the module reads floats as float)
    assert np.array_equal(pcl_ncut_seg.segment(tensor(points), segments=5), expected)
    assert np.array_equal(pcl_ncut_seg.segment(tensor(points, dtype=np.float64), segments=5),
                          expected)
    seg = pcl_ncut_seg.Segmenter(segments=5)
    assert np.array_equal(seg.segment(legacy(points)), expected)
    assert np.array_equal(seg.segment(tensor(points)), expected)
    assert seg.num_points == len(points)


def test_the_clouds_normals_are_read_by_cad_mode(points, wrong_normals):
    estimated = pcl_ncut_seg.segment(points, cad=True)
    given = pcl_ncut_seg.segment(points, normals=wrong_normals, cad=True)
    assert not np.array_equal(given, estimated)  # the normals change CAD mode's result
    for cloud in (legacy(points, wrong_normals), tensor(points, wrong_normals)):
        assert np.array_equal(pcl_ncut_seg.segment(cloud, cad=True), given)
        assert np.array_equal(pcl_ncut_seg.Segmenter(cad=True).segment(cloud), given)
        # normals given beside the cloud take the place of its own
        assert np.array_equal(pcl_ncut_seg.segment(cloud, normals=np.full(points.shape, np.nan),
                                                   cad=True), estimated)


def test_as_arrays(points, wrong_normals):
    p, n = pcl_ncut_seg.as_arrays(legacy(points))
    assert np.array_equal(p, points) and n is None
    p, n = pcl_ncut_seg.as_arrays(tensor(points, wrong_normals))
    assert p.dtype == np.float32 and np.allclose(p, points) and np.allclose(n, wrong_normals)
    with pytest.raises(ValueError, match="no positions"):
        pcl_ncut_seg.as_arrays(o3d.t.geometry.PointCloud())


def test_empty_clouds_raise_value_error():
    with pytest.raises(ValueError, match="no finite point"):
        pcl_ncut_seg.segment(o3d.geometry.PointCloud())
    with pytest.raises(ValueError, match="no positions"):
        pcl_ncut_seg.segment(o3d.t.geometry.PointCloud())


def test_colorize_legacy_and_tensor(points):
    labels = pcl_ncut_seg.segment(points, segments=5)
    rgb = pcl_ncut_seg.segment_colors(labels)
    cloud = legacy(points)
    assert pcl_ncut_seg.colorize(cloud, labels) is cloud
    assert np.allclose(np.asarray(cloud.colors), rgb / 255.0)
    t = pcl_ncut_seg.colorize(tensor(points), labels)
    assert t.point.colors.dtype == o3d.core.Dtype.Float32
    assert np.allclose(t.point.colors.numpy(), rgb / 255.0, atol=1e-6)
    t = tensor(points)
    t.point.colors = o3d.core.Tensor(np.zeros((len(points), 3), np.uint8))
    assert np.array_equal(pcl_ncut_seg.colorize(t, labels).point.colors.numpy(), rgb)


def test_colorize_rejects_bad_input(points):
    labels = pcl_ncut_seg.segment(points)
    with pytest.raises(ValueError, match="one label per point"):
        pcl_ncut_seg.colorize(legacy(points), labels[:-1])
    with pytest.raises(ValueError, match="one label per point"):
        pcl_ncut_seg.colorize(tensor(points), labels[1:])
    with pytest.raises(ValueError, match="integers"):
        pcl_ncut_seg.colorize(legacy(points), labels.astype(float))
    with pytest.raises(TypeError, match="Open3D|open3d"):
        pcl_ncut_seg.colorize(points, labels)
