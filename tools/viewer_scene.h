/*
 * pcl_ncut_seg_viewer's views: what each view shows (Scene: the segmenter's results in a view's
 * colours, with its title), how it is drawn into a PCLVisualizer (Drawer: the points, the
 * markers, the overlay text), where the camera looks from, and what the keys do.
 */
#pragma once

#include "cli/algorithm_flags.h"

#include <pcl/point_cloud.h>
#include <pcl/point_types.h>
#include <pcl/visualization/pcl_visualizer.h>

#include <Eigen/Core>

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

namespace pcl_ncut_seg {
namespace viewer {

using ColorCloud = pcl::PointCloud<pcl::PointXYZRGB>;
using tool::Segmenter;

/** What can be shown. Coarser and finer are the segments of a cut with one segment less or
 * more than the first cut, from the same expensive stage. */
enum class View { Segments, Centrality, Supernodes, Refined, Coarser, Finer };

const char* viewName(View view);

/** The views -view names ("all": every view); empty for an unknown name. */
std::vector<View> namedViews(const std::string& name);

/** The segmenter and everything a view needs. */
class Scene {
public:
  explicit Scene(Segmenter& seg) : seg_(seg) {}

  /** Run the first cut; false on failure. */
  bool segment();

  /** Cut again with this many segments (the cheap stage only); false if the hierarchy cannot
   * give that many. */
  bool cutInto(std::size_t segments);

  std::size_t firstSegments() const { return first_segments_; }
  std::size_t currentSegments() const { return current_segments_; }

  /** The points in the colours of a view, and the title that says what is shown. */
  ColorCloud::Ptr colours(View view, std::string& title) const;

  /** The points at the given input indices, in one colour. */
  ColorCloud::Ptr markers(const std::vector<int>& indices, const std::uint8_t rgb[3]) const;
  std::vector<int> localMaxima() const { return seg_.getLocalMaxima(); }
  std::vector<int> saddles() const { return seg_.getSaddles(); }

private:
  /** Blue (0) through cyan, green, yellow to red (1). */
  static void heat(float x, pcl::PointXYZRGB& p);

  Segmenter& seg_;
  pcl::PointCloud<pcl::PointXYZRGB>::Ptr colored_;
  std::size_t first_segments_ = 0, current_segments_ = 0;
  double first_threshold_ = 0;
  StoppingRule first_rule_ = StoppingRule::ShortCut; ///< of the first cut
  bool reused_ = true;
};

/** Draws a view into a PCLVisualizer: the points, the markers, the overlay text. */
class Drawer {
public:
  Drawer(pcl::visualization::PCLVisualizer& viewer, Scene& scene, int point_size, int width,
         int height)
      : viewer_(viewer), scene_(scene), point_size_(point_size), width_(width), height_(height) {}

  void show(View view);

  void hideKeys() { keys_shown_ = false; }
  void toggleKeys() {
    keys_shown_ = !keys_shown_;
    show(view_);
  }
  View view() const { return view_; }

private:
  void addMarkers(const ColorCloud::Ptr& cloud, const std::string& id);

  void setText(const std::string& text, int x, int y, int font, const std::string& id);

  static std::string keyList();

  pcl::visualization::PCLVisualizer& viewer_;
  Scene& scene_;
  int point_size_, width_, height_;
  View view_ = View::Segments;
  bool keys_shown_ = false;
};

/** Look along the cloud's direction of least extent (its largest silhouette). Up is the given
 * axis, or else the direction of middle extent, so that the widest extent runs across. */
void placeCamera(pcl::visualization::PCLVisualizer& viewer,
                 const pcl::PointCloud<pcl::PointXYZ>& cloud, const Eigen::Vector3d* up_axis);

/** What a key does (the window's keys, and -keys of -screenshot); false for another key. */
bool pressKey(const std::string& key, Scene& scene, Drawer& drawer, bool print_keys);

} // namespace viewer
} // namespace pcl_ncut_seg
