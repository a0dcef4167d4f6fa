/*
 * pcl_ncut_seg_bench_sizes: what a user waits for, file to file, with ours and with PCL's
 * supervoxels + LCCP on the same clouds at four sizes, in one run.
 *
 * The clouds, written as binary PCD files into a temporary directory (removed at exit):
 *  1. a depth camera's view of the bunny alone, about 20,000 valid points: the unorganized crop
 *     of pcl_ncut_seg_bench_views' "(a) bunny alone", sensor origin kept;
 *  2.-4. <data>/models/hand-fine.off sampled uniformly by area at 181,000, 1,000,000 and
 *     10,000,000 points (the last skipped with --quick).
 * Each measurement is a fresh child process (this program with --run) that reads the PCD,
 * segments it and writes the labelled cloud as a binary PCD: "whole" is that wall time, and the
 * child's peak resident memory is the whole process's (libraries included), as a user's program
 * would see it. Ours: the defaults on all cores. LCCP: at the settings chosen on the benchmark
 * (results/peer_settings.csv) for views on the view (normals towards the sensor) and for whole
 * objects on the hand (eval/psb_peers.h).
 */
#include <pcl_ncut_seg/supernode_ncut_segmentation.h>

#include "bench_peers.h"
#include "child_run.h"
#include "peak_memory.h"
#include "psb_peers.h"
#include "timing.h"
#include <cli/build_info.h>
#include <files/point_file.h>
#include <surfaces/depth_view_pcl.h>
#include <surfaces/mesh_sampling.h>

#include <pcl/console/print.h>
#include <pcl/io/pcd_io.h>

#include <malloc.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <csignal>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <limits>
#include <map>
#include <set>
#include <sstream>
#include <string>
#include <vector>

namespace {
using pcl_ncut_seg_bench::loadAverage;
using pcl_ncut_seg_bench::now;
using pcl_ncut_seg_bench::procStatusBytes;

using Cloud = pcl::PointCloud<pcl::PointXYZ>;
using Labelled = pcl::PointCloud<pcl::PointXYZL>;

/// One cloud of the table.
struct Size {
  const char* label;
  bool view;     ///< the bunny's depth view (n: about that many points), else the hand
  std::size_t n; ///< points sampled on hand-fine.off
};
const std::vector<Size> kSizes = {{"bunny view", true, 20000},
                                  {"hand 181k", false, 181000},
                                  {"hand 1M", false, 1000000},
                                  {"hand 10M", false, 10000000}};
constexpr std::size_t kOneRunFrom = 10000000; // clouds this large run once (tens of seconds)

/// LCCP on the view at the chosen settings for views, normals towards the sensor (the PCD's
/// VIEWPOINT).
Labelled::Ptr lccpView(const Cloud& cloud) {
  const Eigen::Vector4f& o = cloud.sensor_origin_;
  return pcl_ncut_seg_bench::lccpLabels(cloud, true, std::array<float, 3>{{o[0], o[1], o[2]}});
}

/// LCCP on a whole model at the chosen settings for whole objects.
Labelled::Ptr lccpModel(const Cloud::Ptr& cloud) {
  return pcl_ncut_seg_bench::lccpLabels(*cloud, false);
}

/// Child: read `in`, segment it with `method`, write the labelled cloud to `out`; print
/// "key=value" pairs on one line.
int runOne(const std::string& in, const std::string& out, const std::string& method, bool view,
           unsigned threads) {
  pcl::console::setVerbosityLevel(pcl::console::L_ERROR);
  // The memory policy of the pcl_ncut_seg tool, for both methods: freed memory is kept for
  // the next stage rather than faulted in again.
  mallopt(M_MMAP_THRESHOLD, 32 << 20);
  mallopt(M_TRIM_THRESHOLD, std::numeric_limits<int>::max());
  const std::size_t base = procStatusBytes("VmRSS"); // the program and its libraries
  std::ostringstream line;
  const double start = now();
  // Ours reads as the pcl_ncut_seg tool does (the project's reader, kit/files), LCCP as a PCL
  // user does.
  Cloud::Ptr cloud(new Cloud);
  pcl_ncut_seg::files::PointFile file;
  std::string error;
  if (method == "ours" ? !pcl_ncut_seg::files::readPointFile(in, {}, file, error)
                       : pcl::io::loadPCDFile(in, *cloud) != 0)
    return 2;
  if (method == "ours") {
    cloud = file.cloud;
    file.blob = pcl::PCLPointCloud2(); // the tool keeps it for -add; this child never writes it
  }
  const double read = now();
  Labelled::Ptr labelled;
  std::size_t segments = 0;
  if (method == "ours") {
    pcl::SupernodeNCutSegmentation<pcl::PointXYZ> seg;
    seg.setInputCloud(cloud);
    seg.setNumberOfThreads(threads);
    std::vector<pcl::PointIndices> parts;
    seg.extract(parts);
    labelled = seg.getLabeledCloud();
    segments = parts.size();
    const pcl_ncut_seg::PhaseTimes& t = seg.getPhaseTimes();
    line << "knn=" << t.knn << " cen=" << t.centrality << " snod=" << t.supernodes
         << " lref=" << t.refinement << " hseg=" << t.hierarchy << " pseg=" << t.points << " ";
  } else {
    labelled = view ? lccpView(*cloud) : lccpModel(cloud);
  }
  const double segmented = now();
  if (!labelled || labelled->empty() || pcl::io::savePCDFileBinary(out, *labelled) != 0)
    return 2;
  const double written = now();
  const std::size_t peak = procStatusBytes("VmHWM");
  if (method != "ours") { // distinct segments, counted after the clock stopped
    std::set<std::uint32_t> distinct;
    for (const auto& p : *labelled)
      if (p.label != 0)
        distinct.insert(p.label);
    segments = distinct.size();
  }
  line << "read=" << read - start << " seg=" << segmented - read << " write=" << written - segmented
       << " whole=" << written - start << " peak=" << peak << " base=" << base << " t=" << segments;
  std::printf("%s\n", line.str().c_str());
  return 0;
}

using pcl_ncut_seg_bench::Result;

/// The command that runs one child (runOne) on `in`, writing `out`.
std::string childCommand(const std::string& self, const std::string& in, const std::string& out,
                         const std::string& method, bool view, unsigned threads) {
  return "'" + self + "' --run '" + in + "' '" + out + "' " + method + " " +
         (view ? "view" : "model") + " " + std::to_string(threads);
}

/// Parent: run a child on `in` and parse its line; the child's output file is removed.
bool measure(const std::string& self, const std::string& in, const std::string& out,
             const std::string& method, bool view, unsigned threads, Result& result) {
  const bool ran =
      pcl_ncut_seg_bench::runChild(childCommand(self, in, out, method, view, threads), result);
  std::filesystem::remove(out);
  return ran && result.count("whole") > 0;
}

std::string g_dir;                     // the temporary directory, removed at exit
volatile std::sig_atomic_t g_stop = 0; // Ctrl-C: stop after the current child, clean up

/// Parent: run `count` children at once on `in`, each with its own output file; the wall time
/// from the first start to the last exit, NaN when any failed.
double measureAtOnce(const std::string& self, const std::string& in, const std::string& dir,
                     int count, unsigned threads) {
  const double start = now();
  std::vector<FILE*> pipes;
  for (int i = 0; i < count; ++i) {
    const std::string out = dir + "/busy" + std::to_string(i) + ".pcd";
    pipes.push_back(popen(childCommand(self, in, out, "ours", false, threads).c_str(), "r"));
  }
  bool ok = true;
  for (int i = 0; i < count; ++i) {
    if (!pipes[i]) {
      ok = false;
      continue;
    }
    std::string line;
    char buffer[1024];
    while (std::fgets(buffer, sizeof buffer, pipes[i]))
      line += buffer;
    Result one;
    pcl_ncut_seg_bench::parseFields(line, one);
    ok = pclose(pipes[i]) == 0 && one.count("whole") > 0 && ok;
  }
  const double wall = now() - start;
  for (int i = 0; i < count; ++i)
    std::filesystem::remove(dir + "/busy" + std::to_string(i) + ".pcd");
  return ok ? wall : NAN;
}

/// A busy machine: 1, 2 and 4 segmenters at once on the same cloud, each on the free cores
/// (--threads 0), on every core whatever the load, and on one thread. Prints each setting's
/// median wall time over the rounds, from the first start to the last exit.
void busyMachine(const std::string& self, const std::string& in, long cores, int runs) {
  std::printf("\nA busy machine: P processes segment the hand's 181k points at once; wall time "
              "until the last ends, s\n%-9s %12s %12s %12s %14s\n",
              "processes", "free cores", "all cores", "one thread", "free/one");
  for (const int count : {1, 2, 4}) {
    std::printf("%-9d", count);
    double median[3] = {NAN, NAN, NAN};
    int column = 0;
    for (const unsigned threads : {0u, static_cast<unsigned>(cores), 1u}) {
      std::vector<double> walls;
      for (int r = 0; r < runs && !g_stop; ++r) {
        const double wall = measureAtOnce(self, in, g_dir, count, threads);
        if (!std::isnan(wall))
          walls.push_back(wall);
      }
      if (!walls.empty()) {
        std::sort(walls.begin(), walls.end());
        median[column] = walls[walls.size() / 2];
      }
      std::printf(" %12.3f", median[column++]);
    }
    std::printf(" %14.2f\n", median[0] / median[2]);
    std::fflush(stdout);
  }
}

/// Writes the cloud of `size` to `path` as a binary PCD (untimed); returns its points, 0 on
/// failure.
std::size_t writeCloud(const Size& size, const pcl_ncut_seg::TriangleMesh& bunny,
                       const pcl_ncut_seg::TriangleMesh& hand, const std::string& path) {
  Cloud cloud;
  if (size.view) { // the view's valid points: the crop a tabletop pipeline hands over
    const Cloud::Ptr frame =
        pcl_ncut_seg::toPclCloud(pcl_ncut_seg_bench::objectView(bunny, size.n));
    for (const auto& p : *frame)
      if (std::isfinite(p.x))
        cloud.push_back(p);
    cloud.sensor_origin_ = frame->sensor_origin_;
    cloud.sensor_orientation_ = frame->sensor_orientation_;
  } else { // as pcl_ncut_seg_bench samples its models (seed 1)
    const std::vector<float> xyz = pcl_ncut_seg::sampleSurface(hand, size.n, 1);
    cloud.resize(xyz.size() / 3);
    for (std::size_t i = 0; i < cloud.size(); ++i)
      cloud[i] = pcl::PointXYZ(xyz[3 * i], xyz[3 * i + 1], xyz[3 * i + 2]);
  }
  if (cloud.empty() || pcl::io::savePCDFileBinary(path, cloud) != 0)
    return 0;
  return cloud.size();
}

void removeDir() {
  if (!g_dir.empty())
    std::filesystem::remove_all(g_dir);
}
void onSignal(int) {
  g_stop = 1;
}

bool loadMesh(const std::string& path, pcl_ncut_seg::TriangleMesh& mesh) {
  std::string error;
  return std::ifstream(path) && pcl_ncut_seg::readOff(path, mesh, &error);
}

void printHelp(const char* name) {
  std::printf(
      "Usage: %s [--quick] [--runs R] [--threads N] [--data DIR]\n"
      "Times ours and PCL's supervoxels + LCCP from a binary PCD to a labelled binary\n"
      "PCD (read, segment, write) on a 20k-point depth view and on hand-fine.off\n"
      "sampled at 181k, 1M and 10M points; each run is a fresh process.\n"
      "  --quick      skip the 10M cloud\n"
      "  --runs R     runs per cloud and method, the median is shown (default 3; 1 at 10M)\n"
      "  --threads N  ours' threads (default 0 = all cores; LCCP is serial)\n"
      "  --data DIR   shared data directory with models/ (default %s)\n",
      name, PCL_NCUT_SEG_BENCH_DATA);
}

} // namespace

int main(int argc, char** argv) {
  if (argc == 7 && std::string(argv[1]) == "--run")
    return runOne(argv[2], argv[3], argv[4], std::string(argv[5]) == "view",
                  static_cast<unsigned>(std::strtoul(argv[6], nullptr, 10)));

  bool quick = false;
  int runs = 3;
  unsigned threads = 0;
  std::string data = PCL_NCUT_SEG_BENCH_DATA;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    if (a == "--quick")
      quick = true;
    else if (a == "--runs" && i + 1 < argc)
      runs = std::max(1, std::atoi(argv[++i]));
    else if (a == "--threads" && i + 1 < argc)
      threads = static_cast<unsigned>(std::strtoul(argv[++i], nullptr, 10));
    else if (a == "--data" && i + 1 < argc)
      data = argv[++i];
    else {
      printHelp(argv[0]);
      return a == "-h" || a == "--help" ? 0 : 1;
    }
  }
  pcl_ncut_seg::TriangleMesh bunny, hand;
  const std::pair<const char*, pcl_ncut_seg::TriangleMesh*> meshes[] = {{"bunny.off", &bunny},
                                                                        {"hand-fine.off", &hand}};
  for (const auto& [name, mesh] : meshes)
    if (!loadMesh(data + "/models/" + name, *mesh)) {
      std::printf("skipped: %s/models/%s not found or unreadable (pass --data DIR)\n", data.c_str(),
                  name);
      return 0;
    }
  char self_buffer[4096];
  const ssize_t len = readlink("/proc/self/exe", self_buffer, sizeof self_buffer - 1);
  if (len <= 0) {
    std::fprintf(stderr, "cannot find this executable through /proc/self/exe\n");
    return 1;
  }
  const std::string self(self_buffer, static_cast<std::size_t>(len));
  std::string dir_template =
      (std::filesystem::temp_directory_path() / "pcl_ncut_seg_bench_sizes.XXXXXX").string();
  if (!mkdtemp(dir_template.data())) {
    std::perror("mkdtemp");
    return 1;
  }
  g_dir = dir_template;
  std::atexit(removeDir);
  std::signal(SIGINT, onSignal); // the child dies of it; we then stop and remove g_dir
  std::signal(SIGTERM, onSignal);

  const long cores = sysconf(_SC_NPROCESSORS_ONLN);
  const std::string ours_threads = threads == 0 ? "all " + std::to_string(cores) + " cores"
                                                : std::to_string(threads) + " threads";
  std::printf("pcl_ncut_seg_bench_sizes (build %s): %ld cores, ours on %s (--threads %u), LCCP "
              "on one; load average at start %s\n",
              pcl_ncut_seg::buildDescription(), cores, ours_threads.c_str(), threads,
              loadAverage().c_str());
  std::printf("%-10s %8s %-4s %6s %6s %6s %6s %6s %6s %6s %7s %6s %7s %7s %5s %4s %4s\n", "cloud",
              "n", "", "read", "kNN", "Cen", "Snod", "LRef", "HSeg", "PSeg", "segment", "write",
              "whole", "peak MB", "B/pt", "segs", "runs");
  struct Done {
    const Size* size;
    std::size_t n;
    Result ours, lccp;
  };
  std::vector<Done> done;
  double base = 0;
  for (const Size& size : kSizes) {
    if (g_stop || (quick && size.n >= kOneRunFrom))
      break;
    const std::string in = g_dir + "/cloud.pcd", out = g_dir + "/labelled.pcd";
    Done d{&size, writeCloud(size, bunny, hand, in), {}, {}};
    malloc_trim(0); // the sampled cloud is gone: do not hold its pages while the children run
    if (d.n == 0) {
      std::printf("%-10s (cannot write %s)\n", size.label, in.c_str());
      continue;
    }
    const int r = size.n >= kOneRunFrom ? 1 : runs;
    for (const std::string method : {"ours", "lccp"}) {
      std::vector<Result> all;
      for (int i = 0; i < r && !g_stop; ++i) {
        Result one;
        if (measure(self, in, out, method, size.view, threads, one))
          all.push_back(one);
      }
      if (all.empty()) {
        std::printf("%-10s %8zu %-4s (%s)\n", size.label, d.n, method == "ours" ? "ours" : "LCCP",
                    g_stop ? "stopped" : "run failed");
        continue;
      }
      // The run of median whole time, all its figures: one run may be slowed by a cold start
      // or by the machine's other load.
      std::sort(all.begin(), all.end(),
                [](const Result& a, const Result& b) { return a.at("whole") < b.at("whole"); });
      Result m = all[all.size() / 2];
      base = std::max(base, m["base"]);
      (method == "ours" ? d.ours : d.lccp) = m;
      const bool ours = method == "ours";
      char phases[64] = "";
      if (ours)
        std::snprintf(phases, sizeof phases, "%6.3f %6.3f %6.3f %6.3f %6.3f %6.3f", m["knn"],
                      m["cen"], m["snod"], m["lref"], m["hseg"], m["pseg"]);
      else
        std::snprintf(phases, sizeof phases, "%6s %6s %6s %6s %6s %6s", "-", "-", "-", "-", "-",
                      "-");
      std::printf("%-10s %8zu %-4s %6.3f %s %7.3f %6.3f %7.3f %7.1f %5.0f %4.0f %4zu\n",
                  ours ? size.label : "", d.n, ours ? "ours" : "LCCP", m["read"], phases, m["seg"],
                  m["write"], m["whole"], m["peak"] / 1e6, m["peak"] / static_cast<double>(d.n),
                  m["t"], all.size());
      std::fflush(stdout);
    }
    std::filesystem::remove(in);
    done.push_back(d);
  }

  // Over every size run, and over the hand's alone: one surface at several densities (the view
  // is another surface, so it bends the fit).
  std::printf("\nWhole time ~ n^a, least squares on logs: over the %zu sizes run, and over the "
              "hand's alone\n",
              done.size());
  for (const std::string method : {"ours", "lccp"}) {
    std::vector<std::pair<double, double>> all, hand;
    for (const Done& d : done) {
      const Result& r = method == "ours" ? d.ours : d.lccp;
      if (!r.count("whole"))
        continue;
      all.emplace_back(static_cast<double>(d.n), r.at("whole"));
      if (!d.size->view)
        hand.emplace_back(static_cast<double>(d.n), r.at("whole"));
    }
    std::printf("  %-4s", method == "ours" ? "ours" : "LCCP");
    for (const auto* points : {&all, &hand}) {
      const double a = pcl_ncut_seg_bench::fitExponent(*points);
      char text[16] = "-";
      if (!std::isnan(a))
        std::snprintf(text, sizeof text, "%.2f", a);
      std::printf("  a = %5s (%zu sizes)", text, points->size());
    }
    std::printf("\n");
  }
  std::printf("Ours / LCCP per size:\n%-10s %8s %7s %7s\n", "cloud", "n", "whole", "peak");
  for (Done& d : done)
    if (d.ours.count("whole") && d.lccp.count("whole"))
      std::printf("%-10s %8zu %7.2f %7.2f\n", d.size->label, d.n, d.ours["whole"] / d.lccp["whole"],
                  d.ours["peak"] / d.lccp["peak"]);
  std::printf(
      "\nSeconds, wall, in a fresh child process per run: read = the binary PCD (just written,\n"
      "so from the page cache) read by the tool's reader (files::readPointFile) for ours, by\n"
      "pcl::io::loadPCDFile for LCCP; segment = ours' extract() and\n"
      "getLabeledCloud() (its phases, Table 1's, before it), or LCCP's normals (the view only),\n"
      "supervoxels, LCCP and relabelling; write = pcl::io::savePCDFileBinary of x y z label;\n"
      "whole = read + segment + write (the process's start, loading its libraries, not counted).\n"
      "peak = the child's peak resident memory (VmHWM), the whole process's: %.0f MB of it is\n"
      "the program and its libraries before reading. B/pt = peak / n. segs: segments (LCCP:\n"
      "distinct labels). Each row: the run of median whole time among %d (1 at 10M points).\n"
      "Both keep freed memory for reuse, as the pcl_ncut_seg tool does (mallopt).\n"
      "Load average at the end %s.\n",
      base / 1e6, runs, loadAverage().c_str());
  const std::string in = g_dir + "/busy.pcd";
  if (!g_stop && writeCloud(kSizes[1], bunny, hand, in) > 0) {
    busyMachine(self, in, cores, runs);
    std::printf("Each process as in the table above (read, segment, write), all P started at\n"
                "once; the median of %d rounds. free cores: --threads 0, the processors less the\n"
                "other processes' running threads when each phase starts; all cores: --threads\n"
                "%ld, the count of an idle machine whatever the load. free/one at most 1: the\n"
                "library makes a loaded machine no slower than one thread each would.\n",
                runs, cores);
    std::filesystem::remove(in);
  }
  return g_stop ? 1 : 0;
}
