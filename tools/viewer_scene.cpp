#include "viewer_scene.h"

#include "cli/console.h"

#include <pcl/console/print.h>

#include <Eigen/Eigenvalues>

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>

namespace pcl_ncut_seg {
namespace viewer {

using pcl::console::print_info;
using tool::warn;

namespace {

const struct {
  View view;
  const char* name;
} kViews[] = {{View::Segments, "segments"},     {View::Centrality, "centrality"},
              {View::Supernodes, "supernodes"}, {View::Refined, "refined"},
              {View::Coarser, "coarser"},       {View::Finer, "finer"}};

// Colours of the centrality markers: not on the heat map's blue-to-red ramp.
constexpr std::uint8_t kMaximumRgb[3] = {255, 255, 255}; // local maxima: white
constexpr std::uint8_t kSaddleRgb[3] = {255, 0, 255};    // saddles: magenta
constexpr double kText = 0.85; // light grey: text never takes a marker's or a segment's colour

const char* const kKeys[] = {
    "1       segments, in distinct colours",
    "2       centrality (heat map, blue = low, red = high), local maxima (white), saddles "
    "(magenta)",
    "3       supernodes before local refinement",
    "4       supernodes after local refinement",
    "Up / ]  one level finer: a cut with one more segment",
    "Down / [  one level coarser: a cut with one segment less",
    "h       show or hide these keys (PCL's own keys are printed on the console)",
    "q       quit"};

} // namespace

const char* viewName(View view) {
  for (const auto& v : kViews)
    if (v.view == view)
      return v.name;
  return "";
}

std::vector<View> namedViews(const std::string& name) {
  std::vector<View> views;
  for (const auto& v : kViews)
    if (name == "all" || name == v.name)
      views.push_back(v.view);
  return views;
}

bool Scene::segment() {
  std::vector<pcl::PointIndices> segments;
  seg_.extract(segments);
  if (segments.empty())
    return false;
  first_segments_ = segments.size();
  current_segments_ = segments.size();
  first_threshold_ = seg_.getParameters().stopping.threshold;
  first_rule_ = seg_.getParameters().stopping.rule;
  colored_ = seg_.getColoredCloud();
  return true;
}

bool Scene::cutInto(std::size_t segments) {
  if (segments < 1)
    return false;
  const pcl_ncut_seg::Analysis* before = seg_.getAnalysis();
  seg_.setNumberOfSegments(static_cast<int>(segments));
  std::vector<pcl::PointIndices> result;
  seg_.extract(result);
  reused_ = seg_.getAnalysis() == before;
  if (result.size() != segments) {
    // Not that many parts: go back to the current cut.
    seg_.setNumberOfSegments(static_cast<int>(current_segments_));
    seg_.extract(result);
    colored_ = seg_.getColoredCloud();
    return false;
  }
  current_segments_ = segments;
  colored_ = seg_.getColoredCloud();
  return true;
}

ColorCloud::Ptr Scene::colours(View view, std::string& title) const {
  std::ostringstream t;
  ColorCloud::Ptr out(new ColorCloud(*colored_));
  if (view == View::Segments || view == View::Coarser || view == View::Finer) {
    t << "Segments: t = " << current_segments_;
    if (current_segments_ == first_segments_ && first_rule_ != StoppingRule::Count)
      t << (first_rule_ == StoppingRule::ShortCut ? " (short-cut rule, NCut <= "
                                                  : " (NCut threshold ")
        << first_threshold_ << ")";
    else if (current_segments_ != first_segments_)
      t << " (hierarchy, " << (current_segments_ > first_segments_ ? "finer" : "coarser")
        << " than the first cut's " << first_segments_ << "; expensive stage "
        << (reused_ ? "reused" : "recomputed") << ")";
  } else if (view == View::Centrality) {
    const std::vector<float> f = seg_.getCentrality();
    float lo = std::numeric_limits<float>::infinity(), hi = -lo;
    for (float v : f)
      if (std::isfinite(v)) {
        lo = std::min(lo, v);
        hi = std::max(hi, v);
      }
    for (std::size_t i = 0; i < out->size(); ++i)
      heat(std::isfinite(f[i]) && hi > lo ? (f[i] - lo) / (hi - lo) : 0.0f, (*out)[i]);
    t << "Centrality f (blue low, red high): " << seg_.getLocalMaxima().size()
      << " local maxima (white), " << seg_.getSaddles().size() << " saddles (magenta)";
  } else {
    const bool refined = view == View::Refined;
    const std::vector<int> label = seg_.getSupernodeLabels(refined);
    for (std::size_t i = 0; i < out->size(); ++i) {
      auto& p = (*out)[i];
      p.r = p.g = p.b = 0;
      if (label[i] >= 0)
        Segmenter::segmentColor(static_cast<std::size_t>(label[i]), p.r, p.g, p.b);
    }
    t << "Supernodes " << (refined ? "after" : "before")
      << " local refinement: " << (refined ? "l = " : "m = ")
      << seg_.getNumberOfSupernodes(refined);
  }
  title = t.str();
  return out;
}

ColorCloud::Ptr Scene::markers(const std::vector<int>& indices, const std::uint8_t rgb[3]) const {
  ColorCloud::Ptr out(new ColorCloud);
  for (int i : indices) {
    pcl::PointXYZRGB p = (*colored_)[static_cast<std::size_t>(i)];
    p.r = rgb[0];
    p.g = rgb[1];
    p.b = rgb[2];
    out->push_back(p);
  }
  return out;
}

void Scene::heat(float x, pcl::PointXYZRGB& p) {
  const float h = (1.0f - std::clamp(x, 0.0f, 1.0f)) * 4.0f; // 0 red .. 4 blue
  const int sector = std::min(static_cast<int>(h), 3);
  const float f = h - static_cast<float>(sector);
  float r = 0, g = 0, b = 0;
  switch (sector) {
  case 0:
    r = 1, g = f;
    break; // red -> yellow
  case 1:
    r = 1 - f, g = 1;
    break; // yellow -> green
  case 2:
    g = 1, b = f;
    break; // green -> cyan
  default:
    g = 1 - f, b = 1;
    break; // cyan -> blue
  }
  p.r = static_cast<std::uint8_t>(std::lround(r * 255));
  p.g = static_cast<std::uint8_t>(std::lround(g * 255));
  p.b = static_cast<std::uint8_t>(std::lround(b * 255));
}

void Drawer::show(View view) {
  view_ = view;
  std::string title;
  ColorCloud::Ptr cloud = scene_.colours(view, title);
  pcl::visualization::PointCloudColorHandlerRGBField<pcl::PointXYZRGB> rgb(cloud);
  if (!viewer_.updatePointCloud<pcl::PointXYZRGB>(cloud, rgb, "points")) {
    viewer_.addPointCloud<pcl::PointXYZRGB>(cloud, rgb, "points");
  }
  viewer_.setPointCloudRenderingProperties(pcl::visualization::PCL_VISUALIZER_POINT_SIZE,
                                           point_size_, "points");
  for (const char* id : {"maxima", "saddles"})
    viewer_.removePointCloud(id);
  if (view == View::Centrality) {
    addMarkers(scene_.markers(scene_.saddles(), kSaddleRgb), "saddles");
    addMarkers(scene_.markers(scene_.localMaxima(), kMaximumRgb), "maxima");
  }
  const int font = std::max(10, height_ / 34);
  setText(title, 10, height_ - font - 10, font, "title");
  setText(keys_shown_ ? keyList() : std::string("h: keys"), 10, 10, font * 4 / 5, "keys");
}

void Drawer::addMarkers(const ColorCloud::Ptr& cloud, const std::string& id) {
  if (cloud->empty())
    return;
  pcl::visualization::PointCloudColorHandlerRGBField<pcl::PointXYZRGB> rgb(cloud);
  viewer_.addPointCloud<pcl::PointXYZRGB>(cloud, rgb, id);
  viewer_.setPointCloudRenderingProperties(pcl::visualization::PCL_VISUALIZER_POINT_SIZE,
                                           point_size_ * 3, id);
}

void Drawer::setText(const std::string& text, int x, int y, int font, const std::string& id) {
  if (!viewer_.updateText(text, x, y, font, kText, kText, kText, id))
    viewer_.addText(text, x, y, font, kText, kText, kText, id);
}

std::string Drawer::keyList() {
  std::string text;
  for (const char* line : kKeys)
    text += (text.empty() ? "" : "\n") + std::string(line);
  return text;
}

void placeCamera(pcl::visualization::PCLVisualizer& viewer,
                 const pcl::PointCloud<pcl::PointXYZ>& cloud, const Eigen::Vector3d* up_axis) {
  Eigen::Vector3d mean = Eigen::Vector3d::Zero();
  std::size_t n = 0;
  for (const auto& p : cloud)
    if (std::isfinite(p.x) && std::isfinite(p.y) && std::isfinite(p.z)) {
      mean += p.getVector3fMap().cast<double>();
      ++n;
    }
  if (n == 0)
    return;
  mean /= static_cast<double>(n);
  Eigen::Matrix3d cov = Eigen::Matrix3d::Zero();
  for (const auto& p : cloud)
    if (std::isfinite(p.x) && std::isfinite(p.y) && std::isfinite(p.z)) {
      const Eigen::Vector3d d = p.getVector3fMap().cast<double>() - mean;
      cov += d * d.transpose();
    }
  Eigen::Vector3d view, up;
  if (up_axis) {
    // The least extent among the directions across the up axis.
    up = *up_axis;
    const Eigen::Matrix3d across = Eigen::Matrix3d::Identity() - up * up.transpose();
    Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eig(across * cov * across);
    // Eigenvalues ascending; the first is ~0 along up itself: take the smaller of the others.
    view = std::abs(eig.eigenvectors().col(0).dot(up)) > 0.5 ? eig.eigenvectors().col(1)
                                                             : eig.eigenvectors().col(0);
  } else {
    Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eig(cov); // eigenvalues ascending
    view = eig.eigenvectors().col(0);
    up = eig.eigenvectors().col(1);
  }
  const double extent = std::sqrt(std::max(cov.trace() / static_cast<double>(n), 1e-12));
  const Eigen::Vector3d eye = mean + view * 10.0 * extent;
  viewer.setCameraPosition(eye.x(), eye.y(), eye.z(), mean.x(), mean.y(), mean.z(), up.x(), up.y(),
                           up.z());
  viewer.resetCamera(); // fit the cloud, keeping the direction
}

bool pressKey(const std::string& key, Scene& scene, Drawer& drawer, bool print_keys) {
  if (key == "1") {
    drawer.show(View::Segments);
  } else if (key == "2") {
    drawer.show(View::Centrality);
  } else if (key == "3") {
    drawer.show(View::Supernodes);
  } else if (key == "4") {
    drawer.show(View::Refined);
  } else if (key == "Up" || key == "bracketright" || key == "Down" || key == "bracketleft") {
    const bool finer = key == "Up" || key == "bracketright";
    const std::size_t t = scene.currentSegments();
    if (!scene.cutInto(finer ? t + 1 : t - 1))
      warn(std::string("no ") + (finer ? "finer" : "coarser") +
           " cut: the hierarchy has no level with " + std::to_string(finer ? t + 1 : t - 1) +
           " segments");
    drawer.show(View::Segments);
  } else if (key == "h" || key == "H") {
    if (print_keys) {
      print_info("pcl_ncut_seg_viewer keys:\n");
      for (const char* line : kKeys)
        print_info("  %s\n", line);
    }
    drawer.toggleKeys();
  } else {
    return false;
  }
  return true;
}

} // namespace viewer
} // namespace pcl_ncut_seg
