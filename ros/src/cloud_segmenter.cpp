#include <pcl_ncut_seg_ros/cloud_segmenter.h>

#include <pcl_ncut_seg/parameter_table.h>

#include <pcl/common/point_tests.h>
#include <pcl_conversions/pcl_conversions.h>
#include <sensor_msgs/PointField.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <memory>
#include <sstream>

namespace pcl_ncut_seg_ros {

namespace {

/** \brief "[x, y, z]", each in its shortest decimal. */
std::string triple(const double* v) {
  return "[" + pcl_ncut_seg::formatNumber(v[0]) + ", " + pcl_ncut_seg::formatNumber(v[1]) + ", " +
         pcl_ncut_seg::formatNumber(v[2]) + "]";
}

} // namespace

const char* sourceName(SensorOrigin::Source source) {
  switch (source) {
  case SensorOrigin::Source::Tf:
    return "tf";
  case SensorOrigin::Source::Points:
    return "points";
  default:
    return "cloud_frame";
  }
}

std::string SegmentStats::yaml() const {
  std::ostringstream out;
  out << "{stamp: " << pcl_ncut_seg::formatNumber(stamp) << ", points: " << points
      << ", segmented: " << segmented << ", segments: " << segments
      << ", analysed: " << (analysed ? "true" : "false") << ", analyses: " << analyses
      << ", cuts: " << cuts
      << ", analysis_seconds: " << pcl_ncut_seg::formatNumber(analysis_seconds)
      << ", cut_seconds: " << pcl_ncut_seg::formatNumber(cut_seconds)
      << ", origin: " << sourceName(origin.source) << ", sensor_origin: "
      << (origin.source == SensorOrigin::Source::Points ? "null" : triple(origin.xyz))
      << ", view: " << (view ? "true" : "false")
      << ", origin_estimated: " << (origin_estimated ? "true" : "false")
      << ", view_origin: " << (view ? triple(view_origin) : "null") << "}";
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
    // In 64 bits: an offset near 2^32 must not wrap around into the point.
    if (field->datatype != sensor_msgs::PointField::FLOAT32 || field->count < 1 ||
        std::uint64_t{field->offset} + 4 > cloud.point_step)
      return std::string("the cloud's field ") + axis + " is not one FLOAT32 within a point" +
             " (datatype " + std::to_string(field->datatype) + ", count " +
             std::to_string(field->count) + ", offset " + std::to_string(field->offset) +
             ", point_step " + std::to_string(cloud.point_step) + ")";
  }
  return "";
}

CloudSegmenter::CloudSegmenter() : seg_(newSegmentation(pcl_ncut_seg::Parameters())) {}

std::unique_ptr<Segmentation>
CloudSegmenter::newSegmentation(const pcl_ncut_seg::Parameters& params) {
  auto seg = std::make_unique<Segmentation>();
  seg->setConsoleMessages(false); // its reasons come back in its status, and go into why
  seg->setParameters(params);
  // The analysis starts with the kNN phase: counting its starts tells an analysis from a re-cut.
  seg->setProgressCallback([this](const char* phase, double fraction) {
    if (fraction == 0.0 && std::strcmp(phase, "kNN") == 0)
      ++analyses_started_;
  });
  return seg;
}

bool CloudSegmenter::setParameters(const pcl_ncut_seg::Parameters& params, std::string* why) {
  if (!pcl_ncut_seg::validate(params, why))
    return false;
  return seg_->setParameters(params);
}

bool CloudSegmenter::segment(const sensor_msgs::PointCloud2& cloud, const std::vector<int>* indices,
                             std::string* why, const SensorOrigin& origin) {
  std::string bad = checkCloud(cloud);
  auto points = std::make_shared<pcl::PointCloud<pcl::PointXYZ>>();
  if (bad.empty()) {
    pcl::fromROSMsg(cloud, *points);
    bad = checkCoordinates(*points, indices);
  }
  if (!bad.empty()) {
    if (why)
      *why = bad;
    return false;
  }
  setSensorOrigin(*points, indices, origin);
  // A new segmentation of the new cloud: a cloud the library refuses leaves the kept one (and
  // its analysis) as it was.
  std::unique_ptr<Segmentation> next = newSegmentation(seg_->getParameters());
  next->setInputCloud(points);
  if (indices)
    next->setIndices(std::make_shared<pcl::Indices>(indices->begin(), indices->end()));
  const std::size_t started = analyses_started_;
  std::vector<pcl::PointIndices> segments;
  if (!extract(*next, segments, why))
    return false;
  // A kNN graph of k needs k + 1 distinct points; fewer is a crop gone wrong, not an object.
  if (const pcl_ncut_seg::Warning* few = status_.find(pcl_ncut_seg::WarningCode::FewPoints)) {
    if (why)
      *why = "fewer than k + 1 = " + std::to_string(next->getNumberOfNeighbours() + 1) +
             " distinct finite points" + (indices ? " within the indices" : "") + ": " +
             few->message;
    return false;
  }
  seg_ = std::move(next);
  segments_ = std::move(segments);
  cloud_ = points;
  header_ = cloud.header;
  origin_ = origin;
  recordStats(started);
  return true;
}

void CloudSegmenter::setSensorOrigin(pcl::PointCloud<pcl::PointXYZ>& points,
                                     const std::vector<int>* indices, const SensorOrigin& origin) {
  if (origin.source == SensorOrigin::Source::Tf) {
    points.sensor_origin_ =
        Eigen::Vector4f(static_cast<float>(origin.xyz[0]), static_cast<float>(origin.xyz[1]),
                        static_cast<float>(origin.xyz[2]), 0.0f);
  } else if (origin.source == SensorOrigin::Source::Points) {
    // An origin among the points is no sensor: the library reads the position off them.
    Eigen::Vector3d sum = Eigen::Vector3d::Zero();
    std::size_t finite = 0;
    const std::size_t n = indices ? indices->size() : points.size();
    for (std::size_t j = 0; j < n; ++j) {
      const std::size_t i = indices ? static_cast<std::size_t>((*indices)[j]) : j;
      if (i < points.size() && pcl::isFinite(points[i])) { // (the library refuses a bad index)
        sum += points[i].getVector3fMap().cast<double>();
        ++finite;
      }
    }
    if (finite > 0)
      points.sensor_origin_.head<3>() = (sum / static_cast<double>(finite)).cast<float>();
  }
}

std::string CloudSegmenter::checkCoordinates(const pcl::PointCloud<pcl::PointXYZ>& points,
                                             const std::vector<int>* indices) {
  const std::size_t n = indices ? indices->size() : points.size();
  for (std::size_t j = 0; j < n; ++j) {
    const std::size_t i = indices ? static_cast<std::size_t>((*indices)[j]) : j;
    if (i >= points.size() || !pcl::isFinite(points[i])) // (the library refuses a bad index)
      continue;
    const float largest = points[i].getVector3fMap().cwiseAbs().maxCoeff();
    if (largest > kMaxCoordinate)
      return "point " + std::to_string(i) + " has a coordinate of " +
             pcl_ncut_seg::formatNumber(largest) + ", beyond +-" +
             pcl_ncut_seg::formatNumber(kMaxCoordinate);
  }
  return "";
}

bool CloudSegmenter::recut(std::string* why) {
  if (!cloud_) {
    if (why)
      *why = "no cloud has been segmented yet";
    return false;
  }
  const std::size_t started = analyses_started_;
  if (!extract(*seg_, segments_, why)) {
    cloud_.reset();
    return false;
  }
  recordStats(started);
  return true;
}

bool CloudSegmenter::extract(Segmentation& seg, std::vector<pcl::PointIndices>& segments,
                             std::string* why) {
  seg.extract(segments);
  status_ = seg.getStatus();
  if (status_.ok() && !segments.empty())
    return true;
  if (why) // the library's reason
    *why = status_.ok() ? "the segmentation found no segment" : status_.message;
  return false;
}

void CloudSegmenter::recordStats(std::size_t analyses_before) {
  const pcl_ncut_seg::PhaseTimes& t = seg_->getPhaseTimes();
  stats_.stamp = header_.stamp.toSec();
  stats_.points = cloud_->size();
  stats_.segments = segments_.size();
  stats_.segmented = 0;
  for (const pcl::PointIndices& s : segments_)
    stats_.segmented += s.indices.size();
  stats_.analysed = analyses_started_ != analyses_before;
  stats_.analyses += stats_.analysed;
  stats_.cuts += 1;
  stats_.analysis_seconds = t.knn + t.centrality + t.supernodes + t.refinement;
  stats_.cut_seconds = t.hierarchy + t.points;
  stats_.origin = origin_;
  viewStats();
}

void CloudSegmenter::viewStats() {
  const pcl_ncut_seg::ViewTest view = seg_->getViewTest();
  stats_.view = view.view;
  stats_.origin_estimated = view.view && view.origin_estimated;
  // The test's origin is relative to the analysed points' centroid (core/views/view_origin.h).
  const std::vector<int>& analysed = seg_->getAnalysedIndices();
  Eigen::Vector3d centroid = Eigen::Vector3d::Zero();
  for (int i : analysed)
    centroid += (*cloud_)[i].getVector3fMap().cast<double>();
  centroid /= static_cast<double>(std::max<std::size_t>(analysed.size(), 1));
  for (int d = 0; d < 3; ++d)
    stats_.view_origin[d] = view.view ? view.origin[d] + centroid[d] : 0.0;
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
    Segmentation::segmentColor(s, r, g, b);
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
