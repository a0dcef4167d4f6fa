#include <pcl_ncut_seg_ros/cloud_segmenter.h>

#include <pcl_ncut_seg/parameter_table.h>

#include <pcl/common/point_tests.h>
#include <pcl_conversions/pcl_conversions.h>
#include <sensor_msgs/PointField.h>

#include <cmath>
#include <cstdint>
#include <cstring>
#include <memory>
#include <sstream>

namespace pcl_ncut_seg_ros {

std::string SegmentStats::yaml() const {
  std::ostringstream out;
  out << "{stamp: " << pcl_ncut_seg::formatNumber(stamp) << ", points: " << points
      << ", segmented: " << segmented << ", segments: " << segments
      << ", analysed: " << (analysed ? "true" : "false") << ", analyses: " << analyses
      << ", cuts: " << cuts
      << ", analysis_seconds: " << pcl_ncut_seg::formatNumber(analysis_seconds)
      << ", cut_seconds: " << pcl_ncut_seg::formatNumber(cut_seconds) << "}";
  return out.str();
}

std::string checkCloud(const sensor_msgs::PointCloud2& cloud) {
  const std::size_t n = static_cast<std::size_t>(cloud.width) * cloud.height;
  if (n == 0)
    return "the cloud is empty (width " + std::to_string(cloud.width) + ", height " +
           std::to_string(cloud.height) + ")";
  const std::size_t row = static_cast<std::size_t>(cloud.width) * cloud.point_step;
  if (cloud.point_step == 0 || cloud.row_step < row ||
      cloud.data.size() < static_cast<std::size_t>(cloud.height - 1) * cloud.row_step + row)
    return "the cloud's data (" + std::to_string(cloud.data.size()) +
           " bytes) does not match its layout (width " + std::to_string(cloud.width) + ", height " +
           std::to_string(cloud.height) + ", point_step " + std::to_string(cloud.point_step) +
           ", row_step " + std::to_string(cloud.row_step) + ")";
  if (cloud.is_bigendian)
    return "the cloud is big-endian";
  std::string names;
  for (const sensor_msgs::PointField& f : cloud.fields)
    names += (names.empty() ? "" : " ") + f.name;
  for (const char* axis : {"x", "y", "z"}) {
    const sensor_msgs::PointField* field = nullptr;
    for (const sensor_msgs::PointField& f : cloud.fields)
      if (f.name == axis)
        field = &f;
    if (!field)
      return std::string("the cloud has no field ") + axis +
             " (its fields: " + (names.empty() ? "none" : names) + ")";
    if (field->datatype != sensor_msgs::PointField::FLOAT32 || field->count < 1 ||
        field->offset + 4u > cloud.point_step)
      return std::string("the cloud's field ") + axis + " is not one FLOAT32 within a point";
  }
  return "";
}

CloudSegmenter::CloudSegmenter() {
  // The analysis starts with the kNN phase: counting its starts tells an analysis from a re-cut.
  seg_.setProgressCallback([this](const char* phase, double fraction) {
    if (fraction == 0.0 && std::strcmp(phase, "kNN") == 0)
      ++analyses_started_;
  });
}

bool CloudSegmenter::setParameters(const pcl_ncut_seg::Parameters& params, std::string* why) {
  if (!pcl_ncut_seg::validate(params, why))
    return false;
  return seg_.setParameters(params);
}

bool CloudSegmenter::segment(const sensor_msgs::PointCloud2& cloud, const std::vector<int>* indices,
                             std::string* why) {
  const std::string bad = checkCloud(cloud);
  if (!bad.empty()) {
    if (why)
      *why = bad;
    return false;
  }
  auto points = std::make_shared<pcl::PointCloud<pcl::PointXYZ>>();
  pcl::fromROSMsg(cloud, *points);
  std::size_t finite = 0;
  if (indices) {
    for (int i : *indices) {
      if (i < 0 || static_cast<std::size_t>(i) >= points->size()) {
        if (why)
          *why = "index " + std::to_string(i) + " is outside the cloud of " +
                 std::to_string(points->size()) + " points";
        return false;
      }
      finite += pcl::isFinite((*points)[i]);
    }
  } else {
    for (const pcl::PointXYZ& p : *points)
      finite += pcl::isFinite(p);
  }
  if (finite == 0) {
    if (why)
      *why = std::string("the cloud has no finite point") + (indices ? " within the indices" : "");
    return false;
  }
  cloud_ = points;
  header_ = cloud.header;
  seg_.setInputCloud(cloud_);
  if (indices)
    seg_.setIndices(std::make_shared<pcl::Indices>(indices->begin(), indices->end()));
  else
    seg_.setIndices(pcl::IndicesPtr());
  return run(why);
}

bool CloudSegmenter::recut(std::string* why) {
  if (!cloud_) {
    if (why)
      *why = "no cloud has been segmented yet";
    return false;
  }
  return run(why);
}

bool CloudSegmenter::run(std::string* why) {
  const std::size_t started = analyses_started_;
  seg_.extract(segments_);
  if (segments_.empty()) {
    cloud_.reset();
    if (why)
      *why = "the segmentation found no segment (see PCL's message above)";
    return false;
  }
  const pcl_ncut_seg::PhaseTimes& t = seg_.getPhaseTimes();
  stats_.stamp = header_.stamp.toSec();
  stats_.points = cloud_->size();
  stats_.segments = segments_.size();
  stats_.segmented = 0;
  for (const pcl::PointIndices& s : segments_)
    stats_.segmented += s.indices.size();
  stats_.analysed = analyses_started_ != started;
  stats_.analyses += stats_.analysed;
  stats_.cuts += 1;
  stats_.analysis_seconds = t.knn + t.centrality + t.supernodes + t.refinement;
  stats_.cut_seconds = t.hierarchy + t.points;
  return true;
}

void CloudSegmenter::labelledCloud(sensor_msgs::PointCloud2& out) const {
  out = sensor_msgs::PointCloud2();
  if (!cloud_)
    return;
  out.header = header_;
  out.width = cloud_->width;
  out.height = cloud_->height;
  out.is_bigendian = false;
  out.is_dense = cloud_->is_dense;
  const char* names[] = {"x", "y", "z", "rgb", "label"};
  for (std::uint32_t i = 0; i < 5; ++i) {
    sensor_msgs::PointField f;
    f.name = names[i];
    f.offset = 4 * i;
    f.datatype = i < 4 ? sensor_msgs::PointField::FLOAT32 : sensor_msgs::PointField::UINT32;
    f.count = 1;
    out.fields.push_back(f);
  }
  out.point_step = 20;
  out.row_step = out.point_step * out.width;
  out.data.assign(static_cast<std::size_t>(out.row_step) * out.height, 0);
  std::vector<std::uint32_t> label(cloud_->size(), 0), rgb(cloud_->size(), 0);
  for (std::size_t s = 0; s < segments_.size(); ++s) {
    std::uint8_t r, g, b;
    pcl::SupernodeNCutSegmentation<pcl::PointXYZ>::segmentColor(s, r, g, b);
    const std::uint32_t packed = (std::uint32_t(r) << 16) | (std::uint32_t(g) << 8) | b;
    for (int i : segments_[s].indices) {
      label[i] = static_cast<std::uint32_t>(s + 1);
      rgb[i] = packed;
    }
  }
  for (std::size_t i = 0; i < cloud_->size(); ++i) {
    std::uint8_t* p = &out.data[i * out.point_step];
    const pcl::PointXYZ& q = (*cloud_)[i];
    std::memcpy(p, &q.x, 4);
    std::memcpy(p + 4, &q.y, 4);
    std::memcpy(p + 8, &q.z, 4);
    std::memcpy(p + 12, &rgb[i], 4); // the packed colour as ROS's FLOAT32 rgb holds it
    std::memcpy(p + 16, &label[i], 4);
  }
}

std::vector<pcl_msgs::PointIndices> CloudSegmenter::segmentIndices() const {
  std::vector<pcl_msgs::PointIndices> out(segments_.size());
  for (std::size_t s = 0; s < segments_.size(); ++s) {
    out[s].header = header_;
    out[s].indices.assign(segments_[s].indices.begin(), segments_[s].indices.end());
  }
  return out;
}

} // namespace pcl_ncut_seg_ros
