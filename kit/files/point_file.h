/*
 * pcl_ncut_seg files: the one reader of the tools' inputs. A point cloud (.pcd, .ply, .npy) or
 * a mesh (.off, .obj, .ply with faces) sampled into points. The tool, the viewer, the
 * evaluator, the Python package and its batch front end all read through readPointFile(), so
 * that they take and refuse the same files for the same reasons.
 */
#pragma once

#include "files/pcd_reader.h"

#include <pcl/PCLPointCloud2.h>
#include <pcl/point_cloud.h>
#include <pcl/point_types.h>

#include <cstdint>
#include <string>

namespace pcl_ncut_seg {
namespace files {

/** \brief How a mesh becomes points: one per face centroid, or samples uniform by area. */
struct MeshSampling {
  std::size_t samples = 0; ///< 0: one point per face
  std::uint64_t seed = 1;
};

/** \brief What was read: every field of the file (for a mesh: x, y, z of the points sampled on
 * it), and the x, y, z as PCL points (organized when the file is), with the file's sensor pose
 * (a PCD's VIEWPOINT, also in the cloud's sensor_origin_ and sensor_orientation_). */
struct PointFile {
  pcl::PCLPointCloud2 blob;
  Viewpoint sensor; ///< a PCD's VIEWPOINT; for other formats the origin
  pcl::PointCloud<pcl::PointXYZ>::Ptr cloud;
  bool mesh = false;
  std::size_t num_faces = 0; ///< of a mesh
  std::string description;   ///< "8000 points" or "mesh of 500 faces, ..."
};

/** \brief The input formats, for messages: ".pcd, .ply, .npy, .off or .obj". */
extern const char* const kInputFormats;

/** \brief True for a file name the tools read (.pcd, .ply, .npy, .off, .obj; any case). */
bool isInputFile(const std::string& path);

/** \brief Read a point file, or a mesh sampled into points as sampling says.
 * \param[in] path the file
 * \param[in] sampling of a mesh (ignored for a point cloud)
 * \param[out] file what it holds, with at least one point of finite x, y and z
 * \param[out] error on failure, one line naming the file and what is wrong with it
 * \return false for a file that cannot be read, holds no points or none finite */
bool readPointFile(const std::string& path, const MeshSampling& sampling, PointFile& file,
                   std::string& error);

} // namespace files
} // namespace pcl_ncut_seg
