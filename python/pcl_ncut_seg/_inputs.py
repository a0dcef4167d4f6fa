"""The points of a file as the pcl_ncut_seg tool reads them: the compiled module's read_file(),
the tool's own reader (kit/files/point_file.h), so that the batch front end takes and refuses
the same files as the tool, for the same reasons, and segments the same points."""
import os

from . import _pcl_ncut_seg as _core  # type: ignore[attr-defined]  # the compiled module

EXTENSIONS = _core.input_extensions


class InputError(ValueError):
    """A file whose points cannot be read; the message says why, in one line."""


class Cloud:
    """points: float32, (N, 3) or (H, W, 3); viewpoint: the PCD's VIEWPOINT (tx ty tz qw qx qy
    qz), the sensor origin first; faces: the mesh's number of faces, None for a point cloud."""

    def __init__(self, points, viewpoint, faces=None):
        self.points, self.viewpoint, self.faces = points, tuple(viewpoint), faces

    @property
    def sensor_origin(self):
        return self.viewpoint[:3]


def read_cloud(path):
    """The Cloud of a file; InputError with the tool's reason when the tool cannot read it."""
    try:
        points, viewpoint, faces, _ = _core.read_file(os.fspath(path))  # read_file()'s
    except ValueError as error:
        raise InputError(str(error)) from None
    return Cloud(points, viewpoint, faces)
