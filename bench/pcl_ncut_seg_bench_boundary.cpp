/*
 * pcl_ncut_seg: what the boundary refinement (setBoundaryBand) costs. Samples a model at N
 * points and, each in a fresh child process (so that the peak memory is its own), segments it
 * with the refinement off and on: the whole extract() (both stages), then a second extract()
 * after a change of the cut's threshold (the cheap stage alone, what a user re-runs), with its
 * HSeg and PSeg columns (PSeg holds the refinement), and the peak memory beyond the input
 * cloud. It prints figures; it is not a test.
 *
 *   pcl_ncut_seg_bench_boundary MODEL.off N [--band F] [--threads T]
 */
#include <pcl_ncut_seg/parameter_table.h>
#include <pcl_ncut_seg/supernode_ncut_segmentation.h>

#include "peak_memory.h"
#include "timing.h"
#include <surfaces/mesh_sampling.h>

#include <cstdio>
#include <cstdlib>
#include <optional>
#include <sstream>
#include <string>
#include <vector>

namespace {
using pcl_ncut_seg_bench::cpuNow;
using pcl_ncut_seg_bench::now;
using pcl_ncut_seg_bench::procStatusBytes;
using pcl_ncut_seg_bench::startPeakMemory;

int runOne(const std::string& path, std::size_t n, std::optional<double> band, int threads) {
  pcl_ncut_seg::TriangleMesh mesh;
  std::string error;
  if (!pcl_ncut_seg::readOff(path, mesh, &error)) {
    std::fprintf(stderr, "cannot read %s: %s\n", path.c_str(), error.c_str());
    return 2;
  }
  const std::vector<float> xyz = pcl_ncut_seg::sampleSurface(mesh, n, 1);
  pcl::PointCloud<pcl::PointXYZ>::Ptr cloud(new pcl::PointCloud<pcl::PointXYZ>);
  cloud->resize(n);
  for (std::size_t i = 0; i < n; ++i)
    (*cloud)[i] = pcl::PointXYZ(xyz[3 * i], xyz[3 * i + 1], xyz[3 * i + 2]);
  const std::size_t base = startPeakMemory();
  pcl::SupernodeNCutSegmentation<pcl::PointXYZ> seg;
  seg.setInputCloud(cloud);
  seg.setNumberOfThreads(static_cast<unsigned>(threads));
  seg.setBoundaryBand(band);
  std::vector<pcl::PointIndices> segments;
  double start = now();
  seg.extract(segments);
  const double first = now() - start;
  const pcl_ncut_seg::PhaseTimes t1 = seg.getPhaseTimes();
  seg.setThreshold(0.09); // a cut parameter: the expensive stage is reused
  start = now();
  const double cpu_start = cpuNow();
  seg.extract(segments);
  const double again = now() - start, again_cpu = cpuNow() - cpu_start;
  const pcl_ncut_seg::PhaseTimes& t2 = seg.getPhaseTimes();
  const std::size_t peak = procStatusBytes("VmHWM");
  std::printf("%.3f %.3f %.3f %.3f %.3f %.4f %.4f %zu %.0f\n", first, t1.refinement, t1.points,
              again, again_cpu, t2.hierarchy, t2.points, segments.size(),
              static_cast<double>(peak > base ? peak - base : 0) / static_cast<double>(n));
  return 0;
}

} // namespace

int main(int argc, char** argv) {
  if (argc == 6 && std::string(argv[1]) == "--run") // the band or "off"
    return runOne(argv[2], std::strtoull(argv[3], nullptr, 10),
                  std::string(argv[4]) == "off" ? std::nullopt
                                                : std::optional<double>(std::atof(argv[4])),
                  std::atoi(argv[5]));
  if (argc < 3) {
    std::fprintf(stderr, "Usage: %s MODEL.off N [--band F] [--threads T]\n", argv[0]);
    return 1;
  }
  pcl_ncut_seg::Parameters params; // the band: the default, or --band's
  int threads = 0;
  for (int i = 3; i + 1 < argc; i += 2) {
    const std::string a = argv[i];
    std::string why;
    if (a == "--band") {
      if (!pcl_ncut_seg::setParameter(params, "boundary_band", argv[i + 1], &why)) {
        std::fprintf(stderr, "--band: %s\n", why.c_str());
        return 1;
      }
    } else if (a == "--threads")
      threads = std::atoi(argv[i + 1]);
    else {
      std::fprintf(stderr, "unknown option %s\n", a.c_str());
      return 1;
    }
  }
  std::printf("%s, %s points; seconds (wall); peak = bytes per point beyond the input cloud\n",
              argv[1], argv[2]);
  std::printf("| band | extract() | LRef | PSeg | cut() again | its CPU time | HSeg | PSeg | t | "
              "peak B/point |\n|---|---|---|---|---|---|---|---|---|---|\n");
  const std::string band = pcl_ncut_seg::parameterValue(params, "boundary_band");
  for (const std::string& b : {std::string("off"), band}) {
    std::ostringstream command;
    command << "'" << argv[0] << "' --run '" << argv[1] << "' " << argv[2] << " " << b << " "
            << threads;
    FILE* pipe = popen(command.str().c_str(), "r");
    if (!pipe)
      return 1;
    char line[512] = {0};
    const bool ok = std::fgets(line, sizeof line, pipe) != nullptr;
    if (pclose(pipe) != 0 || !ok)
      return 1;
    double first, lref, pseg, again, again_cpu, hseg2, pseg2, peak;
    std::size_t t;
    if (std::sscanf(line, "%lf %lf %lf %lf %lf %lf %lf %zu %lf", &first, &lref, &pseg, &again,
                    &again_cpu, &hseg2, &pseg2, &t, &peak) != 9)
      return 1;
    std::printf("| %s | %.3f | %.3f | %.3f | %.3f | %.3f | %.4f | %.4f | %zu | %.0f |\n", b.c_str(),
                first, lref, pseg, again, again_cpu, hseg2, pseg2, t, peak);
  }
  return 0;
}
