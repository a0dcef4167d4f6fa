/*
 * pcl_ncut_seg_bench_exact: the Exact centrality (Sec. 4.1, eq. 1) alone, on one sampled model.
 *
 * Builds the kNN graph as the PCL front end does (points in Morton order, k = 10, symmetric),
 * then times one full search (Dial's buckets and Boost.Graph's Dijkstra) and computeCentrality()
 * with the given threads, and prints a hash of f and the samples: equal hashes for equal
 * results, whatever the number of threads.
 */
#include "core/centrality/centrality.h"
#include "core/common/morton.h"
#include "core/graph/csr_graph.h"
#include "core/graph/shortest_paths.h"

#include "timing.h"
#include <surfaces/mesh_sampling.h>

#include <pcl/kdtree/kdtree_flann.h>
#include <pcl/point_cloud.h>
#include <pcl/point_types.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <limits>
#include <string>
#include <vector>

namespace {
using pcl_ncut_seg_bench::loadAverage;
using pcl_ncut_seg_bench::now;

template <class T> std::uint64_t hashBits(const std::vector<T>& x, std::uint64_t h) {
  for (const T& v : x) {
    std::uint32_t bits = 0;
    std::memcpy(&bits, &v, sizeof bits);
    h = (h ^ bits) * 1099511628211ull;
  }
  return h;
}

} // namespace

int main(int argc, char** argv) {
  std::string data = PCL_NCUT_SEG_BENCH_DATA;
  std::string model = "block.off";
  std::size_t n = 180926;
  std::vector<unsigned> threads = {1, 2};
  int searches = 20;
  std::string dump;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    if (a == "--model" && i + 1 < argc)
      model = argv[++i];
    else if (a == "--n" && i + 1 < argc)
      n = std::strtoull(argv[++i], nullptr, 10);
    else if (a == "--threads" && i + 1 < argc)
      threads = {static_cast<unsigned>(std::atoi(argv[++i]))};
    else if (a == "--searches" && i + 1 < argc)
      searches = std::atoi(argv[++i]);
    else if (a == "--data" && i + 1 < argc)
      data = argv[++i];
    else if (a == "--dump" && i + 1 < argc)
      dump = argv[++i];
    else {
      std::fprintf(stderr,
                   "Usage: %s [--model FILE] [--n N] [--threads N] [--searches N] [--data DIR]\n"
                   "          [--dump GRAPH]\n"
                   "Times the Exact centrality on <data>/models/FILE sampled at N points\n"
                   "(default block.off, 180926; threads 1 then 2). --dump writes the graph\n"
                   "(n, then offsets, targets and lengths as raw 32-bit words) and exits.\n",
                   argv[0]);
      return 2;
    }
  }
  pcl_ncut_seg::TriangleMesh mesh;
  std::string error;
  if (!pcl_ncut_seg::readOff(data + "/models/" + model, mesh, &error)) {
    std::fprintf(stderr, "cannot read %s: %s\n", model.c_str(), error.c_str());
    return 2;
  }
  const std::vector<float> raw = pcl_ncut_seg::sampleSurface(mesh, n, 1);
  // As the front end: vertices in Morton order, ties in the centrality by input order.
  const std::vector<std::uint32_t> order = pcl_ncut_seg::mortonOrder(raw.data(), n);
  std::vector<float> xyz(3 * n);
  pcl::PointCloud<pcl::PointXYZ>::Ptr cloud(new pcl::PointCloud<pcl::PointXYZ>);
  cloud->resize(n);
  for (std::size_t i = 0; i < n; ++i) {
    for (int c = 0; c < 3; ++c)
      xyz[3 * i + c] = raw[3 * order[i] + c];
    (*cloud)[i] = pcl::PointXYZ(xyz[3 * i], xyz[3 * i + 1], xyz[3 * i + 2]);
  }
  const std::size_t k = 10;
  std::vector<std::uint32_t> knn(n * k, std::numeric_limits<std::uint32_t>::max());
  {
    pcl::KdTreeFLANN<pcl::PointXYZ> tree(false);
    tree.setInputCloud(cloud);
    pcl::Indices nn;
    std::vector<float> sqr;
    for (std::size_t i = 0; i < n; ++i) {
      tree.nearestKSearch((*cloud)[i], static_cast<int>(k + 1), nn, sqr);
      std::size_t j = 0;
      for (const auto q : nn)
        if (j < k && q >= 0 && static_cast<std::size_t>(q) != i)
          knn[i * k + j++] = static_cast<std::uint32_t>(q);
    }
  }
  const pcl_ncut_seg::CsrGraph graph =
      pcl_ncut_seg::buildSymmetricKnnGraph(xyz.data(), n, knn.data(), k);
  if (!dump.empty()) {
    std::ofstream out(dump, std::ios::binary);
    const std::uint32_t count = static_cast<std::uint32_t>(n);
    out.write(reinterpret_cast<const char*>(&count), 4);
    out.write(reinterpret_cast<const char*>(graph.offsets.data()), 4 * (n + 1));
    out.write(reinterpret_cast<const char*>(graph.targets.data()), 4 * graph.targets.size());
    out.write(reinterpret_cast<const char*>(graph.lengths.data()), 4 * graph.lengths.size());
    return out ? 0 : 1;
  }
  std::printf("%s at %zu points: %zu directed edges; load average %s\n", model.c_str(), n,
              graph.numDirectedEdges(), loadAverage().c_str());

  // One full search from a few sources: Dial's buckets against Boost's Dijkstra.
  {
    const float inf = std::numeric_limits<float>::infinity();
    std::vector<float> dist(n, inf);
    pcl_ncut_seg::BucketDijkstra search(graph);
    double dial = 0.0, boost = 0.0;
    bool same = true;
    for (int s = 0; s < searches; ++s) {
      const std::uint32_t source =
          static_cast<std::uint32_t>((static_cast<std::uint64_t>(s) * 2654435761u) % n);
      std::fill(dist.begin(), dist.end(), inf);
      const double t0 = now();
      search.run(source, dist.data());
      dial += now() - t0;
      if (s < 3) {
        const double t1 = now();
        const std::vector<float> ref = pcl_ncut_seg::geodesicDistances(graph, source);
        boost += now() - t1;
        same = same && std::memcmp(ref.data(), dist.data(), n * sizeof(float)) == 0;
      }
    }
    std::printf("one full search: BucketDijkstra %.2f ms (mean of %d), Boost %.2f ms (incl. "
                "graph copy), distances %s\n",
                1e3 * dial / searches, searches, 1e3 * boost / 3,
                same ? "bit-identical" : "DIFFER");
  }
  for (unsigned t : threads) {
    const double t0 = now();
    const pcl_ncut_seg::Centrality c = pcl_ncut_seg::computeCentrality(graph, 0, t, order.data());
    const double elapsed = now() - t0;
    const std::uint64_t h = hashBits(c.samples, hashBits(c.f, 1469598103934665603ull));
    std::printf("computeCentrality threads %u: %.3f s, %zu samples, hash %016llx; load %s\n", t,
                elapsed, c.samples.size(), static_cast<unsigned long long>(h),
                loadAverage().c_str());
  }
  return 0;
}
