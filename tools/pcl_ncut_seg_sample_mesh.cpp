/*
 * pcl_ncut_seg_sample_mesh: turn an OFF mesh into a point cloud, by area-uniform samples of its
 * surface, one point per face, or what a depth camera sees of it (-view, depth_view.h), for
 * pcl_ncut_seg and the tests.
 */
#include <surfaces/depth_view_pcl.h>
#include <surfaces/mesh_sampling.h>

#include <pcl/console/parse.h>
#include <pcl/console/print.h>
#include <pcl/exceptions.h>
#include <pcl/io/pcd_io.h>
#include <pcl/point_cloud.h>
#include <pcl/point_types.h>

#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

#include <unistd.h>

namespace {

void printHelp(const char* name) {
  const pcl_ncut_seg::CameraSettings cam;
  pcl::console::print_info(
      "Usage: %s <in.off> <out.pcd> [options]\n"
      "Writes points on the mesh's surface as a binary_compressed pcl::PointXYZ PCD, or with\n"
      "-view what a depth camera sees of it as an organized binary PCD (width x height, NaN\n"
      "where no surface was hit) with the camera's pose as the sensor origin and orientation:\n"
      "the model scaled to a %.1f m bounding-box diagonal, centred at the origin, %.1f m in\n"
      "front of a %.0f-degree pinhole camera (PCL's camera frame: z forward, x right, y down).\n"
      "  -n N        number of area-uniform samples (default 8000)\n"
      "  -seed S     random seed; the same seed gives the same points (default 1)\n"
      "  -centroids  one point per face at its centroid instead of random samples\n"
      "  -view S     a depth view from the random direction of seed S (an integer >= 0)\n"
      "  -resolution WxH    the view's size in pixels, each side 8-4096 (default %dx%d)\n"
      "  -range_noise SIG   the view's range noise in metres at 1 m, growing with the depth\n"
      "                     squared, 0-0.1 (0: none; default %g)\n"
      "  -h          this help\n",
      name, cam.object_diagonal, cam.distance, cam.horizontal_fov_degrees, cam.width, cam.height,
      cam.noise_at_1m);
}

/** The whole text as a number in [lo, hi]. */
bool parseNumber(const char* text, double lo, double hi, double& value) {
  char* end = nullptr;
  value = std::strtod(text, &end);
  return end != text && *end == '\0' && value >= lo && value <= hi;
}

/** A flag's number if given; false with one error line if it is malformed or out of range. */
bool numberFlag(int argc, char** argv, const char* flag, double lo, double hi, bool integer,
                double& value) {
  const int at = pcl::console::find_argument(argc, argv, flag);
  if (at < 0)
    return true;
  if (at + 1 >= argc || !parseNumber(argv[at + 1], lo, hi, value) ||
      (integer && value != static_cast<double>(static_cast<long long>(value)))) {
    pcl::console::print_error("%s needs %s in [%g, %g].\n", flag,
                              integer ? "an integer" : "a number", lo, hi);
    return false;
  }
  return true;
}

/** The view's camera from the flags; false with one error line. */
bool readCamera(int argc, char** argv, pcl_ncut_seg::CameraSettings& cam, std::uint64_t& seed) {
  double s = 0;
  if (!numberFlag(argc, argv, "-view", 0, 1e15, true, s) ||
      !numberFlag(argc, argv, "-range_noise", 0, 0.1, false, cam.noise_at_1m))
    return false;
  seed = static_cast<std::uint64_t>(s);
  const int at = pcl::console::find_argument(argc, argv, "-resolution");
  if (at >= 0 &&
      (at + 1 >= argc || !pcl_ncut_seg::parseResolution(argv[at + 1], cam.width, cam.height))) {
    pcl::console::print_error("-resolution needs WxH such as 640x480, each side in [8, 4096].\n");
    return false;
  }
  return true;
}

/** Write beside the target and rename: a failed run never leaves a half-written output. */
bool writeAtomically(const pcl::PointCloud<pcl::PointXYZ>& cloud, const std::string& out_path,
                     bool compressed) {
  const std::string tmp_path = out_path + ".tmp" + std::to_string(::getpid());
  bool written = false;
  try {
    written = (compressed ? pcl::io::savePCDFileBinaryCompressed(tmp_path, cloud)
                          : pcl::io::savePCDFileBinary(tmp_path, cloud)) == 0 &&
              std::rename(tmp_path.c_str(), out_path.c_str()) == 0;
  } catch (const pcl::IOException&) {
    written = false; // PCL throws when it cannot open the file
  }
  if (!written) {
    std::remove(tmp_path.c_str());
    pcl::console::print_error("%s: cannot write.\n", out_path.c_str());
  }
  return written;
}

/** -view: the depth view of the mesh. */
int writeView(const pcl_ncut_seg::TriangleMesh& mesh, const pcl_ncut_seg::CameraSettings& cam,
              std::uint64_t seed, const std::string& in_path, const std::string& out_path) {
  const pcl_ncut_seg::DepthView view = pcl_ncut_seg::renderView(mesh, cam, seed);
  if (view.width == 0) {
    pcl::console::print_error("%s: the mesh has no faces or no extent.\n", in_path.c_str());
    return 1;
  }
  if (!writeAtomically(*pcl_ncut_seg::toPclCloud(view), out_path, false))
    return 1;
  const auto& o = view.pose.origin;
  pcl::console::print_info("Wrote a %d x %d view (%zu points on the surface) to %s; camera at "
                           "(%.3f, %.3f, %.3f)\n",
                           view.width, view.height, view.validPixels(), out_path.c_str(), o[0],
                           o[1], o[2]);
  return 0;
}

/** The flags of the other mode given with -view, or of -view without it; false if any. */
bool mixedModes(int argc, char** argv) {
  const bool view = pcl::console::find_argument(argc, argv, "-view") >= 0;
  for (const char* flag : {"-n", "-seed", "-centroids", "-resolution", "-range_noise"}) {
    const bool view_flag =
        std::string(flag) == "-resolution" || std::string(flag) == "-range_noise";
    if (pcl::console::find_argument(argc, argv, flag) >= 0 && view != view_flag) {
      pcl::console::print_error(view ? "%s does not go with -view.\n" : "%s needs -view.\n", flag);
      return true;
    }
  }
  return false;
}

} // namespace

int main(int argc, char** argv) {
  if (pcl::console::find_switch(argc, argv, "-h") ||
      pcl::console::find_switch(argc, argv, "--help")) {
    printHelp(argv[0]);
    return 0;
  }
  const std::vector<int> off_args = pcl::console::parse_file_extension_argument(argc, argv, ".off");
  const std::vector<int> pcd_args = pcl::console::parse_file_extension_argument(argc, argv, ".pcd");
  if (off_args.size() != 1 || pcd_args.size() != 1) {
    pcl::console::print_error("Need exactly one input .off and one output .pcd file (see -h).\n");
    return 1;
  }
  const std::string in_path = argv[off_args[0]];
  const std::string out_path = argv[pcd_args[0]];
  if (mixedModes(argc, argv))
    return 1;
  pcl_ncut_seg::CameraSettings cam;
  std::uint64_t view_seed = 0;
  if (!readCamera(argc, argv, cam, view_seed))
    return 1;

  int n = 8000;
  if (pcl::console::find_argument(argc, argv, "-n") >= 0 &&
      (pcl::console::parse_argument(argc, argv, "-n", n) < 0 || n <= 0)) {
    pcl::console::print_error("-n needs a positive integer.\n");
    return 1;
  }
  unsigned seed = 1;
  if (pcl::console::find_argument(argc, argv, "-seed") >= 0 &&
      pcl::console::parse_argument(argc, argv, "-seed", seed) < 0) {
    pcl::console::print_error("-seed needs a non-negative integer.\n");
    return 1;
  }
  const bool centroids = pcl::console::find_switch(argc, argv, "-centroids");

  pcl_ncut_seg::TriangleMesh mesh;
  std::string error;
  if (!pcl_ncut_seg::readOff(in_path, mesh, &error)) {
    pcl::console::print_error("%s\n", error.c_str());
    return 1;
  }
  if (pcl::console::find_argument(argc, argv, "-view") >= 0)
    return writeView(mesh, cam, view_seed, in_path, out_path);
  const std::vector<float> xyz =
      centroids ? pcl_ncut_seg::faceCentroids(mesh)
                : pcl_ncut_seg::sampleSurface(mesh, static_cast<std::size_t>(n), seed);
  if (xyz.empty()) {
    pcl::console::print_error("%s: the mesh has no faces or no area.\n", in_path.c_str());
    return 1;
  }

  pcl::PointCloud<pcl::PointXYZ> cloud;
  cloud.resize(xyz.size() / 3);
  for (std::size_t i = 0; i < cloud.size(); ++i)
    cloud[i] = pcl::PointXYZ(xyz[3 * i], xyz[3 * i + 1], xyz[3 * i + 2]);
  if (!writeAtomically(cloud, out_path, true))
    return 1;
  pcl::console::print_info("Wrote %zu points to %s\n", cloud.size(), out_path.c_str());
  return 0;
}
