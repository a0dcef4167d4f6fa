/*
 * pcl_ncut_seg_bench_density: the same surface at several densities. Each of the paper's kind
 * of models in <data>/models is sampled uniformly by area at 10k, 50k, 250k and 1M points (one
 * seed for every size), segmented with the defaults, and printed per size: the wall and CPU
 * time, the segment count, and the Rand index of the size's labels against those of the
 * reference size (50k), carried to each point of the size from its nearest reference point.
 * Skips (exit 0, with a message) when the shared data is absent.
 */
#include <pcl_ncut_seg/parameter_table.h>
#include <pcl_ncut_seg/supernode_ncut_segmentation.h>

#include "eval_sampling.h"
#include "timing.h"
#include <shapes/metrics.h>
#include <surfaces/mesh_sampling.h>

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <map>
#include <set>
#include <string>
#include <vector>

namespace {

namespace fs = std::filesystem;
using Cloud = pcl::PointCloud<pcl::PointXYZ>;

const std::vector<std::string> kModels = {"cgal-hand", "hand-fine",      "horse",        "bunny",
                                          "santa",     "cgal-armadillo", "cgal-elephant"};
const std::vector<std::size_t> kSizes = {10000, 50000, 250000, 1000000};
constexpr std::size_t kReference = 50000;
constexpr std::uint64_t kSeed = 1;

struct Options {
  fs::path data = PCL_NCUT_SEG_BENCH_DATA;
  std::vector<std::string> models = kModels;
  std::vector<std::size_t> sizes = kSizes;
  std::size_t reference = kReference;
  int threads = 1;
  pcl_ncut_seg::Parameters params; ///< the defaults, with --max_points
};

/** Per size, over the models: the Rand index against the reference and the count's change. */
struct SizeStats {
  double ri_sum = 0, wall_sum = 0;
  int models = 0, max_change = 0;
};
using Stats = std::map<std::size_t, SizeStats>;

/** One size's result. */
struct Result {
  std::size_t points = 0;
  std::vector<float> xyz;
  std::vector<int> labels;
  std::size_t segments = 0;
  double wall = 0, cpu = 0;
};

std::vector<std::string> split(const std::string& text) {
  std::vector<std::string> out;
  std::size_t start = 0;
  for (std::size_t comma; (comma = text.find(',', start)) != std::string::npos; start = comma + 1)
    out.push_back(text.substr(start, comma - start));
  out.push_back(text.substr(start));
  return out;
}

int usage(const char* argv0, int code) {
  std::printf(
      "Usage: %s [--models A,B] [--sizes N,M] [--reference N] [--threads T]\n"
      "       [--max_points N|off] [--data DIR]\n"
      "The same surface at several densities: time, segment count and the Rand index\n"
      "against the reference size's labels (carried by nearest point), per size.\n"
      "  --models A,B   OFF files in DIR/models, without .off (default: the paper's kind:\n"
      "                 cgal-hand,hand-fine,horse,bunny,santa,cgal-armadillo,cgal-elephant)\n"
      "  --sizes N,M    area-uniform samples per model (default 10000,50000,250000,1000000)\n"
      "  --reference N  the size the others are compared with (default 50000; added to\n"
      "                 the sizes if missing)\n"
      "  --threads T    the segmenter's threads (default 1)\n"
      "  --max_points N the analysis' resolution (setMaxPoints; default the library's,\n"
      "                 off: every point analysed)\n"
      "  --data DIR     shared data directory with models/ (default %s)\n",
      argv0, PCL_NCUT_SEG_BENCH_DATA);
  return code;
}

/** The options, or an exit code (>= 0) to stop with. */
int parse(int argc, char** argv, Options& o) {
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    const bool has_value = i + 1 < argc;
    if (a == "--models" && has_value)
      o.models = split(argv[++i]);
    else if (a == "--sizes" && has_value) {
      o.sizes.clear();
      for (const auto& s : split(argv[++i]))
        o.sizes.push_back(std::strtoull(s.c_str(), nullptr, 10));
    } else if (a == "--reference" && has_value)
      o.reference = std::strtoull(argv[++i], nullptr, 10);
    else if (a == "--threads" && has_value)
      o.threads = std::atoi(argv[++i]);
    else if (a == "--max_points" && has_value) {
      std::string why;
      if (!pcl_ncut_seg::setParameter(o.params, "max_points", argv[++i], &why))
        return std::fprintf(stderr, "%s\n", why.c_str()), 1;
    } else if (a == "--data" && has_value)
      o.data = argv[++i];
    else
      return usage(argv[0], a == "-h" || a == "--help" ? 0 : 1);
  }
  for (std::size_t s : o.sizes)
    if (s < 100)
      return std::fprintf(stderr, "sizes must be >= 100 points\n"), 1;
  if (o.threads < 0)
    return std::fprintf(stderr, "--threads must be >= 0\n"), 1;
  if (std::find(o.sizes.begin(), o.sizes.end(), o.reference) == o.sizes.end())
    o.sizes.push_back(o.reference);
  std::sort(o.sizes.begin(), o.sizes.end());
  return -1;
}

Result segmentAt(const pcl_ncut_seg::TriangleMesh& mesh, std::size_t n, const Options& o) {
  Result r;
  r.points = n;
  r.xyz = pcl_ncut_seg::sampleSurface(mesh, n, kSeed);
  Cloud::Ptr cloud(new Cloud);
  cloud->resize(n);
  for (std::size_t i = 0; i < n; ++i)
    (*cloud)[i] = pcl::PointXYZ(r.xyz[3 * i], r.xyz[3 * i + 1], r.xyz[3 * i + 2]);
  const double wall = pcl_ncut_seg_bench::now(), cpu = pcl_ncut_seg_bench::cpuNow();
  pcl::SupernodeNCutSegmentation<pcl::PointXYZ> seg;
  seg.setInputCloud(cloud);
  pcl_ncut_seg::Parameters p = o.params;
  p.execution.num_threads = o.threads;
  seg.setParameters(p);
  std::vector<pcl::PointIndices> segments;
  seg.extract(segments);
  r.wall = pcl_ncut_seg_bench::now() - wall;
  r.cpu = pcl_ncut_seg_bench::cpuNow() - cpu;
  r.labels = pcl_ncut_seg::test::segmentsToLabels(segments, n);
  r.segments = std::set<int>(r.labels.begin(), r.labels.end()).size();
  return r;
}

/** The Rand index over r's points between its labels and the reference's, carried from the
 * reference's nearest point. */
double randIndexAgainst(const Result& r, const Result& reference) {
  if (&r == &reference)
    return 1.0;
  const auto nearest = pcl_ncut_seg::eval::nearestPoints(reference.xyz, r.xyz);
  return pcl_ncut_seg::test::randIndex(r.labels,
                                       pcl_ncut_seg::eval::faceLabels(reference.labels, nearest));
}

/** One model at every size: a line per size; false if it could not be read. */
bool benchModel(const Options& o, const std::string& name, Stats& stats) {
  pcl_ncut_seg::TriangleMesh mesh;
  std::string error;
  if (!pcl_ncut_seg::readOff((o.data / "models" / (name + ".off")).string(), mesh, &error)) {
    std::fprintf(stderr, "%s\n", error.c_str());
    return false;
  }
  std::vector<Result> results;
  for (std::size_t n : o.sizes) {
    results.push_back(segmentAt(mesh, n, o));
    std::fflush(stdout);
  }
  const auto ref = std::find_if(results.begin(), results.end(),
                                [&](const Result& r) { return r.points == o.reference; });
  for (const Result& r : results) {
    const double ri = randIndexAgainst(r, *ref);
    const int change = static_cast<int>(r.segments) - static_cast<int>(ref->segments);
    SizeStats& s = stats[r.points];
    s.ri_sum += ri;
    s.wall_sum += r.wall;
    s.max_change = std::max(s.max_change, std::abs(change));
    ++s.models;
    std::printf("%-15s %8zu %9.2f %9.2f %5zu %+5d %8.3f\n", name.c_str(), r.points, r.wall, r.cpu,
                r.segments, change, ri);
  }
  return true;
}

} // namespace

int main(int argc, char** argv) {
  Options o;
  if (const int code = parse(argc, argv, o); code >= 0)
    return code;
  if (!fs::is_directory(o.data / "models")) {
    std::printf("skipped: no %s (the shared data is absent; --data DIR points to it)\n",
                (o.data / "models").c_str());
    return 0;
  }
  std::printf("load %s, %d thread(s); reference %zu points; seed %llu; max_points %s\n",
              pcl_ncut_seg_bench::loadAverage().c_str(), o.threads, o.reference,
              static_cast<unsigned long long>(kSeed),
              pcl_ncut_seg::parameterValue(o.params, "max_points").c_str());
  std::printf("%-15s %8s %9s %9s %5s %5s %8s\n", "model", "points", "wall s", "cpu s", "segs",
              "d ref", "RI ref");
  Stats stats;
  for (const auto& name : o.models)
    if (!benchModel(o, name, stats))
      return 1;
  std::printf("\nper size over the models: mean wall s, mean Rand index against %zu points, "
              "largest change of the count\n",
              o.reference);
  double ri_sum = 0;
  int ri_count = 0;
  for (const auto& [size, s] : stats) {
    std::printf("%8zu %9.2f %8.3f %5d\n", size, s.wall_sum / s.models, s.ri_sum / s.models,
                s.max_change);
    if (size != o.reference) {
      ri_sum += s.ri_sum;
      ri_count += s.models;
    }
  }
  if (ri_count > 0)
    std::printf("mean Rand index against %zu points over the other sizes: %.3f (%d runs)\n",
                o.reference, ri_sum / ri_count, ri_count);
  return 0;
}
