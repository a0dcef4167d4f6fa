/*
 * pcl_ncut_seg tools: writing files in one step, so that a failed run leaves no file behind
 * and never a half-replaced one.
 */
#pragma once

#include "files/pcd_reader.h"

#include <pcl/PCLPointCloud2.h>

#include <Eigen/Geometry>

#include <string>

namespace pcl_ncut_seg {
namespace tool {

/** \brief A temporary file beside the target, renamed over it by commit() and removed
 * otherwise, so that a failed run leaves no file behind. */
class AtomicFile {
public:
  AtomicFile() = default;
  AtomicFile(const AtomicFile&) = delete;
  AtomicFile& operator=(const AtomicFile&) = delete;
  ~AtomicFile();

  /** \brief Create the temporary file; one error line and false if that cannot be done. */
  bool open(const std::string& path);
  const std::string& temporaryPath() const { return tmp_; }
  const std::string& path() const { return path_; }
  /** \brief Rename the temporary file over the target; one error line on failure. */
  bool commit();

private:
  std::string path_, tmp_;
};

/** \brief How a PCD file stores its points. */
enum class PcdEncoding {
  Binary, ///< the default, as PCL's tools write (pcl_viewer reads both)
  Ascii   ///< text, with enough digits to read back every value exactly
};

/** \brief The sensor's pose, a PCD file's VIEWPOINT (PCL's sensor_origin_ and
 * sensor_orientation_); none given: the origin and no rotation. */
using SensorPose = files::Viewpoint;

/** \brief Write a cloud as PCD, with the sensor's pose as its VIEWPOINT, to the file's
 * temporary path; one error line on failure. */
bool writePcd(AtomicFile& file, const pcl::PCLPointCloud2& blob, PcdEncoding encoding,
              const SensorPose& sensor = SensorPose());

/** \brief Write text to the file's temporary path; one error line on failure. */
bool writeText(AtomicFile& file, const std::string& contents);

} // namespace tool
} // namespace pcl_ncut_seg
