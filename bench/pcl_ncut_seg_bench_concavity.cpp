/*
 * pcl_ncut_seg: times the concave-crease step (core/cut/concavity.h) on its own: oriented normals
 * and the contact concavity of the supernodes, on a model sampled at a given size, with the
 * peak memory the step adds. With --dump FILE it writes its results, and with --compare FILE it
 * compares them with such a file (written by another build), so that two implementations can be
 * checked against each other. It prints figures; it is not a test.
 *
 *   pcl_ncut_seg_bench_concavity MODEL.off N [--threads T] [--repeat R] [--dump F] [--compare F]
 */
#include "core/cut/concavity.h"
#include "core/graph/csr_graph.h"
#include "core/pipeline/analysis_stages.h"
#include "core/pipeline/pipeline.h"

#include "peak_memory.h"
#include "timing.h"
#include <surfaces/mesh_sampling.h>

#include <pcl/kdtree/kdtree_flann.h>
#include <pcl/point_types.h>

#include <malloc.h>
#ifdef _OPENMP
#include <omp.h>
#endif

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <numeric>
#include <string>

namespace {
using pcl_ncut_seg_bench::cpuNow;
using pcl_ncut_seg_bench::now;
using pcl_ncut_seg_bench::procStatusBytes;
using pcl_ncut_seg_bench::startPeakMemory;

/// Points in Morton order, as the segmenter orders them.
void mortonSort(std::vector<float>& xyz) {
  const std::size_t n = xyz.size() / 3;
  float lo[3] = {1e30f, 1e30f, 1e30f}, hi[3] = {-1e30f, -1e30f, -1e30f};
  for (std::size_t i = 0; i < n; ++i)
    for (int c = 0; c < 3; ++c) {
      lo[c] = std::min(lo[c], xyz[3 * i + c]);
      hi[c] = std::max(hi[c], xyz[3 * i + c]);
    }
  const float extent = std::max({hi[0] - lo[0], hi[1] - lo[1], hi[2] - lo[2], 1e-30f});
  std::vector<std::pair<std::uint64_t, std::uint32_t>> code(n);
  for (std::size_t i = 0; i < n; ++i) {
    std::uint64_t m = 0;
    std::uint32_t q[3];
    for (int c = 0; c < 3; ++c)
      q[c] = static_cast<std::uint32_t>((xyz[3 * i + c] - lo[c]) / extent * 2097151.0f);
    for (int b = 20; b >= 0; --b)
      for (int c = 0; c < 3; ++c)
        m = (m << 1) | ((q[c] >> b) & 1u);
    code[i] = {m, static_cast<std::uint32_t>(i)};
  }
  std::sort(code.begin(), code.end());
  std::vector<float> out(3 * n);
  for (std::size_t i = 0; i < n; ++i)
    std::copy_n(&xyz[3 * code[i].second], 3, &out[3 * i]);
  xyz.swap(out);
}

} // namespace

int main(int argc, char** argv) {
  if (argc < 3) {
    std::fprintf(stderr,
                 "Usage: %s MODEL.off N [--threads T] [--repeat R] [--dump F] "
                 "[--compare F]\n",
                 argv[0]);
    return 2;
  }
  const std::string path = argv[1];
  const std::size_t n = std::strtoull(argv[2], nullptr, 10);
  int threads = 0, repeat = 3;
  std::string dump, compare;
  for (int i = 3; i + 1 < argc; i += 2) {
    const std::string opt = argv[i];
    if (opt == "--threads")
      threads = std::atoi(argv[i + 1]);
    else if (opt == "--repeat")
      repeat = std::max(1, std::atoi(argv[i + 1]));
    else if (opt == "--dump")
      dump = argv[i + 1];
    else if (opt == "--compare")
      compare = argv[i + 1];
  }
#ifdef _OPENMP
  if (threads > 0)
    omp_set_num_threads(threads);
#endif
  pcl_ncut_seg::TriangleMesh mesh;
  std::string error;
  if (!pcl_ncut_seg::readOff(path, mesh, &error)) {
    std::fprintf(stderr, "cannot read %s: %s\n", path.c_str(), error.c_str());
    return 2;
  }
  std::vector<float> xyz = pcl_ncut_seg::sampleSurface(mesh, n, 1);
  mortonSort(xyz);
  pcl::PointCloud<pcl::PointXYZ>::Ptr cloud(new pcl::PointCloud<pcl::PointXYZ>);
  cloud->resize(n);
  for (std::size_t i = 0; i < n; ++i)
    (*cloud)[i] = pcl::PointXYZ(xyz[3 * i], xyz[3 * i + 1], xyz[3 * i + 2]);
  const std::size_t k = 10;
  std::vector<std::uint32_t> knn(n * k, static_cast<std::uint32_t>(n));
  {
    pcl::KdTreeFLANN<pcl::PointXYZ> tree;
    tree.setInputCloud(cloud);
#pragma omp parallel
    {
      pcl::Indices idx;
      std::vector<float> d2;
#pragma omp for schedule(static)
      for (std::int64_t p = 0; p < static_cast<std::int64_t>(n); ++p) {
        tree.nearestKSearch((*cloud)[p], static_cast<int>(k + 1), idx, d2);
        std::size_t j = 0;
        for (const auto q : idx)
          if (q != p && j < k)
            knn[p * k + j++] = static_cast<std::uint32_t>(q);
      }
    }
  }
  cloud.reset();
  pcl_ncut_seg::CsrGraph graph = pcl_ncut_seg::buildSymmetricKnnGraph(xyz.data(), n, knn.data(), k);
  std::vector<std::uint32_t>().swap(knn);
  pcl_ncut_seg::PhaseTimes times;
  pcl_ncut_seg::Parameters params;
  params.execution.num_threads = static_cast<unsigned>(std::max(threads, 0));
  std::vector<pcl_ncut_seg::Centrality> f =
      pcl_ncut_seg::centralityStage(graph, params, nullptr, times, nullptr);
  const pcl_ncut_seg::Analysis analysis =
      pcl_ncut_seg::featureStages(std::move(graph), std::move(f[0]), params, times, nullptr);
  const auto& label = analysis.supernodes.label;

  const std::size_t base = startPeakMemory();
  double t_normals = 1e30, t_contact = 1e30, cpu_normals = 1e30, cpu_contact = 1e30;
  std::vector<float> normals;
  pcl_ncut_seg::Connectivity concavity;
  for (int r = 0; r < repeat; ++r) {
    std::vector<float>().swap(normals);
    const double t0 = now(), c0 = cpuNow();
    normals = pcl_ncut_seg::orientedNormals(*analysis.graph, xyz.data());
    const double t1 = now(), c1 = cpuNow();
    concavity = pcl_ncut_seg::contactConcavity(*analysis.graph, xyz.data(), normals, label);
    const double t2 = now(), c2 = cpuNow();
    t_normals = std::min(t_normals, t1 - t0);
    t_contact = std::min(t_contact, t2 - t1);
    cpu_normals = std::min(cpu_normals, c1 - c0);
    cpu_contact = std::min(cpu_contact, c2 - c1);
  }
  const std::size_t peak = procStatusBytes("VmHWM");
  std::printf("n=%zu edges=%zu supernodes=%zu contacts=%zu\n", n,
              analysis.graph->numDirectedEdges() / 2, analysis.supernodes.size(), concavity.size());
  std::printf("wall: orientedNormals %.4f s, contactConcavity %.4f s, total %.4f s; cpu: %.4f s, "
              "%.4f s, total %.4f s (best of %d); peak beyond the start %.1f B/pt\n",
              t_normals, t_contact, t_normals + t_contact, cpu_normals, cpu_contact,
              cpu_normals + cpu_contact, repeat,
              static_cast<double>(peak > base ? peak - base : 0) / static_cast<double>(n));

  if (!dump.empty()) {
    std::ofstream out(dump, std::ios::binary);
    out.write(reinterpret_cast<const char*>(normals.data()),
              static_cast<std::streamsize>(normals.size() * sizeof(float)));
    for (const auto& [key, c] : concavity) {
      out.write(reinterpret_cast<const char*>(&key.first), 4);
      out.write(reinterpret_cast<const char*>(&key.second), 4);
      out.write(reinterpret_cast<const char*>(&c), 8);
    }
  }
  if (!compare.empty()) {
    std::ifstream in(compare, std::ios::binary);
    std::vector<float> other(normals.size());
    in.read(reinterpret_cast<char*>(other.data()),
            static_cast<std::streamsize>(other.size() * sizeof(float)));
    pcl_ncut_seg::Connectivity other_c;
    std::uint32_t a, b;
    double c;
    while (in.read(reinterpret_cast<char*>(&a), 4) && in.read(reinterpret_cast<char*>(&b), 4) &&
           in.read(reinterpret_cast<char*>(&c), 8))
      other_c[{a, b}] = c;
    std::size_t both = 0, same = 0, bad_fit = 0;
    for (std::size_t p = 0; p < n; ++p) {
      const float* u = &normals[3 * p];
      const float* v = &other[3 * p];
      const float d = u[0] * v[0] + u[1] * v[1] + u[2] * v[2];
      if (d == 0.0f)
        continue;
      ++both;
      same += d > 0.0f;
      bad_fit += std::abs(d) < 0.999f;
    }
    double max_diff = 0.0, sum_diff = 0.0;
    std::size_t missing = 0;
    for (const auto& [key, v] : concavity) {
      const auto it = other_c.find(key);
      if (it == other_c.end()) {
        ++missing;
        continue;
      }
      max_diff = std::max(max_diff, std::abs(v - it->second));
      sum_diff += std::abs(v - it->second);
    }
    std::printf(
        "compare: normals in both %zu, same orientation %.4f%%, |cos| < 0.999: %zu; "
        "contacts %zu vs %zu (missing %zu), concavity mean |diff| %.4g, max %.4g\n",
        both,
        100.0 * static_cast<double>(same) / static_cast<double>(std::max<std::size_t>(both, 1)),
        bad_fit, concavity.size(), other_c.size(), missing,
        sum_diff / static_cast<double>(std::max<std::size_t>(concavity.size(), 1)), max_diff);
  }
  return 0;
}
