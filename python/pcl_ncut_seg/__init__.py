"""Part segmentation of point-sampled surfaces (Yamazaki et al.) with PCL, for numpy and Open3D.

    import pcl_ncut_seg
    labels = pcl_ncut_seg.segment(points, segments=6)

points is an (N, 3) float32 or float64 array, anything with __array__ that numpy reads as one,
a depth image's (H, W, 3) points, or an Open3D point cloud (open3d.geometry.PointCloud or
open3d.t.geometry.PointCloud: its points, and its normals when it has some). The result is N
int32 labels: 1 to t for the t segments (numbered by their first point), 0 for points in no
segment: the labels of pcl::SupernodeNCutSegmentation and of the pcl_ncut_seg tool.

Parameters go by the tool's flag names without the '-' (k=12, threshold=0.1, segments=6, ...);
parameter_table() lists them with their ranges and defaults. None turns an optional extension
off (or to auto), True/False are on/off, paper=True starts from the paper's settings. A bad
cloud or parameter raises ValueError with the library's reason. Segmenter keeps the expensive
stage between calls. colorize(cloud, labels) colours an Open3D cloud by segment.
read_file(path) reads a .pcd, .ply, .npy, .off or .obj file as the pcl_ncut_seg tool reads it.
"""
import os


from . import _pcl_ncut_seg as _core
from ._clouds import as_arrays, colorize, segment_colors
from ._pcl_ncut_seg import __version__, default_parameters, parameter_shorthands, parameter_table

__all__ = [
    "Segmenter",
    "__version__",
    "as_arrays",
    "colorize",
    "default_parameters",
    "parameter_shorthands",
    "parameter_table",
    "read_file",
    "segment",
    "segment_colors",
]


def segment(points, normals=None, sensor_origin=None, **parameters):
    """segment(points, normals=None, sensor_origin=None, **parameters) -> numpy.ndarray

    Segment a cloud with the project's defaults changed by the keyword parameters (the names of
    parameter_table(); paper=True: the paper's settings).

    points: an (N, 3) float32 or float64 array (NaN rows are in no segment), anything numpy
    reads as one (__array__), a depth image's (H, W, 3) points (NaN where nothing came back),
    or an Open3D cloud (open3d.geometry.PointCloud, open3d.t.geometry.PointCloud), whose
    normals, when it has some, are taken unless normals is given.
    normals: an array of the points' shape: the normals CAD mode (cad=True) reads in place of
    estimating them (NaN rows: estimated); the other stages do not read normals.
    sensor_origin: the (x, y, z) of the sensor that saw the points, in their frame (None: the
    frame's origin, as PCL's sensor_origin_: a view in the camera's frame needs none). A single
    view is analysed from there; when it cannot be the sensor, the position is read off the
    points.

    Returns N (or H x W) int32 labels, 1-based, 0 for points in no segment. Raises ValueError
    on a bad cloud, no finite point or a bad parameter; the library's warnings (fewer points
    than k + 1, ...) are RuntimeWarnings.
    """
    points, normals = as_arrays(points, normals)
    return _core.segment(points, normals, sensor_origin, **parameters)


def read_file(path, samples=0, seed=1):
    """read_file(path, samples=0, seed=1) -> (points, viewpoint, faces, description)

    Read a file as the pcl_ncut_seg tool reads it, with its reader: a .pcd (ascii, binary or
    binary_compressed), a .ply (points, or a mesh when it has faces), an .npy of points, an .off
    or .obj mesh. A mesh becomes one point per face centroid, or samples points uniformly by
    area (seed: their random seed).

    points: float32, (N, 3), or (H, W, 3) for an organized cloud; viewpoint: the PCD's
    VIEWPOINT (tx, ty, tz, qw, qx, qy, qz: the sensor origin, then its orientation); faces: the
    mesh's number of faces, None for a point cloud; description: what was read, in words.
    Raises ValueError with the tool's one-line reason for a file it cannot read, or that holds
    no point with finite coordinates.
    """
    return _core.read_file(os.fspath(path), samples, seed)


class Segmenter(_core.Segmenter):
    __doc__ = _core.Segmenter.__doc__ + """

segment() takes what pcl_ncut_seg.segment() takes: arrays, anything with __array__, and
Open3D point clouds (with their normals)."""

    def segment(self, points=None, normals=None, sensor_origin=None, **parameters):
        """segment(points=None, normals=None, sensor_origin=None, **parameters) -> numpy.ndarray

        Set the parameters (as set()), then segment points (as pcl_ncut_seg.segment() takes
        them: an array, anything with __array__ or an Open3D cloud, with its normals, seen
        from sensor_origin). None: the points of the last call again, reusing the expensive
        stage (kNN graph, centrality, supernodes) when only cut parameters changed.

        Returns N int32 labels (H x W for an (H, W, 3) image), 1-based, 0 for points in no
        segment. ValueError on bad input, and the Segmenter keeps its previous state.
        """
        if points is not None:
            points, normals = as_arrays(points, normals)
        return super().segment(points, normals, sensor_origin, **parameters)
