#include "cli/input.h"

#include "cli/console.h"
#include "cli/paths.h"
#include "surfaces/mesh_sampling.h"

#include <pcl/PolygonMesh.h>
#include <pcl/conversions.h>
#include <pcl/io/pcd_io.h>
#include <pcl/io/ply_io.h>

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstring>
#include <exception>
#include <sstream>

#include <sys/stat.h>

namespace pcl_ncut_seg {
namespace tool {

const char* const kInputFormats = ".pcd, .ply, .off or .obj";

std::vector<Flag> meshFlags() {
  std::vector<Flag> table = {
      intFlag("-samples", "N", "N points sampled uniformly by area instead of one per face, >= 1",
              "one per face", 1),
      intFlag("-seed", "S", "random seed of -samples, >= 0", "1", 0),
  };
  for (Flag& f : table)
    f.group = "mesh input";
  return table;
}

MeshSampling meshSampling(const Flags& flags) {
  MeshSampling s;
  if (flags.has("-samples"))
    s.samples = static_cast<std::size_t>(flags.integer("-samples"));
  if (flags.has("-seed"))
    s.seed = static_cast<std::uint64_t>(flags.integer("-seed"));
  s.given = flags.has("-samples") || flags.has("-seed");
  s.flag = flags.has("-samples") ? "-samples" : "-seed";
  return s;
}

bool isInputFile(const std::string& path) {
  const std::string ext = extension(path);
  return ext == ".pcd" || ext == ".ply" || ext == ".off" || ext == ".obj";
}

namespace {

/** True when the cloud has x, y, z fields and at least one point; else one error line. */
bool hasXyzAndPoints(const std::string& path, const pcl::PCLPointCloud2& blob) {
  for (const char* name : {"x", "y", "z"}) {
    const auto it = std::find_if(blob.fields.begin(), blob.fields.end(),
                                 [name](const pcl::PCLPointField& f) { return f.name == name; });
    if (it == blob.fields.end()) {
      fail("'" + path + "' has no " + name + " field: need points with x, y and z");
      return false;
    }
  }
  if (static_cast<std::uint64_t>(blob.width) * blob.height == 0) {
    fail("'" + path + "' contains no points");
    return false;
  }
  return true;
}

/** A PCLPointCloud2 with the fields x y z (float) from a flat array. */
pcl::PCLPointCloud2 xyzBlob(const std::vector<float>& xyz) {
  pcl::PointCloud<pcl::PointXYZ> cloud;
  cloud.resize(xyz.size() / 3);
  for (std::size_t i = 0; i < cloud.size(); ++i)
    cloud[i] = pcl::PointXYZ(xyz[3 * i], xyz[3 * i + 1], xyz[3 * i + 2]);
  cloud.width = static_cast<std::uint32_t>(cloud.size());
  cloud.height = 1;
  cloud.is_dense = true;
  pcl::PCLPointCloud2 blob;
  pcl::toPCLPointCloud2(cloud, blob);
  return blob;
}

/** A PLY's vertices and faces as a TriangleMesh (polygons fan-triangulated). */
bool toTriangleMesh(const std::string& path, const pcl::PolygonMesh& polygons, TriangleMesh& mesh) {
  pcl::PointCloud<pcl::PointXYZ> vertices;
  {
    SilencePcl silence;
    pcl::fromPCLPointCloud2(polygons.cloud, vertices);
  }
  mesh = TriangleMesh();
  for (const pcl::PointXYZ& p : vertices)
    mesh.vertices.insert(mesh.vertices.end(), {p.x, p.y, p.z});
  for (std::size_t f = 0; f < polygons.polygons.size(); ++f) {
    const auto& v = polygons.polygons[f].vertices;
    for (const auto index : v)
      if (static_cast<std::size_t>(index) >= vertices.size()) {
        fail("cannot read '" + path + "': face " + std::to_string(f) +
             " refers to a vertex that does not exist");
        return false;
      }
    for (std::size_t i = 1; i + 1 < v.size(); ++i) {
      mesh.faces.insert(mesh.faces.end(),
                        {static_cast<std::uint32_t>(v[0]), static_cast<std::uint32_t>(v[i]),
                         static_cast<std::uint32_t>(v[i + 1])});
      mesh.original_face.push_back(static_cast<std::uint32_t>(f));
    }
  }
  mesh.num_original_faces = polygons.polygons.size();
  return true;
}

/** Points on a mesh: one per face, or area-uniform samples. */
bool sampleMesh(const std::string& path, const TriangleMesh& mesh, const MeshSampling& sampling,
                Input& input) {
  input.mesh = true;
  input.num_faces = mesh.num_original_faces;
  if (mesh.numTriangles() == 0) {
    fail("'" + path + "' is a mesh without faces (polygons of three or more vertices)");
    return false;
  }
  std::vector<float> xyz;
  std::ostringstream what;
  what << "mesh of " << mesh.num_original_faces << " faces, ";
  if (sampling.samples > 0) {
    xyz = sampleSurface(mesh, sampling.samples, sampling.seed);
    if (xyz.empty()) {
      fail("'" + path + "' is a mesh without area: cannot sample points on it");
      return false;
    }
    what << sampling.samples << " points sampled uniformly by area (seed " << sampling.seed << ")";
  } else {
    xyz = faceCentroids(mesh);
    what << "one point per face centroid";
  }
  input.blob = xyzBlob(xyz);
  input.description = what.str();
  return true;
}

/** One error line saying why a file that is not readable cannot be read. */
void failUnreadable(const std::string& path) {
  struct stat st;
  if (::stat(path.c_str(), &st) != 0)
    fail("cannot read '" + path + "': " + std::strerror(errno));
  else if (!S_ISREG(st.st_mode))
    fail("cannot read '" + path + "': not a regular file");
  else
    fail("cannot read '" + path + "': permission denied");
}

/** An .off or .obj mesh, sampled into points. */
bool readMeshFile(const std::string& path, const MeshSampling& sampling, Input& input) {
  TriangleMesh mesh;
  std::string error;
  const bool off = extension(path) == ".off";
  if (!(off ? readOff(path, mesh, &error) : readObj(path, mesh, &error))) {
    fail("cannot read " + error);
    return false;
  }
  return sampleMesh(path, mesh, sampling, input);
}

/** A .ply: its points, or its mesh sampled into points when it has faces. */
bool readPly(const std::string& path, const MeshSampling& sampling, Input& input) {
  pcl::PolygonMesh polygons;
  int status = -1;
  {
    SilencePcl silence;
    try {
      status = pcl::PLYReader().read(path, polygons);
    } catch (const std::exception&) {
      status = -1;
    }
  }
  if (status < 0) {
    fail("cannot read '" + path + "': not a valid PLY file");
    return false;
  }
  if (polygons.polygons.empty()) {
    input.blob = std::move(polygons.cloud);
    return true;
  }
  TriangleMesh mesh;
  return hasXyzAndPoints(path, polygons.cloud) && toTriangleMesh(path, polygons, mesh) &&
         sampleMesh(path, mesh, sampling, input);
}

/** A .pcd, its header checked before its data is read. */
bool readPcd(const std::string& path, Input& input) {
  // PCL 1.13's PCDReader::read crashes on a file without a header; check the header first.
  // It also tells a cloud without x, y, z or without points before its data is read.
  const std::string invalid = "cannot read '" + path + "': not a valid PCD file";
  Eigen::Vector4f origin;
  Eigen::Quaternionf orientation;
  int version = 0, data_type = 0;
  unsigned int data_index = 0;
  int status = -1;
  {
    SilencePcl silence;
    try {
      status = pcl::PCDReader().readHeader(path, input.blob, origin, orientation, version,
                                           data_type, data_index);
    } catch (const std::exception&) {
      status = -1;
    }
  }
  if (status < 0 || input.blob.fields.empty()) {
    fail(invalid);
    return false;
  }
  if (!hasXyzAndPoints(path, input.blob))
    return false;
  {
    SilencePcl silence;
    try {
      status =
          pcl::io::loadPCDFile(path, input.blob, input.sensor.origin, input.sensor.orientation);
    } catch (const std::exception&) {
      status = -1;
    }
  }
  if (status < 0)
    fail(invalid);
  return status >= 0;
}

/** The x, y, z of what was read as PCL points; false when none is finite. */
bool toPoints(const std::string& path, Input& input) {
  if (!hasXyzAndPoints(path, input.blob))
    return false;
  input.cloud.reset(new pcl::PointCloud<pcl::PointXYZ>);
  {
    SilencePcl silence; // fromPCLPointCloud2 warns about fields it does not need
    pcl::fromPCLPointCloud2(input.blob, *input.cloud);
  }
  // A view's sensor origin: the library then knows where the view was seen from.
  input.cloud->sensor_origin_ = input.sensor.origin;
  input.cloud->sensor_orientation_ = input.sensor.orientation;
  std::size_t finite = 0;
  for (const pcl::PointXYZ& p : input.cloud->points)
    finite += std::isfinite(p.x) && std::isfinite(p.y) && std::isfinite(p.z);
  if (finite == 0) {
    fail("'" + path + "' contains no point with finite coordinates");
    return false;
  }
  if (!input.mesh)
    input.description = std::to_string(input.cloud->size()) + " points";
  return true;
}

} // namespace

bool loadInput(const std::string& path, const MeshSampling& sampling, Input& input) {
  input = Input();
  if (!isInputFile(path)) {
    fail("input '" + path + "' is not a " + kInputFormats + " file");
    return false;
  }
  if (!isReadableFile(path)) {
    failUnreadable(path);
    return false;
  }
  const std::string ext = extension(path);
  const bool read = ext == ".pcd"   ? readPcd(path, input)
                    : ext == ".ply" ? readPly(path, sampling, input)
                                    : readMeshFile(path, sampling, input);
  if (!read)
    return false;
  if (!input.mesh && sampling.given) {
    fail(sampling.flag + " applies to a mesh input (.off, .obj, .ply with faces); '" + path +
         "' holds points only");
    return false;
  }
  return toPoints(path, input);
}

} // namespace tool
} // namespace pcl_ncut_seg
