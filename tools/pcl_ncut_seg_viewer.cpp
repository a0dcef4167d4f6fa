/*
 * pcl_ncut_seg_viewer: look at a segmentation by pcl::SupernodeNCutSegmentation and at the
 * stages that lead to it (Yamazaki et al., "Segmenting Point-sampled Surfaces"): the segments,
 * the centrality with its local maxima and saddles (the paper's Fig. 1), the supernodes before
 * and after local refinement (Figs. 3 and 5), and the hierarchy one level coarser or finer.
 *
 *   pcl_ncut_seg_viewer [input] [options]
 *   pcl_ncut_seg_viewer [input] -screenshot out.png [-view name|all] [-size WxH]
 */
#include "cli/algorithm_flags.h"
#include "cli/console.h"
#include "cli/flags.h"
#include "cli/input.h"
#include "cli/output.h"
#include "cli/paths.h"
#include "cli/progress.h"

#include <pcl/console/print.h>
#include <pcl/visualization/pcl_visualizer.h>

#include <vtkNew.h>
#include <vtkPNGWriter.h>
#include <vtkRenderWindow.h>
#include <vtkWindowToImageFilter.h>

#include <Eigen/Eigenvalues>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <limits>
#include <sstream>
#include <string>
#include <vector>

using namespace pcl::console;
using namespace pcl_ncut_seg::tool;

namespace {

using ColorCloud = pcl::PointCloud<pcl::PointXYZRGB>;
using pcl_ncut_seg::StoppingRule;

/** What can be shown. Coarser and finer are the segments of a cut with one segment less or
 * more than the first cut, from the same expensive stage. */
enum class View { Segments, Centrality, Supernodes, Refined, Coarser, Finer };

const struct {
  View view;
  const char* name;
} kViews[] = {{View::Segments, "segments"},     {View::Centrality, "centrality"},
              {View::Supernodes, "supernodes"}, {View::Refined, "refined"},
              {View::Coarser, "coarser"},       {View::Finer, "finer"}};

const char* viewName(View view) {
  for (const auto& v : kViews)
    if (v.view == view)
      return v.name;
  return "";
}

// Colours of the centrality markers: not on the heat map's blue-to-red ramp.
constexpr std::uint8_t kMaximumRgb[3] = {255, 255, 255}; // local maxima: white
constexpr std::uint8_t kSaddleRgb[3] = {255, 0, 255};    // saddles: magenta
constexpr double kBackground = 0.12;                     // dark grey
constexpr double kText = 0.85; // light grey: text never takes a marker's or a segment's colour

/** "+x" .. "-z" as a unit vector; false for another text. */
bool upAxis(const std::string& text, Eigen::Vector3d& up) {
  if (text.size() != 2 || (text[0] != '+' && text[0] != '-') || text[1] < 'x' || text[1] > 'z')
    return false;
  up = Eigen::Vector3d::Zero();
  up(text[1] - 'x') = text[0] == '+' ? 1.0 : -1.0;
  return true;
}

/** "WxH" with each side in [16, 8192]; false for another text. */
bool windowSize(const std::string& text, int& width, int& height) {
  char x = 0;
  std::istringstream in(text);
  return in >> width >> x >> height && x == 'x' && in.eof() && width >= 16 && height >= 16 &&
         width <= 8192 && height <= 8192;
}

/** The views -view names ("all": every view); empty for an unknown name. */
std::vector<View> namedViews(const std::string& name) {
  std::vector<View> views;
  for (const auto& v : kViews)
    if (name == "all" || name == v.name)
      views.push_back(v.view);
  return views;
}

/** The keys of -keys, split at spaces; false for a key the viewer does not know. */
bool pressedKeys(const std::string& text, std::vector<std::string>& keys) {
  std::istringstream in(text);
  for (std::string key; in >> key;) {
    if (key != "1" && key != "2" && key != "3" && key != "4" && key != "Up" && key != "Down" &&
        key != "h")
      return false;
    keys.push_back(key);
  }
  return true;
}

/** A flag's check from a parser of its value. */
template <typename Parse>
std::function<bool(const std::string&, std::string*)> checkWith(Parse parse,
                                                                const std::string& expected) {
  return [parse, expected](const std::string& text, std::string* why) {
    if (parse(text))
      return true;
    *why = "expected " + expected;
    return false;
  };
}

std::vector<Flag> viewerFlags() {
  std::vector<Flag> table = algorithmFlags();
  append(table, meshFlags());
  append(table,
         {textFlag("-screenshot", "FILE.png",
                   "render off-screen to FILE.png and exit (needs an X display: run under "
                   "xvfb-run -a)"),
          textFlag("-view", "NAME",
                   "the view of -screenshot: segments, centrality, supernodes, refined, coarser, "
                   "finer, or all (FILE_<view>.png each)",
                   "segments"),
          textFlag("-keys", "\"K1 K2 ...\"",
                   "with -screenshot: press these keys (1, 2, 3, 4, Up, Down, h) before each "
                   "view is taken"),
          textFlag("-size", "WxH", "window or screenshot size in pixels", "640x480"),
          textFlag("-up", "AXIS",
                   "the model's axis that points up on screen: +x, -x, +y, -y, +z or -z; the "
                   "camera looks from the side of least extent",
                   "the middle principal axis"),
          intFlag("-point_size", "P", "point size in pixels, >= 1", "3", 1, 50)},
         "viewer");
  findFlag(table, "-view")->check =
      checkWith([](const std::string& t) { return !namedViews(t).empty(); },
                "segments, centrality, supernodes, refined, coarser, finer or all");
  findFlag(table, "-keys")->check = checkWith(
      [](const std::string& t) {
        std::vector<std::string> keys;
        return pressedKeys(t, keys);
      },
      "keys among 1, 2, 3, 4, Up, Down and h");
  findFlag(table, "-size")->check = checkWith(
      [](const std::string& t) {
        int width = 0, height = 0;
        return windowSize(t, width, height);
      },
      "WxH, e.g. 640x480, each side in [16, 8192]");
  findFlag(table, "-up")->check = checkWith(
      [](const std::string& t) {
        Eigen::Vector3d up;
        return upAxis(t, up);
      },
      "+x, -x, +y, -y, +z or -z");
  findFlag(table, "-screenshot")->check =
      checkWith([](const std::string& t) { return extension(t) == ".png"; }, "a .png file");
  append(table, commonFlags());
  return table;
}

void printHelp(const char* name) {
  print_info("Syntax is: %s [input] <options>\n", name);
  print_info("Shows the segmentation of a point-sampled surface (Yamazaki et al., \"Segmenting "
             "Point-sampled Surfaces\")\nand its stages. The input is a point cloud (.pcd, "
             ".ply) or a mesh (.off, .obj, .ply with faces);\nwith no input, the bundled model "
             "armadillo.pcd. Press h in the window for the keys.\n");
  print_info("  where options are:\n");
  printFlags(viewerFlags());
}

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

/** The segmenter and everything a view needs. */
class Scene {
public:
  explicit Scene(Segmenter& seg) : seg_(seg) {}

  /** Run the first cut; false on failure. */
  bool segment() {
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

  /** Cut again with this many segments (the cheap stage only); false if the hierarchy cannot
   * give that many. */
  bool cutInto(std::size_t segments) {
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

  std::size_t firstSegments() const { return first_segments_; }
  std::size_t currentSegments() const { return current_segments_; }

  /** The points in the colours of a view, and the title that says what is shown. */
  ColorCloud::Ptr colours(View view, std::string& title) const {
    std::ostringstream t;
    ColorCloud::Ptr out(new ColorCloud(*colored_));
    if (view == View::Segments || view == View::Coarser || view == View::Finer) {
      t << "Segments: t = " << current_segments_;
      if (current_segments_ == first_segments_ && first_rule_ != StoppingRule::Count)
        t << (first_rule_ == StoppingRule::ShortCut     ? " (short-cut rule, NCut <= "
              : first_rule_ == StoppingRule::LargestGap ? " (largest NCut gap, NCut <= "
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

  /** The points at the given input indices, in one colour. */
  ColorCloud::Ptr markers(const std::vector<int>& indices, const std::uint8_t rgb[3]) const {
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
  std::vector<int> localMaxima() const { return seg_.getLocalMaxima(); }
  std::vector<int> saddles() const { return seg_.getSaddles(); }

private:
  /** Blue (0) through cyan, green, yellow to red (1). */
  static void heat(float x, pcl::PointXYZRGB& p) {
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

  void show(View view) {
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

  void hideKeys() { keys_shown_ = false; }
  void toggleKeys() {
    keys_shown_ = !keys_shown_;
    show(view_);
  }
  View view() const { return view_; }

private:
  void addMarkers(const ColorCloud::Ptr& cloud, const std::string& id) {
    if (cloud->empty())
      return;
    pcl::visualization::PointCloudColorHandlerRGBField<pcl::PointXYZRGB> rgb(cloud);
    viewer_.addPointCloud<pcl::PointXYZRGB>(cloud, rgb, id);
    viewer_.setPointCloudRenderingProperties(pcl::visualization::PCL_VISUALIZER_POINT_SIZE,
                                             point_size_ * 3, id);
  }

  void setText(const std::string& text, int x, int y, int font, const std::string& id) {
    if (!viewer_.updateText(text, x, y, font, kText, kText, kText, id))
      viewer_.addText(text, x, y, font, kText, kText, kText, id);
  }

  static std::string keyList() {
    std::string text;
    for (const char* line : kKeys)
      text += (text.empty() ? "" : "\n") + std::string(line);
    return text;
  }

  pcl::visualization::PCLVisualizer& viewer_;
  Scene& scene_;
  int point_size_, width_, height_;
  View view_ = View::Segments;
  bool keys_shown_ = false;
};

/** Look along the cloud's direction of least extent (its largest silhouette). Up is the given
 * axis, or else the direction of middle extent, so that the widest extent runs across. */
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

/** What a key does (the window's keys, and -keys of -screenshot); false for another key. */
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

/** Render the window and write it as a PNG, in one step (no partial file on failure). */
bool writeScreenshot(pcl::visualization::PCLVisualizer& viewer, const std::string& path) {
  AtomicFile file;
  if (!file.open(path))
    return false;
  vtkRenderWindow* window = viewer.getRenderWindow();
  window->Render();
  vtkNew<vtkWindowToImageFilter> grab;
  grab->SetInput(window);
  grab->SetInputBufferTypeToRGB();
  grab->ReadFrontBufferOff();
  grab->Update();
  vtkNew<vtkPNGWriter> writer;
  writer->SetFileName(file.temporaryPath().c_str());
  writer->SetInputConnection(grab->GetOutputPort());
  writer->Write();
  if (writer->GetErrorCode() != 0) {
    fail("cannot write '" + path + "'");
    return false;
  }
  return file.commit();
}

} // namespace

namespace {

/** What the viewer's command line asks for, besides the algorithm's parameters. */
struct ViewerOptions {
  std::string input_path;
  MeshSampling sampling;
  std::string shot;        ///< -screenshot: the PNG to write; "" for the window
  std::vector<View> views; ///< -view
  std::vector<std::string> keys;
  int width = 640, height = 480, point_size = 3;
  bool has_up = false;
  Eigen::Vector3d up = Eigen::Vector3d::UnitY();
  bool quiet = false;
};

/** The viewer's options from the flags (whose values the table has checked); false with one
 * error line when they do not go together or there is no display. */
bool readOptions(const Flags& flags, ViewerOptions& o) {
  if (flags.files.size() > 1) {
    fail("too many file arguments: expected one input, got '" + flags.files[1] + "' as a second");
    return false;
  }
  o.shot = flags.has("-screenshot") ? flags.text("-screenshot") : "";
  for (const char* only_shot : {"-view", "-keys"})
    if (flags.has(only_shot) && o.shot.empty()) {
      fail(std::string(only_shot) + " goes with -screenshot; in the window, press h for the keys");
      return false;
    }
  o.views = namedViews(flags.has("-view") ? flags.text("-view") : "segments");
  if (flags.has("-keys"))
    pressedKeys(flags.text("-keys"), o.keys);
  if (flags.has("-size"))
    windowSize(flags.text("-size"), o.width, o.height);
  o.has_up = flags.has("-up") && upAxis(flags.text("-up"), o.up);
  if (flags.has("-point_size"))
    o.point_size = static_cast<int>(flags.integer("-point_size"));
  o.quiet = flags.has("-quiet");
  o.sampling = meshSampling(flags);
  const char* display = std::getenv("DISPLAY");
  if (!display || !*display) {
    fail(std::string("no X display (DISPLAY is not set): ") +
         (o.shot.empty() ? "run on a desktop, or use -screenshot under xvfb-run -a"
                         : "run under xvfb-run -a"));
    return false;
  }
  o.input_path = flags.files.empty() ? findBundledModel() : flags.files[0];
  return !o.input_path.empty();
}

/** Read the input and make the first cut, with a progress bar. */
bool segmentInput(const ViewerOptions& o, bool progress_wanted, Segmenter& seg, Scene& scene,
                  Input& input) {
  ProgressBar progress(progress_wanted);
  progress.update("Read", 0.0);
  if (!loadInput(o.input_path, o.sampling, input))
    return false;
  progress.update("Read", 1.0);
  seg.setInputCloud(input.cloud);
  seg.setProgressCallback(progress.callback());
  if (!scene.segment()) {
    fail("segmentation of '" + o.input_path + "' produced no segments");
    return false;
  }
  seg.setProgressCallback({});
  if (!o.quiet)
    print_info("%s: %s, %zu segments\n", o.input_path.c_str(), input.description.c_str(),
               scene.firstSegments());
  return true;
}

/** -screenshot: each view of -view rendered off-screen to its PNG. */
bool takeScreenshots(const ViewerOptions& o, Scene& scene, const Input& input) {
  pcl::visualization::PCLVisualizer viewer("pcl_ncut_seg_viewer", false);
  viewer.getRenderWindow()->SetOffScreenRendering(1);
  viewer.setSize(o.width, o.height);
  viewer.setBackgroundColor(kBackground, kBackground, kBackground);
  viewer.setShowFPS(false);
  Drawer drawer(viewer, scene, o.point_size, o.width, o.height);
  drawer.show(View::Segments);
  placeCamera(viewer, *input.cloud, o.has_up ? &o.up : nullptr);
  for (View view : o.views) {
    // One view: the file as given; all: FILE_<view>.png beside it.
    const std::string path =
        o.views.size() == 1 ? o.shot
                            : o.shot.substr(0, o.shot.size() - 4) + "_" + viewName(view) + ".png";
    if (view == View::Coarser || view == View::Finer) {
      const std::size_t want =
          view == View::Finer ? scene.firstSegments() + 1 : scene.firstSegments() - 1;
      if (!scene.cutInto(want))
        warn(std::string("no ") + viewName(view) + " cut with " + std::to_string(want) +
             " segments; showing " + std::to_string(scene.currentSegments()));
    } else if (scene.currentSegments() != scene.firstSegments()) {
      scene.cutInto(scene.firstSegments());
    }
    drawer.hideKeys();
    drawer.show(view);
    for (const std::string& key : o.keys)
      pressKey(key, scene, drawer, false);
    if (!writeScreenshot(viewer, path))
      return false;
    if (!o.quiet)
      print_info("Wrote %s (%s, %zu segments)\n", path.c_str(), viewName(view),
                 scene.currentSegments());
  }
  return true;
}

/** The window, until the user closes it. */
void showWindow(const ViewerOptions& o, Scene& scene, const Input& input) {
  pcl::visualization::PCLVisualizer viewer("pcl_ncut_seg_viewer: " + o.input_path);
  viewer.setSize(o.width, o.height);
  viewer.setBackgroundColor(kBackground, kBackground, kBackground);
  Drawer drawer(viewer, scene, o.point_size, o.width, o.height);
  drawer.show(View::Segments);
  placeCamera(viewer, *input.cloud, o.has_up ? &o.up : nullptr);
  viewer.registerKeyboardCallback([&](const pcl::visualization::KeyboardEvent& event) {
    if (event.keyDown())
      pressKey(event.getKeySym(), scene, drawer, true);
  });
  viewer.spin();
}

} // namespace

int main(int argc, char** argv) {
  Flags flags;
  if (!parseFlags(argc, argv, viewerFlags(), flags))
    return 1;
  if (flags.has("-h")) {
    printHelp(argv[0]);
    return 0;
  }
  if (flags.has("-quiet"))
    setVerbosityLevel(L_WARN);
  ViewerOptions options;
  Segmenter seg;
  if (!readOptions(flags, options) || !applyAlgorithmFlags(flags, seg))
    return 1;
  Input input;
  Scene scene(seg);
  if (!segmentInput(options, progressWanted(flags), seg, scene, input))
    return 1;
  if (!options.shot.empty())
    return takeScreenshots(options, scene, input) ? 0 : 1;
  showWindow(options, scene, input);
  return 0;
}
