"""pcl_ncut_seg.read_file(): the tool's reader of files, from Python."""
import pathlib

import numpy as np
import pytest

import batch_inputs
import pcd
import pcl_ncut_seg


def test_a_cloud_reads_as_float32_points_with_its_viewpoint(tmp_path):
    points = np.random.default_rng(3).normal(size=(50, 3)).astype(np.float32)
    pcd.write_xyz(tmp_path / "c.pcd", points)
    got, viewpoint, faces, description = pcl_ncut_seg.read_file(tmp_path / "c.pcd")
    assert got.dtype == np.float32 and np.array_equal(got, points)
    assert viewpoint == (0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0)
    assert faces is None and description == "50 points"


def test_an_organized_view_keeps_its_rows_and_its_sensor(tmp_path):
    points = np.arange(4 * 5 * 3, dtype=np.float32).reshape(4, 5, 3)
    points[1, 2] = np.nan
    batch_inputs.write_pcd_view(str(tmp_path / "v.pcd"), points, (0.5, -1.0, 2.0))
    got, viewpoint, _, _ = pcl_ncut_seg.read_file(str(tmp_path / "v.pcd"))
    assert got.shape == (4, 5, 3) and np.array_equal(got, points, equal_nan=True)
    assert viewpoint[:3] == (0.5, -1.0, 2.0)


def test_a_mesh_is_its_face_centroids_or_samples(tmp_path):
    vertices, polygons = batch_inputs._capsule(10, 8, True)
    batch_inputs.write_off(str(tmp_path / "m.off"), vertices, polygons)
    centroids, _, faces, _ = pcl_ncut_seg.read_file(pathlib.Path(tmp_path / "m.off"))
    assert faces == len(polygons) and centroids.shape == (faces, 3)
    samples, _, _, description = pcl_ncut_seg.read_file(tmp_path / "m.off", samples=300, seed=4)
    assert samples.shape == (300, 3) and "seed 4" in description
    again, _, _, _ = pcl_ncut_seg.read_file(tmp_path / "m.off", samples=300, seed=4)
    assert np.array_equal(samples, again)


def test_a_bad_file_raises_the_tools_reason(tmp_path):
    path = tmp_path / "bad.pcd"
    path.write_bytes(b"VERSION 0.7\nFIELDS x y z\nSIZE 4 3 4\nTYPE F F F\nWIDTH 1\nPOINTS 1\n"
                     b"DATA ascii\n1 2 3\n")
    with pytest.raises(ValueError, match=r"bad.pcd': not a valid PCD file: field 'y' has TYPE F "
                                         r"SIZE 3"):
        pcl_ncut_seg.read_file(path)
    with pytest.raises(ValueError, match="No such file"):
        pcl_ncut_seg.read_file(tmp_path / "none.ply")
