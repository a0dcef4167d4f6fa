#include "files/point_file.h"

#include "files/npy_reader.h"
#include "files/ply_reader.h"
#include "files/values.h"
#include "surfaces/mesh_sampling.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstring>
#include <sstream>

namespace pcl_ncut_seg {
namespace files {

const char* const kInputFormats = ".pcd, .ply, .npy, .off or .obj";

namespace {

/** The field named name of a single value, or null. */
const pcl::PCLPointField* field(const pcl::PCLPointCloud2& blob, const char* name) {
  for (const pcl::PCLPointField& f : blob.fields)
    if (f.name == name)
      return &f;
  return nullptr;
}

/** The x, y, z of any numeric type as PCL points, organized as the blob is. */
bool toPoints(const std::string& path, PointFile& file, std::string& error) {
  const pcl::PCLPointField* xyz[3] = {field(file.blob, "x"), field(file.blob, "y"),
                                      field(file.blob, "z")};
  for (int c = 0; c < 3; ++c) {
    const char* name = c == 0 ? "x" : c == 1 ? "y" : "z";
    if (!xyz[c]) {
      error = "'" + path + "' has no " + name + " field: need points with x, y and z";
      return false;
    }
    if (xyz[c]->count != 1) {
      error = "'" + path + "' has a field " + name + " of COUNT " + std::to_string(xyz[c]->count) +
              ": x, y and z are one value each";
      return false;
    }
  }
  const std::size_t n = std::size_t(file.blob.width) * file.blob.height;
  if (n == 0) {
    error = "'" + path + "' contains no points";
    return false;
  }
  auto& cloud =
      *(file.cloud = pcl::PointCloud<pcl::PointXYZ>::Ptr(new pcl::PointCloud<pcl::PointXYZ>));
  cloud.resize(n);
  cloud.width = file.blob.width;
  cloud.height = file.blob.height;
  std::size_t finite = 0;
  const std::uint8_t* data = file.blob.data.data();
  const std::size_t step = file.blob.point_step;
  const bool floats = xyz[0]->datatype == pcl::PCLPointField::FLOAT32 &&
                      xyz[1]->datatype == pcl::PCLPointField::FLOAT32 &&
                      xyz[2]->datatype == pcl::PCLPointField::FLOAT32;
  for (std::size_t i = 0; i < n; ++i) {
    const std::uint8_t* point = data + i * step;
    pcl::PointXYZ& p = cloud[i];
    for (int c = 0; c < 3; ++c) // the usual float fields copied, any other type converted
      if (floats)
        std::memcpy(&p.data[c], point + xyz[c]->offset, 4);
      else
        p.data[c] = valueAsFloat(point + xyz[c]->offset, xyz[c]->datatype);
    finite += std::isfinite(p.x) && std::isfinite(p.y) && std::isfinite(p.z);
  }
  if (finite == 0) {
    error = "'" + path + "' contains no point with finite coordinates";
    return false;
  }
  file.blob.is_dense = finite == n;
  cloud.is_dense = file.blob.is_dense;
  // A view's sensor origin: the library then knows where the view was seen from.
  cloud.sensor_origin_ = file.sensor.origin;
  cloud.sensor_orientation_ = file.sensor.orientation;
  if (!file.mesh)
    file.description = std::to_string(n) + " points";
  return true;
}

/** A PCLPointCloud2 with the fields x y z (float) from a flat array. */
pcl::PCLPointCloud2 xyzBlob(const std::vector<float>& xyz) {
  pcl::PCLPointCloud2 blob = xyzCloud(static_cast<std::uint32_t>(xyz.size() / 3), 1);
  std::memcpy(blob.data.data(), xyz.data(), blob.data.size());
  return blob;
}

/** Points on a mesh: one per face, or area-uniform samples. */
bool sampleMesh(const std::string& path, const TriangleMesh& mesh, const MeshSampling& sampling,
                PointFile& file, std::string& error) {
  file.mesh = true;
  file.num_faces = mesh.num_original_faces;
  if (mesh.numTriangles() == 0) {
    error = "'" + path + "' is a mesh without faces (polygons of three or more vertices)";
    return false;
  }
  std::vector<float> xyz;
  std::ostringstream what;
  what << "mesh of " << mesh.num_original_faces << " faces, ";
  if (sampling.samples > 0) {
    xyz = sampleSurface(mesh, sampling.samples, sampling.seed);
    if (xyz.empty()) {
      error = "'" + path + "' is a mesh without area: cannot sample points on it";
      return false;
    }
    what << sampling.samples << " points sampled uniformly by area (seed " << sampling.seed << ")";
  } else {
    xyz = faceCentroids(mesh);
    what << "one point per face centroid";
  }
  file.blob = xyzBlob(xyz);
  file.description = what.str();
  return true;
}

/** A PLY's faces as a TriangleMesh over its vertices (polygons fan-triangulated). */
bool plyMesh(const std::string& path, PlyContents& ply, TriangleMesh& mesh, std::string& error) {
  PointFile vertices;
  vertices.blob = std::move(ply.vertices);
  if (!toPoints(path, vertices, error))
    return false;
  mesh = TriangleMesh();
  for (const pcl::PointXYZ& p : *vertices.cloud)
    mesh.vertices.insert(mesh.vertices.end(), {p.x, p.y, p.z});
  const std::size_t num_faces = ply.face_offsets.size() - 1;
  for (std::size_t f = 0; f < num_faces; ++f) {
    const std::int64_t* v = ply.face_indices.data() + ply.face_offsets[f];
    const std::size_t k = ply.face_offsets[f + 1] - ply.face_offsets[f];
    for (std::size_t i = 0; i < k; ++i)
      if (v[i] < 0 || static_cast<std::size_t>(v[i]) >= vertices.cloud->size()) {
        error = "cannot read '" + path + "': face " + std::to_string(f) +
                " refers to a vertex that does not exist";
        return false;
      }
    for (std::size_t i = 1; i + 1 < k; ++i) {
      mesh.faces.insert(mesh.faces.end(),
                        {static_cast<std::uint32_t>(v[0]), static_cast<std::uint32_t>(v[i]),
                         static_cast<std::uint32_t>(v[i + 1])});
      mesh.original_face.push_back(static_cast<std::uint32_t>(f));
    }
  }
  mesh.num_original_faces = num_faces;
  return true;
}

bool readFormat(const std::string& path, const std::string& ext, const MeshSampling& sampling,
                PointFile& file, std::string& error) {
  FileBytes bytes;
  std::string why;
  if (!bytes.open(path, why)) {
    error = "cannot read '" + path + "': " + why;
    return false;
  }
  const auto invalid = [&](const char* format) {
    error = "cannot read '" + path + "': not a valid " + format + " file: " + why;
    return false;
  };
  if (ext == ".pcd")
    return readPcd(bytes, file.blob, file.sensor, why) || invalid("PCD");
  if (ext == ".npy")
    return readNpy(bytes, file.blob, why) || invalid(".npy");
  TriangleMesh mesh;
  if (ext == ".off" || ext == ".obj") {
    if (!(ext == ".off" ? readOff(path, mesh, &why) : readObj(path, mesh, &why))) {
      error = "cannot read " + why;
      return false;
    }
    return sampleMesh(path, mesh, sampling, file, error);
  }
  PlyContents ply;
  if (!readPly(bytes, ply, why))
    return invalid("PLY");
  if (!ply.has_faces) {
    file.blob = std::move(ply.vertices);
    return true;
  }
  return plyMesh(path, ply, mesh, error) && sampleMesh(path, mesh, sampling, file, error);
}

} // namespace

bool isInputFile(const std::string& path) {
  const std::string ext = extensionOf(path);
  return ext == ".pcd" || ext == ".ply" || ext == ".npy" || ext == ".off" || ext == ".obj";
}

bool readPointFile(const std::string& path, const MeshSampling& sampling, PointFile& file,
                   std::string& error) {
  file = PointFile();
  if (!isInputFile(path)) {
    error = "input '" + path + "' is not a " + kInputFormats + " file";
    return false;
  }
  if (readFormat(path, extensionOf(path), sampling, file, error) && toPoints(path, file, error))
    return true;
  file = PointFile(); // a refused file leaves nothing read
  return false;
}

} // namespace files
} // namespace pcl_ncut_seg
