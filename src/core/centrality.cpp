// Sec. 4.1: farthest-point samples on graph distance and the mean geodesic distance, eq. (1).
#include <pcl_ncut_seg/core/centrality.h>

#include <boost/graph/compressed_sparse_row_graph.hpp>
#include <boost/graph/dijkstra_shortest_paths_no_color_map.hpp>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <limits>

#ifdef _OPENMP
#include <omp.h>
#endif

namespace pcl_ncut_seg {
namespace {

using BoostGraph =
    boost::compressed_sparse_row_graph<boost::directedS, boost::no_property, boost::no_property,
                                       boost::no_property, std::uint32_t, std::uint32_t>;
using Edge = boost::graph_traits<BoostGraph>::edge_descriptor;
constexpr float kInf = std::numeric_limits<float>::infinity();

BoostGraph toBoost(const CsrGraph& graph) {
  std::vector<std::pair<std::uint32_t, std::uint32_t>> edges;
  edges.reserve(graph.numDirectedEdges());
  for (std::uint32_t v = 0; v < graph.numVertices(); ++v)
    for (std::uint32_t e = graph.offsets[v]; e < graph.offsets[v + 1]; ++e)
      edges.emplace_back(v, graph.targets[e]);
  // Rows are already sorted, so Boost's edge index equals the CSR position in `graph`.
  return BoostGraph(boost::edges_are_sorted, edges.begin(), edges.end(),
                    static_cast<std::uint32_t>(graph.numVertices()));
}

/// Edge lengths, as +inf out of a vertex that the current search cannot improve (dist >= h):
/// the bounded search of farthest-point sampling stops there (Sec. 4.1 step 5c).
struct PrunedLength {
  using key_type = Edge;
  using value_type = float;
  using reference = float;
  using category = boost::readable_property_map_tag;
  const float* length;
  const float* dist;
  const float* h;
};
inline float get(const PrunedLength& m, const Edge& e) {
  return m.dist[e.src] >= m.h[e.src] ? kInf : m.length[e.idx];
}

struct RecordDiscovered : boost::default_dijkstra_visitor {
  std::vector<std::uint32_t>* touched;
  explicit RecordDiscovered(std::vector<std::uint32_t>* t) : touched(t) {}
  void discover_vertex(std::uint32_t v, const BoostGraph&) const { touched->push_back(v); }
};

/// Dijkstra from `source`; dist must be +inf on the source's component and is left filled.
template <class WeightMap, class Visitor>
void dijkstra(const BoostGraph& g, std::uint32_t source, float* dist, WeightMap weight,
              Visitor visitor) {
  dist[source] = 0.0f;
  boost::dijkstra_shortest_paths_no_color_map_no_init(
      g, source, boost::dummy_property_map(), dist, weight, boost::get(boost::vertex_index, g),
      std::less<float>(), std::plus<float>(), kInf, 0.0f, visitor);
}

} // namespace

std::vector<float> geodesicDistances(const CsrGraph& graph, std::uint32_t source) {
  const BoostGraph g = toBoost(graph);
  std::vector<float> dist(graph.numVertices(), kInf);
  dijkstra(
      g, source, dist.data(),
      boost::make_iterator_property_map(graph.lengths.data(), boost::get(boost::edge_index, g)),
      boost::default_dijkstra_visitor());
  return dist;
}

Centrality computeCentrality(const CsrGraph& graph, std::size_t num_samples, unsigned num_threads,
                             const ProgressFn& progress) {
  const std::size_t n = graph.numVertices();
  Centrality out;
  out.f.assign(n, 0.0f);
  if (n == 0)
    return out;
  out.num_components = connectedComponents(graph, out.component);
  std::vector<std::vector<std::uint32_t>> members(out.num_components);
  for (std::uint32_t v = 0; v < n; ++v)
    members[out.component[v]].push_back(v);

  const BoostGraph g = toBoost(graph);
  const auto length =
      boost::make_iterator_property_map(graph.lengths.data(), boost::get(boost::edge_index, g));
  std::vector<float> h(n, kInf), dist(n, kInf);
  std::vector<std::uint32_t> touched;
  // Per component: its samples and a fixed-point quantum that bounds every distance in it.
  std::vector<std::pair<std::uint32_t, std::uint32_t>> tasks; // (sample, component)
  std::vector<double> quantum(out.num_components, 1.0);
  std::vector<std::size_t> count(out.num_components, 0);

  for (std::uint32_t c = 0; c < out.num_components; ++c) {
    const auto& comp = members[c];
    const std::size_t want =
        std::min(comp.size(), num_samples > 0 ? num_samples
                                              : static_cast<std::size_t>(std::ceil(
                                                    std::sqrt(static_cast<double>(comp.size())))));
    // First sample: farthest from the component's smallest vertex (a deterministic choice for
    // the arbitrary tie of step 4 when h is infinite everywhere).
    touched.clear();
    dijkstra(g, comp.front(), dist.data(), length, RecordDiscovered(&touched));
    std::uint32_t first = comp.front();
    float ecc = 0.0f;
    for (std::uint32_t v : comp)
      if (dist[v] > ecc) {
        ecc = dist[v];
        first = v;
      }
    for (std::uint32_t v : touched)
      dist[v] = kInf;
    // Any geodesic distance in the component is at most 2 * ecc (triangle inequality).
    if (ecc > 0.0f)
      quantum[c] = 2.0 * ecc / static_cast<double>(std::int64_t(1) << 40);

    std::uint32_t s = first;
    for (std::size_t i = 0; i < want; ++i) {
      if (i > 0) { // step 4: the vertex with the largest h, ties to the smallest index
        float best = -1.0f;
        for (std::uint32_t v : comp)
          if (h[v] > best) {
            best = h[v];
            s = v;
          }
      }
      tasks.emplace_back(s, c);
      // Steps 5c: h <- min(h, g(s, .)), searching only where h can still drop.
      touched.clear();
      dijkstra(g, s, dist.data(), PrunedLength{graph.lengths.data(), dist.data(), h.data()},
               RecordDiscovered(&touched));
      for (std::uint32_t v : touched) {
        h[v] = std::min(h[v], dist[v]);
        dist[v] = kInf;
      }
      h[s] = 0.0f;
    }
    count[c] = want;
  }
  h = std::vector<float>();
  dist = std::vector<float>();

  // Steps 5a-b: full searches from every sample, summed in fixed point so that the sum does
  // not depend on the order, hence not on the number of threads.
  int threads = 1;
#ifdef _OPENMP
  threads = num_threads > 0 ? static_cast<int>(num_threads) : omp_get_max_threads();
#else
  (void)num_threads;
#endif
  threads = std::max(1, std::min<int>(threads, static_cast<int>(tasks.size())));
  std::vector<std::vector<std::int64_t>> partial(threads);
  std::atomic<std::size_t> done{0};
  if (progress)
    progress(0.0);
#pragma omp parallel num_threads(threads)
  {
    int t = 0;
#ifdef _OPENMP
    t = omp_get_thread_num();
#endif
    std::vector<std::int64_t>& acc = partial[t];
    acc.assign(n, 0);
    std::vector<float> d(n, kInf);
#pragma omp for schedule(dynamic, 1)
    for (std::ptrdiff_t i = 0; i < static_cast<std::ptrdiff_t>(tasks.size()); ++i) {
      const auto [sample, c] = tasks[i];
      const auto& comp = members[c];
      dijkstra(g, sample, d.data(), length, boost::default_dijkstra_visitor());
      const double inv = 1.0 / quantum[c];
      for (std::uint32_t v : comp) {
        acc[v] += std::llround(static_cast<double>(d[v]) * inv);
        d[v] = kInf;
      }
      // Only the calling thread (the team's master) reports, so the callback needs no lock.
      const std::size_t finished = done.fetch_add(1) + 1;
      if (progress && t == 0)
        progress(static_cast<double>(finished) / static_cast<double>(tasks.size()));
    }
  }
  if (progress)
    progress(1.0);
  for (std::uint32_t v = 0; v < n; ++v) {
    std::int64_t sum = 0;
    for (const auto& acc : partial)
      sum += acc[v];
    const std::uint32_t c = out.component[v];
    out.f[v] =
        static_cast<float>(static_cast<double>(sum) * quantum[c] / static_cast<double>(count[c]));
  }
  out.samples.reserve(tasks.size());
  for (const auto& t : tasks)
    out.samples.push_back(t.first);
  return out;
}

} // namespace pcl_ncut_seg
