/*
 * pcl_ncut_seg_sample_mesh: turn an OFF mesh into a point cloud, by area-uniform samples of its
 * surface or one point per face, for pcl_ncut_seg and the tests.
 */
#include "mesh_sampling.h"

#include <pcl/console/parse.h>
#include <pcl/console/print.h>
#include <pcl/exceptions.h>
#include <pcl/io/pcd_io.h>
#include <pcl/point_cloud.h>
#include <pcl/point_types.h>

#include <cstdio>
#include <string>
#include <vector>

#include <unistd.h>

namespace {

void printHelp(const char* name) {
  pcl::console::print_info(
      "Usage: %s <in.off> <out.pcd> [options]\n"
      "Writes points on the mesh's surface as a binary_compressed pcl::PointXYZ PCD.\n"
      "  -n N        number of area-uniform samples (default 8000)\n"
      "  -seed S     random seed; the same seed gives the same points (default 1)\n"
      "  -centroids  one point per face at its centroid instead of random samples\n"
      "  -h          this help\n",
      name);
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

  // Write beside the target and rename: a failed run never leaves a half-written output.
  const std::string tmp_path = out_path + ".tmp" + std::to_string(::getpid());
  bool written = false;
  try {
    written = pcl::io::savePCDFileBinaryCompressed(tmp_path, cloud) == 0 &&
              std::rename(tmp_path.c_str(), out_path.c_str()) == 0;
  } catch (const pcl::IOException&) {
    written = false; // PCL throws when it cannot open the file
  }
  if (!written) {
    std::remove(tmp_path.c_str());
    pcl::console::print_error("%s: cannot write.\n", out_path.c_str());
    return 1;
  }
  pcl::console::print_info("Wrote %zu points to %s\n", cloud.size(), out_path.c_str());
  return 0;
}
