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

#include "viewer_scene.h"

#include <pcl/console/print.h>
#include <pcl/visualization/pcl_visualizer.h>

#include <vtkNew.h>
#include <vtkPNGWriter.h>
#include <vtkRenderWindow.h>
#include <vtkWindowToImageFilter.h>

#include <Eigen/Core>

#include <cstdlib>
#include <functional>
#include <sstream>
#include <string>
#include <vector>

using namespace pcl::console;
using namespace pcl_ncut_seg::tool;
using namespace pcl_ncut_seg::viewer;

namespace {

constexpr double kBackground = 0.12; // dark grey

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
  if (flags.has("-version")) {
    printVersion();
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
