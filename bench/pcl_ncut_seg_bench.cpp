/*
 * pcl_ncut_seg_bench: the paper's Table 1 for this implementation.
 *
 * Samples the paper's kinds of models at the paper's sizes (4k-181k points) and beyond (300k,
 * 1M), segments each with the default (Fast) and the Exact centrality, and prints the time of
 * every phase, n, m, l, t and the peak memory beyond the input cloud; then a fitted exponent
 * per phase (time ~ n^a), the speed-up of two threads over one on the centrality, and the time
 * PCL's own part segmenter (supervoxels + LCCP) takes on the same clouds.
 *
 * Each measurement runs in a fresh child process (this program with --run), so that peak
 * memory is its own and one run does not warm the next.
 */
#include <pcl_ncut_seg/supernode_ncut_segmentation.h>

#include "bench_peers.h"
#include "child_run.h"
#include "peak_memory.h"
#include "timing.h"
#include <cli/build_info.h>
#include <surfaces/mesh_sampling.h>

#include <malloc.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <map>
#include <sstream>
#include <string>
#include <vector>

namespace {
using pcl_ncut_seg_bench::loadAverage;
using pcl_ncut_seg_bench::now;
using pcl_ncut_seg_bench::procStatusBytes;
using pcl_ncut_seg_bench::startPeakMemory;

using Cloud = pcl::PointCloud<pcl::PointXYZ>;

/// One row of the table: a model sampled at n points.
struct Row {
  const char* label;
  const char* model; // file in <data>/models
  std::size_t n;
};

// The paper's Table 1 models and sizes (its prism has no counterpart here), then larger clouds.
const std::vector<Row> kFullRows = {{"hand_c", "cgal-hand.off", 4000},
                                    {"horse_c", "horse.off", 4002},
                                    {"bunny_c", "bunny.off", 4088},
                                    {"santa_c", "santa.off", 5002},
                                    {"cube", "cgal-cube-meshed.off", 9602},
                                    {"hand_f", "cgal-hand.off", 30000},
                                    {"bunny_f", "bunny.off", 34834},
                                    {"horse_f", "horse.off", 40002},
                                    {"santa_f", "santa.off", 50002},
                                    {"block", "block.off", 180926},
                                    {"armadillo", "cgal-armadillo.off", 300000},
                                    {"armadillo", "cgal-armadillo.off", 1000000}};
const std::vector<Row> kQuickRows = {{"hand_c", "cgal-hand.off", 4000},
                                     {"santa_f", "santa.off", 50002},
                                     {"block", "block.off", 180926},
                                     {"armadillo", "cgal-armadillo.off", 1000000}};

Cloud::Ptr sampleModel(const std::string& path, std::size_t n, double* diagonal) {
  pcl_ncut_seg::TriangleMesh mesh;
  std::string error;
  if (!pcl_ncut_seg::readOff(path, mesh, &error)) {
    std::fprintf(stderr, "cannot read %s: %s\n", path.c_str(), error.c_str());
    std::exit(2);
  }
  const std::vector<float> xyz = pcl_ncut_seg::sampleSurface(mesh, n, 1);
  Cloud::Ptr cloud(new Cloud);
  cloud->resize(n);
  float lo[3] = {1e30f, 1e30f, 1e30f}, hi[3] = {-1e30f, -1e30f, -1e30f};
  for (std::size_t i = 0; i < n; ++i) {
    (*cloud)[i] = pcl::PointXYZ(xyz[3 * i], xyz[3 * i + 1], xyz[3 * i + 2]);
    for (int c = 0; c < 3; ++c) {
      lo[c] = std::min(lo[c], xyz[3 * i + c]);
      hi[c] = std::max(hi[c], xyz[3 * i + c]);
    }
  }
  *diagonal = std::sqrt((hi[0] - lo[0]) * (hi[0] - lo[0]) + (hi[1] - lo[1]) * (hi[1] - lo[1]) +
                        (hi[2] - lo[2]) * (hi[2] - lo[2]));
  return cloud;
}

/// Child: segment one cloud, print "key=value" pairs on one line.
int runOne(const std::string& path, std::size_t n, const std::string& method, int threads) {
  double diagonal = 1.0;
  Cloud::Ptr cloud = sampleModel(path, n, &diagonal);
  const std::size_t base = startPeakMemory();
  std::ostringstream out;
  if (method == "lccp") {
    // PCL's part segmenter at the settings chosen on the benchmark (results/peer_settings.csv).
    const double start = now();
    const pcl::PointCloud<pcl::PointXYZL>::Ptr labels =
        pcl_ncut_seg_bench::lccpLabels(*cloud, false);
    std::map<std::uint32_t, int> segments;
    for (const auto& p : *labels)
      segments[p.label] = 1;
    out << "total=" << now() - start << " t=" << segments.size();
  } else {
    pcl::SupernodeNCutSegmentation<pcl::PointXYZ> seg;
    seg.setInputCloud(cloud);
    seg.setCentralityMode(method == "exact" ? pcl_ncut_seg::CentralityMode::Exact
                                            : pcl_ncut_seg::CentralityMode::Fast);
    seg.setNumberOfThreads(static_cast<unsigned>(threads));
    std::vector<pcl::PointIndices> segments;
    seg.extract(segments);
    const pcl_ncut_seg::PhaseTimes& t = seg.getPhaseTimes();
    // FNV-1a over the labels: equal hashes for equal segmentations.
    std::uint64_t hash = 1469598103934665603ull;
    const pcl::PointCloud<pcl::PointXYZL>::Ptr labelled = seg.getLabeledCloud();
    for (const auto& p : *labelled)
      hash = (hash ^ p.label) * 1099511628211ull;
    out << "knn=" << t.knn << " cen=" << t.centrality << " snod=" << t.supernodes
        << " lref=" << t.refinement << " hseg=" << t.hierarchy << " pseg=" << t.points
        << " total=" << t.total() << " m=" << seg.getNumberOfSupernodes(false)
        << " l=" << seg.getNumberOfSupernodes(true) << " t=" << segments.size() << " hash=" << hash;
  }
  const std::size_t peak = procStatusBytes("VmHWM");
  out << " peak=" << (peak > base ? peak - base : 0);
  std::printf("%s\n", out.str().c_str());
  return 0;
}

using pcl_ncut_seg_bench::Result;

/// Parent: run a child and parse its line.
bool measure(const std::string& self, const std::string& path, std::size_t n,
             const std::string& method, int threads, Result& result) {
  const std::string command = "'" + self + "' --run '" + path + "' " + std::to_string(n) + " " +
                              method + " " + std::to_string(threads);
  return pcl_ncut_seg_bench::runChild(command, result) && result.count("total") > 0;
}

void printHelp(const char* name) {
  std::printf(
      "Usage: %s [--quick] [--threads N] [--exact-max N] [--no-lccp] [--data DIR]\n"
      "Prints the paper's Table 1 for pcl_ncut_seg (default and exact centrality), fitted\n"
      "exponents per phase, the two-thread speed-up of the centrality and PCL's supervoxels +\n"
      "LCCP on the same clouds. Each run is a fresh process.\n"
      "  --quick        4k, 50k, 181k and 1M points only\n"
      "  --threads N    threads (default 0 = all cores)\n"
      "  --exact-max N  largest cloud run in exact mode (default 300000)\n"
      "  --no-lccp      skip PCL's supervoxels + LCCP\n"
      "  --data DIR     shared data directory with models/ (default %s)\n",
      name, PCL_NCUT_SEG_BENCH_DATA);
}

} // namespace

int main(int argc, char** argv) {
  if (argc == 6 && std::string(argv[1]) == "--run")
    return runOne(argv[2], std::strtoull(argv[3], nullptr, 10), argv[4], std::atoi(argv[5]));

  bool quick = false, lccp = true;
  int threads = 0;
  std::size_t exact_max = 300000;
  std::string data = PCL_NCUT_SEG_BENCH_DATA;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    if (a == "--quick")
      quick = true;
    else if (a == "--no-lccp")
      lccp = false;
    else if (a == "--threads" && i + 1 < argc)
      threads = std::atoi(argv[++i]);
    else if (a == "--exact-max" && i + 1 < argc)
      exact_max = std::strtoull(argv[++i], nullptr, 10);
    else if (a == "--data" && i + 1 < argc)
      data = argv[++i];
    else {
      printHelp(argv[0]);
      return a == "-h" || a == "--help" ? 0 : 1;
    }
  }
  char self_buffer[4096];
  const ssize_t len = readlink("/proc/self/exe", self_buffer, sizeof self_buffer - 1);
  if (len <= 0) {
    std::fprintf(stderr, "cannot find this executable through /proc/self/exe\n");
    return 1;
  }
  const std::string self(self_buffer, static_cast<std::size_t>(len));
  const std::vector<Row>& rows = quick ? kQuickRows : kFullRows;
  const long cores = sysconf(_SC_NPROCESSORS_ONLN);
  std::printf("pcl_ncut_seg benchmark (build %s): %ld cores, threads %d (0 = all), load average "
              "at start %s\n",
              pcl_ncut_seg::buildDescription(), cores, threads, loadAverage().c_str());
  std::printf("Times in seconds (wall); peak = memory beyond the input cloud, MB and bytes per "
              "point.\n");

  std::map<std::string, std::vector<Result>> results; // per method, per row
  for (const std::string method : {"default", "exact"}) {
    std::printf("\nTable 1, %s centrality%s\n", method.c_str(),
                method == "default" ? " (Fast: coarse graph of 20000 representatives)"
                                    : " (Exact: sqrt(n) searches on the full graph)");
    std::printf("%-10s %8s %5s %4s %3s %7s %7s %7s %7s %7s %7s %7s %8s %6s  %s\n", "model", "n",
                "m", "l", "t", "kNN", "Cen", "Snod", "LRef", "HSeg", "PSeg", "total", "peak MB",
                "B/pt", "load");
    for (const Row& row : rows) {
      Result r;
      if (method == "exact" && row.n > exact_max) {
        results[method].push_back(r);
        continue;
      }
      if (!measure(self, data + "/models/" + row.model, row.n, method, threads, r)) {
        std::printf("%-10s %8zu  (run failed)\n", row.label, row.n);
        results[method].push_back(Result());
        continue;
      }
      results[method].push_back(r);
      std::printf("%-10s %8zu %5.0f %4.0f %3.0f %7.3f %7.3f %7.3f %7.3f %7.3f %7.3f %7.3f %8.1f "
                  "%6.0f  %s\n",
                  row.label, row.n, r["m"], r["l"], r["t"], r["knn"], r["cen"], r["snod"],
                  r["lref"], r["hseg"], r["pseg"], r["total"], r["peak"] / 1e6,
                  r["peak"] / static_cast<double>(row.n), loadAverage().c_str());
      std::fflush(stdout);
    }
  }

  std::printf("\nScaling: fitted exponent a of time ~ n^a (rows with time >= 1 ms)\n");
  std::printf("%-8s %6s %6s %6s %6s %6s %6s %6s\n", "mode", "kNN", "Cen", "Snod", "LRef", "HSeg",
              "PSeg", "total");
  for (const std::string method : {"default", "exact"}) {
    std::printf("%-8s", method.c_str());
    for (const char* phase : {"knn", "cen", "snod", "lref", "hseg", "pseg", "total"}) {
      std::vector<std::pair<double, double>> points;
      for (std::size_t i = 0; i < rows.size(); ++i)
        if (results[method][i].count(phase))
          points.emplace_back(static_cast<double>(rows[i].n), results[method][i][phase]);
      int used = 0;
      const double a = pcl_ncut_seg_bench::fitExponent(points, &used);
      if (std::isnan(a))
        std::printf(" %6s", "-");
      else
        std::printf(" %6.2f", a);
    }
    std::printf("\n");
  }

  // Two threads against one on the centrality, on the block (181k points).
  std::printf("\nThreads: centrality phase on one thread and on two, same labels?\n");
  for (const std::string method : {"exact", "default"}) {
    const Row row = method == "exact" ? Row{"block", "block.off", 180926}
                                      : Row{"armadillo", "cgal-armadillo.off", 1000000};
    Result one, two;
    if (measure(self, data + "/models/" + row.model, row.n, method, 1, one) &&
        measure(self, data + "/models/" + row.model, row.n, method, 2, two))
      std::printf("%-8s %-10s %8zu  Cen 1 thread %7.3f  2 threads %7.3f  speed-up %.2fx  "
                  "labels %s  load %s\n",
                  method.c_str(), row.label, row.n, one["cen"], two["cen"], one["cen"] / two["cen"],
                  one["hash"] == two["hash"] ? "identical" : "DIFFER", loadAverage().c_str());
  }

  if (lccp) {
    std::printf("\nPCL supervoxels + LCCP on the same clouds (results/peer_settings.csv's whole "
                "row)\n");
    std::printf("%-10s %8s %8s %6s %10s %10s  %s\n", "model", "n", "LCCP s", "t", "default s",
                "ours/LCCP", "load");
    for (std::size_t i = 0; i < rows.size(); ++i) {
      Result r;
      if (!measure(self, data + "/models/" + rows[i].model, rows[i].n, "lccp", threads, r)) {
        std::printf("%-10s %8zu  (run failed)\n", rows[i].label, rows[i].n);
        continue;
      }
      const double ours =
          results["default"][i].count("total") ? results["default"][i]["total"] : NAN;
      std::printf("%-10s %8zu %8.3f %6.0f %10.3f %10.2f  %s\n", rows[i].label, rows[i].n,
                  r["total"], r["t"], ours, ours / r["total"], loadAverage().c_str());
      std::fflush(stdout);
    }
  }
  return 0;
}
