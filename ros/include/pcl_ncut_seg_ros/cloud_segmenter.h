/*
 * pcl_ncut_seg ROS: pcl::SupernodeNCutSegmentation behind sensor_msgs/PointCloud2. It checks
 * a cloud, segments it, and keeps it with its expensive stage, so that new cut parameters
 * re-cut it without the analysis (the two stages of the segmentation). No ROS node here: the
 * nodelet and the tests drive it.
 */
#pragma once

#include <pcl_ncut_seg/parameters.h>
#include <pcl_ncut_seg/supernode_ncut_segmentation.h>

#include <pcl_msgs/PointIndices.h>
#include <sensor_msgs/PointCloud2.h>

#include <cstddef>
#include <memory>
#include <string>
#include <vector>

namespace pcl_ncut_seg_ros {

/** \brief Where the sensor was when the cloud was taken, as the nodelet hands it over. */
struct SensorOrigin {
  enum class Source {
    CloudFrame, ///< no ~sensor_frame: the origin of the cloud's frame (PCL's assumption)
    Tf,         ///< ~sensor_frame's origin in the cloud's frame, from TF
    Points      ///< ~sensor_frame not resolved: the position is read off the points
  };
  Source source = Source::CloudFrame;
  double xyz[3] = {0, 0, 0}; ///< in the cloud's frame (Tf; 0 for CloudFrame, unused for Points)
};

/** \brief The source's name in ~stats: cloud_frame, tf or points. */
const char* sourceName(SensorOrigin::Source source);

/** \brief What the last segmentation did. */
struct SegmentStats {
  double stamp = 0;            ///< the cloud's header stamp, in seconds
  std::size_t points = 0;      ///< points of the cloud (finite or not)
  std::size_t segmented = 0;   ///< points in a segment
  std::size_t segments = 0;    ///< segments found
  bool analysed = false;       ///< the expensive stage ran (false: a kept one was re-cut)
  std::size_t analyses = 0;    ///< expensive stages run so far
  std::size_t cuts = 0;        ///< cuts run so far (every segmentation is one)
  double analysis_seconds = 0; ///< of the last analysis (also when it was kept)
  double cut_seconds = 0;      ///< of the last cut

  // Where the sensor was: as handed over, and as the analysis' view test found it.
  SensorOrigin origin;               ///< the sensor origin handed over with the cloud
  bool view = false;                 ///< the analysis took the points for one view
  bool origin_estimated = false;     ///< that view's sensor position was read off the points
  double view_origin[3] = {0, 0, 0}; ///< that position, in the cloud's frame (when view)

  /** \brief A one-line YAML mapping of the above, as the nodelet publishes on ~stats. */
  std::string yaml() const;
};

using Segmentation = pcl::SupernodeNCutSegmentation<pcl::PointXYZ>;

class CloudSegmenter {
public:
  CloudSegmenter();
  CloudSegmenter(const CloudSegmenter&) = delete; // its segmentation's callback holds this
  CloudSegmenter& operator=(const CloudSegmenter&) = delete;

  /** \brief Take valid parameters (false with why, nothing changed, for invalid ones). A
   * change of the cut stages only keeps the analysis of the kept cloud; see recut(). */
  bool setParameters(const pcl_ncut_seg::Parameters& params, std::string* why);
  const pcl_ncut_seg::Parameters& parameters() const { return seg_->getParameters(); }

  /** \brief Check the message (x, y, z as FLOAT32; a layout that matches its data) and the
   * coordinates (none beyond kMaxCoordinate), then segment the cloud, restricted to indices if
   * given, as seen from origin. The library checks the rest (indices within the cloud, a
   * finite point) and its reason is why; a cloud of fewer than k + 1 distinct finite points
   * (the library's WarningCode::FewPoints) is refused too. A bad cloud returns false with why
   * and leaves the kept cloud, and its analysis, as they were. */
  bool segment(const sensor_msgs::PointCloud2& cloud, const std::vector<int>* indices,
               std::string* why, const SensorOrigin& origin = SensorOrigin());

  /** \brief Segment the kept cloud again with the parameters now set: the analysis is kept
   * when only cut parameters changed. False with why when no cloud is kept. */
  bool recut(std::string* why);

  bool hasCloud() const { return static_cast<bool>(cloud_); }

  /** \brief The kept cloud labelled: the input's header, width, height and order; fields x, y,
   * z, rgb, label; label 1 .. segments, 0 (black) for points in no segment. */
  void labelledCloud(sensor_msgs::PointCloud2& out) const;

  /** \brief The segments as indices into the input cloud, in segment order, each with the
   * input's header. */
  std::vector<pcl_msgs::PointIndices> segmentIndices() const;

  const SegmentStats& stats() const { return stats_; }
  /** \brief The library's status of the last segment() or recut() that reached it: its
   * warnings (e.g. repeated indices) also when it succeeded. */
  const pcl_ncut_seg::Status& status() const { return status_; }
  const Segmentation& segmentation() const { return *seg_; }

private:
  /** \brief A segmentation with these parameters, silent (its status says why), counting
   * its analyses. */
  std::unique_ptr<Segmentation> newSegmentation(const pcl_ncut_seg::Parameters& params);
  /** \brief seg.extract() into segments; false with the library's reason. */
  bool extract(Segmentation& seg, std::vector<pcl::PointIndices>& segments, std::string* why);
  /** \brief The sensor's position into points.sensor_origin_, as origin says. */
  static void setSensorOrigin(pcl::PointCloud<pcl::PointXYZ>& points,
                              const std::vector<int>* indices, const SensorOrigin& origin);
  /** \brief Why the points (those of indices, if given) lie too far out, or "". */
  static std::string checkCoordinates(const pcl::PointCloud<pcl::PointXYZ>& points,
                                      const std::vector<int>* indices);
  /** \brief What the last extract() did into stats_. */
  void recordStats(std::size_t analyses_before);
  /** \brief The last analysis' view test into stats_, its origin in the cloud's frame. */
  void viewStats();

  std::unique_ptr<Segmentation> seg_;         ///< the kept cloud's (never null)
  pcl::PointCloud<pcl::PointXYZ>::Ptr cloud_; ///< the kept cloud (null before a good one)
  std_msgs::Header header_;                   ///< its header
  SensorOrigin origin_;                       ///< its sensor origin as handed over
  std::vector<pcl::PointIndices> segments_;
  pcl_ncut_seg::Status status_;
  SegmentStats stats_;
  std::size_t analyses_started_ = 0;
};

/** \brief Why the cloud cannot be segmented (missing x, y or z, a layout that does not match
 * the data, no points), or "" if it can. */
std::string checkCloud(const sensor_msgs::PointCloud2& cloud);

/** \brief The largest coordinate taken (1000 km): beyond it, float coordinates lie 6 cm or
 * more apart, too coarse for parts, and their squared distances soon overflow. */
constexpr float kMaxCoordinate = 1e6f;

} // namespace pcl_ncut_seg_ros
