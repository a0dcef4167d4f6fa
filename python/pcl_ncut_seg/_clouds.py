"""Clouds in, colours out: numpy arrays, anything with __array__, and Open3D's point clouds
(legacy open3d.geometry.PointCloud and tensor open3d.t.geometry.PointCloud), found by what
they have, so that Open3D is imported only by those who use it."""
import colorsys

import numpy as np


def _is_legacy_cloud(cloud):
    return hasattr(cloud, "points") and callable(getattr(cloud, "has_normals", None))


def _is_tensor_cloud(cloud):
    return hasattr(cloud, "point") and hasattr(cloud, "to_legacy")


def _tensor_array(tensor):
    """An Open3D tensor as a numpy array (copied to the host when it is on another device)."""
    if hasattr(tensor, "cpu"):
        tensor = tensor.cpu()
    return tensor.numpy()


def as_arrays(cloud, normals=None):
    """as_arrays(cloud, normals=None) -> (points, normals)

    The points and normals that segment() reads from cloud: for an open3d.geometry.PointCloud
    its points and (when it has normals and normals is None) its normals as float64 arrays; for
    an open3d.t.geometry.PointCloud its positions and normals attributes; anything else (an
    array, anything with __array__) is returned as it is, for segment() to read with
    numpy.asarray. normals given here take the place of the cloud's.
    """
    if _is_legacy_cloud(cloud):
        points = np.asarray(cloud.points)
        if normals is None and cloud.has_normals():
            normals = np.asarray(cloud.normals)
        return points, normals
    if _is_tensor_cloud(cloud):
        attributes = cloud.point
        if "positions" not in attributes:
            raise ValueError("the Open3D cloud has no positions (an empty "
                             "open3d.t.geometry.PointCloud)")
        points = _tensor_array(attributes["positions"])
        if normals is None and "normals" in attributes:
            normals = _tensor_array(attributes["normals"])
        return points, normals
    return cloud, normals


def _labels_array(labels):
    labels = np.asarray(labels)
    if labels.dtype.kind not in "iu":
        raise ValueError(f"labels must be integers, got {labels.dtype.name}")
    labels = labels.reshape(-1)
    if labels.size and labels.min() < 0:
        raise ValueError(f"labels must be >= 0 (0: in no segment), got {labels.min()}")
    return labels


def segment_colors(labels):
    """segment_colors(labels) -> numpy.ndarray

    A colour per point for labels (as segment() returns them): uint8, N x 3 (N = labels.size),
    one colour per segment (golden-ratio hues, the colours of the library's getColoredCloud()
    and of the tool's output), black for 0 (points in no segment). ValueError for labels that
    are not integers >= 0.
    """
    labels = _labels_array(labels)
    t = int(labels.max(initial=0))
    palette = np.zeros((t + 1, 3), np.uint8)
    for i in range(t):
        hue = (0.1 + 0.618033988749895 * i) % 1.0
        value = 0.7 if (i // 7) % 2 else 0.95
        palette[i + 1] = np.floor(np.array(colorsys.hsv_to_rgb(hue, 0.75, value)) * 255 + 0.5)
    return palette[labels]


def colorize(cloud, labels):
    """colorize(cloud, labels) -> cloud

    Colour an Open3D point cloud (open3d.geometry.PointCloud or open3d.t.geometry.PointCloud)
    by segment, in place, with segment_colors(labels), and return it. A legacy cloud gets
    float64 colours in [0, 1]; a tensor cloud keeps the dtype of the colours it has (uint8 or
    float), float32 in [0, 1] when it has none. ValueError when labels has not one label per
    point; TypeError for anything but an Open3D cloud.
    """
    labels = _labels_array(labels)
    if _is_legacy_cloud(cloud):
        import open3d as o3d

        n = len(cloud.points)
        _check_count(n, labels)
        cloud.colors = o3d.utility.Vector3dVector(segment_colors(labels) / 255.0)
        return cloud
    if _is_tensor_cloud(cloud):
        import open3d as o3d

        if "positions" not in cloud.point:
            raise ValueError("the Open3D cloud has no positions")
        positions = cloud.point["positions"]
        _check_count(positions.shape[0], labels)
        colors = segment_colors(labels)
        if "colors" in cloud.point and cloud.point["colors"].dtype == o3d.core.Dtype.UInt8:
            values = colors
        else:
            values = (colors / 255.0).astype(np.float32)
        cloud.point["colors"] = o3d.core.Tensor(values, device=positions.device)
        return cloud
    raise TypeError("colorize takes an open3d.geometry.PointCloud or "
                    f"open3d.t.geometry.PointCloud, got {type(cloud).__name__}; "
                    "segment_colors(labels) gives the colours as an array")


def _check_count(n, labels):
    if labels.size != n:
        raise ValueError(f"labels must have one label per point: {n} points, "
                         f"{labels.size} labels")
