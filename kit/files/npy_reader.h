/*
 * pcl_ncut_seg files: numpy's .npy arrays of points, (N, 3) or an organized (H, W, 3), of
 * floats or integers, read as float32 x, y, z (versions 1 to 3 of the format, either byte
 * order, C or Fortran order).
 */
#pragma once

#include "files/file_bytes.h"

#include <pcl/PCLPointCloud2.h>

#include <string>

namespace pcl_ncut_seg {
namespace files {

/** \brief Read an .npy of points into blob (fields x y z, FLOAT32; an (H, W, 3) array is an
 * organized cloud of WIDTH W and HEIGHT H).
 * \param[out] error on failure, one line saying what is wrong
 * \return false on a file that is not an .npy of points */
bool readNpy(const FileBytes& file, pcl::PCLPointCloud2& blob, std::string& error);

} // namespace files
} // namespace pcl_ncut_seg
