/*
 * pcl_ncut_seg: a depth view (depth_view.h) as an organized pcl::PointCloud, with the sensor
 * pose in sensor_origin_ and sensor_orientation_.
 */
#pragma once

#include "surfaces/depth_view.h"

#include <pcl/point_cloud.h>
#include <pcl/point_types.h>

namespace pcl_ncut_seg {

/** \brief The view's width x height points (NaN where no surface was hit, is_dense false) in the
 * view's world frame, with the camera's pose (world = origin + orientation * camera). */
inline pcl::PointCloud<pcl::PointXYZ>::Ptr toPclCloud(const DepthView& view) {
  pcl::PointCloud<pcl::PointXYZ>::Ptr cloud(new pcl::PointCloud<pcl::PointXYZ>);
  cloud->width = static_cast<std::uint32_t>(view.width);
  cloud->height = static_cast<std::uint32_t>(view.height);
  cloud->points.resize(view.face.size());
  for (std::size_t i = 0; i < view.face.size(); ++i)
    cloud->points[i] = pcl::PointXYZ(view.xyz[3 * i], view.xyz[3 * i + 1], view.xyz[3 * i + 2]);
  cloud->is_dense = view.validPixels() == view.face.size();
  const auto& o = view.pose.origin;
  cloud->sensor_origin_ = Eigen::Vector4f(static_cast<float>(o[0]), static_cast<float>(o[1]),
                                          static_cast<float>(o[2]), 0);
  const auto q = view.pose.quaternion();
  cloud->sensor_orientation_ =
      Eigen::Quaternionf(static_cast<float>(q[0]), static_cast<float>(q[1]),
                         static_cast<float>(q[2]), static_cast<float>(q[3]));
  return cloud;
}

} // namespace pcl_ncut_seg
