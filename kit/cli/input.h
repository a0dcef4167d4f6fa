/*
 * pcl_ncut_seg tools: reading the input, a point cloud (.pcd, .ply) or a mesh (.off, .obj,
 * .ply with faces) sampled into points.
 */
#pragma once

#include "cli/flags.h"
#include "cli/output.h"

#include <pcl/PCLPointCloud2.h>
#include <pcl/point_cloud.h>
#include <pcl/point_types.h>

#include <cstdint>
#include <string>
#include <vector>

namespace pcl_ncut_seg {
namespace tool {

/** \brief What was read: every field of the file (for a mesh: x, y, z of the points sampled on
 * it), and the x, y, z as PCL points, with the file's sensor pose (a PCD's VIEWPOINT). */
struct Input {
  pcl::PCLPointCloud2 blob;
  SensorPose sensor; ///< a PCD's VIEWPOINT; for other formats none
  pcl::PointCloud<pcl::PointXYZ>::Ptr cloud;
  bool mesh = false;
  std::size_t num_faces = 0; ///< of a mesh
  std::string description;   ///< "8000 points" or "mesh of 500 faces, ..."
};

/** \brief How a mesh becomes points: one per face centroid, or samples uniform by area. */
struct MeshSampling {
  std::size_t samples = 0; ///< 0: one point per face
  std::uint64_t seed = 1;
  bool given = false; ///< -samples or -seed was given (an error for a point cloud)
  std::string flag;   ///< the one given, for that error
};

/** \brief Sampling a mesh input into points: -samples, -seed. */
std::vector<Flag> meshFlags();
/** \brief The sampling the mesh flags given ask for. */
MeshSampling meshSampling(const Flags& flags);

/** \brief Input formats, for messages. */
extern const char* const kInputFormats;

/** \brief True for a file name the tools read (.pcd, .ply, .off, .obj). */
bool isInputFile(const std::string& path);

/** \brief Read a .pcd, a .ply (points, or a mesh when it has faces), an .off or an .obj mesh.
 * A mesh becomes points as sampling says. On failure print one error line and return false. */
bool loadInput(const std::string& path, const MeshSampling& sampling, Input& input);

} // namespace tool
} // namespace pcl_ncut_seg
