/*
 * pcl_ncut_seg tools: reading the input, a point cloud (.pcd, .ply, .npy) or a mesh (.off,
 * .obj, .ply with faces) sampled into points, through the one reader of files/point_file.h,
 * with the tools' flags for sampling a mesh.
 */
#pragma once

#include "cli/flags.h"
#include "cli/output.h"
#include "files/point_file.h"

#include <string>
#include <vector>

namespace pcl_ncut_seg {
namespace tool {

/** \brief What was read (files/point_file.h). */
using Input = files::PointFile;

/** \brief How a mesh becomes points, and whether the flags asked for it. */
struct MeshSampling : files::MeshSampling {
  bool given = false; ///< -samples or -seed was given (an error for a point cloud)
  std::string flag;   ///< the one given, for that error
};

/** \brief Sampling a mesh input into points: -samples, -seed. */
std::vector<Flag> meshFlags();
/** \brief The sampling the mesh flags given ask for. */
MeshSampling meshSampling(const Flags& flags);

using files::isInputFile;
using files::kInputFormats;

/** \brief Read an input file (files::readPointFile). A mesh becomes points as sampling says.
 * On failure print one error line and return false. */
bool loadInput(const std::string& path, const MeshSampling& sampling, Input& input);

} // namespace tool
} // namespace pcl_ncut_seg
