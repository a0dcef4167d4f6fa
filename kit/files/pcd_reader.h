/*
 * pcl_ncut_seg files: PCD files (ascii, binary and binary_compressed), read without PCL's
 * reader. Every count of the header is checked against the file before anything is
 * allocated: PCL 1.13's PCDReader crashes or allocates without bound on a header that
 * disagrees with its data (docs/inputs.md).
 */
#pragma once

#include "files/file_bytes.h"

#include <pcl/PCLPointCloud2.h>

#include <Eigen/Geometry>

#include <string>

namespace pcl_ncut_seg {
namespace files {

/** \brief A PCD's VIEWPOINT: the sensor's origin and orientation. */
struct Viewpoint {
  Eigen::Vector4f origin = Eigen::Vector4f::Zero();
  Eigen::Quaternionf orientation = Eigen::Quaternionf::Identity();
};

/** \brief Read a PCD file into blob (its fields, WIDTH, HEIGHT and data, as
 * pcl::io::loadPCDFile gives them) and its VIEWPOINT.
 * \param[in] file the open file
 * \param[out] blob, viewpoint what it holds
 * \param[out] error on failure, one line saying what is wrong (the key, the field, the line)
 * \return false on any file the PCD format does not allow */
bool readPcd(const FileBytes& file, pcl::PCLPointCloud2& blob, Viewpoint& viewpoint,
             std::string& error);

} // namespace files
} // namespace pcl_ncut_seg
