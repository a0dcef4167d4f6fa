#include "files.h"

#include "files/point_file.h"

#include <pybind11/numpy.h>

#include <cstring>
#include <string>

namespace py = pybind11;

namespace pcl_ncut_seg_python {

namespace {

const char* const kReadFileDoc =
    R"doc(read_file(path, samples=0, seed=1) -> (points, viewpoint, faces, description)

Read a point file as the pcl_ncut_seg tool reads it: a .pcd (ascii, binary or
binary_compressed), a .ply (points, or a mesh when it has faces), an .npy of points, an .off or
.obj mesh. A mesh becomes one point per face centroid, or samples points uniformly by area
(seed: their random seed).

points: float32, (N, 3), or (H, W, 3) for an organized cloud (HEIGHT > 1); viewpoint: the
PCD's VIEWPOINT (tx ty tz qw qx qy qz: the sensor origin, then its orientation); faces: the
mesh's number of faces, None for a point cloud; description: what was read, in words.
Raises ValueError with the tool's one-line reason for a file it cannot read or that holds no
point with finite coordinates.)doc";

py::tuple readFile(const std::string& path, std::size_t samples, std::uint64_t seed) {
  pcl_ncut_seg::files::PointFile file;
  pcl_ncut_seg::files::MeshSampling sampling;
  sampling.samples = samples;
  sampling.seed = seed;
  std::string error;
  bool ok = false;
  {
    py::gil_scoped_release release;
    ok = pcl_ncut_seg::files::readPointFile(path, sampling, file, error);
  }
  if (!ok)
    throw py::value_error(error);
  const pcl::PointCloud<pcl::PointXYZ>& cloud = *file.cloud;
  std::vector<py::ssize_t> shape = {static_cast<py::ssize_t>(cloud.size()), 3};
  if (cloud.height > 1)
    shape = {static_cast<py::ssize_t>(cloud.height), static_cast<py::ssize_t>(cloud.width), 3};
  py::array_t<float> points(shape);
  float* out = points.mutable_data();
  for (std::size_t i = 0; i < cloud.size(); ++i)
    std::memcpy(out + 3 * i, cloud[i].data, 3 * sizeof(float));
  const auto& s = file.sensor;
  const py::tuple viewpoint =
      py::make_tuple(s.origin[0], s.origin[1], s.origin[2], s.orientation.w(), s.orientation.x(),
                     s.orientation.y(), s.orientation.z());
  const py::object faces = file.mesh ? py::object(py::int_(file.num_faces)) : py::none();
  return py::make_tuple(points, viewpoint, faces, file.description);
}

} // namespace

void defineFiles(py::module_& m) {
  m.def("read_file", &readFile, py::arg("path"), py::arg("samples") = 0, py::arg("seed") = 1,
        kReadFileDoc);
  m.attr("input_extensions") = py::make_tuple(".pcd", ".ply", ".npy", ".off", ".obj");
}

} // namespace pcl_ncut_seg_python
