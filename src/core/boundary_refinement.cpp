// Point-level boundary refinement after the hierarchy (an extension of Sec. 5.2; Katz and Tal
// 2003's fuzzy cuts over the kNN graph).
#include <pcl_ncut_seg/core/boundary_refinement.h>

// GCC 12 sees a maybe-uninitialized optional inside Boost.Graph's edge iterators (a false
// positive in the library's headers).
#if defined(__GNUC__) && !defined(__clang__)
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wmaybe-uninitialized"
#endif
#include <boost/graph/adjacency_list.hpp>
#include <boost/graph/boykov_kolmogorov_max_flow.hpp>
#include <boost/range/iterator_range.hpp>
#if defined(__GNUC__) && !defined(__clang__)
#pragma GCC diagnostic pop
#endif

#include <algorithm>
#include <array>
#include <cmath>
#include <functional>
#include <limits>
#include <queue>
#include <utility>

namespace pcl_ncut_seg {

std::vector<std::uint8_t> edgeCreases(const CsrGraph& graph, const float* xyz,
                                      const std::vector<float>& normals) {
  const std::size_t n = graph.numVertices();
  std::vector<std::uint8_t> crease(graph.numDirectedEdges(), 0);
  // Signed bend of an edge, as in contactConcavity(): > 0 where the surface folds outwards.
  auto bend = [&](std::size_t p, std::uint32_t q, float length) {
    if (!(length > 0.0f))
      return 0.0;
    double s = 0.0;
    for (int d = 0; d < 3; ++d)
      s += (normals[3 * p + d] - normals[3 * q + d]) * (xyz[3 * p + d] - xyz[3 * q + d]);
    return s / length;
  };
  double total = 0.0;
  std::size_t edges = 0;
  for (std::size_t p = 0; p < n; ++p)
    for (std::uint32_t e = graph.offsets[p]; e < graph.offsets[p + 1]; ++e)
      if (graph.targets[e] > p) {
        total += std::abs(bend(p, graph.targets[e], graph.lengths[e]));
        ++edges;
      }
  const double typical = edges > 0 ? total / static_cast<double>(edges) : 0.0;
  if (!(typical > 0.0))
    return crease;
  // The bend is symmetric in p and q: both directions get the same value.
  for (std::size_t p = 0; p < n; ++p)
    for (std::uint32_t e = graph.offsets[p]; e < graph.offsets[p + 1]; ++e) {
      const double c = std::max(0.0, -bend(p, graph.targets[e], graph.lengths[e])) / typical;
      crease[e] = static_cast<std::uint8_t>(std::min(255.0, std::round(16.0 * c)));
    }
  return crease;
}

namespace {

/// Maximum flow on a small network (a band of points and two terminals): Boost.Graph's
/// Boykov-Kolmogorov algorithm, fast on graphs of surface neighbourhoods; sequential, so the
/// cut is the same whatever the number of threads.
class MaxFlow {
  using Traits = boost::adjacency_list_traits<boost::vecS, boost::vecS, boost::directedS>;
  using Graph = boost::adjacency_list<
      boost::vecS, boost::vecS, boost::directedS,
      boost::property<boost::vertex_color_t, boost::default_color_type,
                      boost::property<boost::vertex_distance_t, long,
                                      boost::property<boost::vertex_predecessor_t,
                                                      Traits::edge_descriptor>>>,
      boost::property<boost::edge_capacity_t, double,
                      boost::property<boost::edge_residual_capacity_t, double,
                                      boost::property<boost::edge_reverse_t,
                                                      Traits::edge_descriptor>>>>;

public:
  explicit MaxFlow(std::uint32_t nodes) : graph_(nodes) {}

  /// An arc u -> v of capacity cap_uv and its reverse of capacity cap_vu.
  void addEdge(std::uint32_t u, std::uint32_t v, double cap_uv, double cap_vu) {
    const auto uv = boost::add_edge(u, v, graph_).first;
    const auto vu = boost::add_edge(v, u, graph_).first;
    boost::put(boost::edge_capacity, graph_, uv, cap_uv);
    boost::put(boost::edge_capacity, graph_, vu, cap_vu);
    boost::put(boost::edge_reverse, graph_, uv, vu);
    boost::put(boost::edge_reverse, graph_, vu, uv);
  }

  double run(std::uint32_t s, std::uint32_t t) {
    return boost::boykov_kolmogorov_max_flow(graph_, boost::vertex(s, graph_),
                                             boost::vertex(t, graph_));
  }

  /// After run(): the nodes reachable from s in the residual network (the source side).
  std::vector<char> sourceSide(std::uint32_t s) const {
    std::vector<char> seen(boost::num_vertices(graph_), 0);
    std::vector<std::uint32_t> stack{s};
    seen[s] = 1;
    while (!stack.empty()) {
      const std::uint32_t u = stack.back();
      stack.pop_back();
      for (const auto& e : boost::make_iterator_range(boost::out_edges(u, graph_))) {
        const auto v = static_cast<std::uint32_t>(boost::target(e, graph_));
        if (boost::get(boost::edge_residual_capacity, graph_, e) > 0.0 && !seen[v]) {
          seen[v] = 1;
          stack.push_back(v);
        }
      }
    }
    return seen;
  }

private:
  Graph graph_;
};

} // namespace

std::size_t refineBoundaries(const CsrGraph& graph, const std::vector<float>& radii,
                             const std::vector<std::uint8_t>& crease, const BoundaryParams& params,
                             std::vector<std::uint32_t>& segment, std::size_t num_segments) {
  const std::size_t n = graph.numVertices();
  if (!(params.band_fraction > 0.0) || num_segments < 2 || n == 0 || segment.size() != n ||
      radii.size() != n)
    return 0;
  const bool use_crease = !crease.empty() && crease.size() == graph.numDirectedEdges() &&
                          params.crease_weight > 0.0;
  std::array<double, 256> factor;
  for (std::size_t c = 0; c < factor.size(); ++c)
    factor[c] = use_crease ? std::exp(-params.crease_weight * static_cast<double>(c) / 16.0) : 1.0;
  auto capacity = [&](std::uint32_t e) {
    return static_cast<double>(graph.lengths[e]) * (use_crease ? factor[crease[e]] : 1.0);
  };
  auto area = [&](std::uint32_t p) {
    return static_cast<double>(radii[p]) * static_cast<double>(radii[p]);
  };

  // Members, areas and kNN-graph components of each segment.
  std::vector<std::vector<std::uint32_t>> members(num_segments);
  std::vector<double> seg_area(num_segments, 0.0);
  for (std::uint32_t p = 0; p < n; ++p) {
    members[segment[p]].push_back(p);
    seg_area[segment[p]] += area(p);
  }
  std::vector<std::uint32_t> stamp(n, 0);
  std::uint32_t stamp_id = 0;
  std::vector<std::uint32_t> stack;
  auto components = [&](std::uint32_t x) {
    ++stamp_id;
    std::size_t count = 0;
    for (std::uint32_t root : members[x]) {
      if (stamp[root] == stamp_id)
        continue;
      ++count;
      stamp[root] = stamp_id;
      stack.assign(1, root);
      while (!stack.empty()) {
        const std::uint32_t u = stack.back();
        stack.pop_back();
        for (std::uint32_t e = graph.offsets[u]; e < graph.offsets[u + 1]; ++e) {
          const std::uint32_t v = graph.targets[e];
          if (segment[v] == x && stamp[v] != stamp_id) {
            stamp[v] = stamp_id;
            stack.push_back(v);
          }
        }
      }
    }
    return count;
  };
  std::vector<std::size_t> num_components(num_segments);
  for (std::uint32_t x = 0; x < num_segments; ++x)
    num_components[x] = components(x);

  // Touching pairs, in order of their ids.
  std::vector<std::pair<std::uint32_t, std::uint32_t>> pairs;
  for (std::uint32_t p = 0; p < n; ++p)
    for (std::uint32_t e = graph.offsets[p]; e < graph.offsets[p + 1]; ++e) {
      const std::uint32_t q = graph.targets[e];
      if (segment[p] < segment[q])
        pairs.emplace_back(segment[p], segment[q]);
    }
  std::sort(pairs.begin(), pairs.end());
  pairs.erase(std::unique(pairs.begin(), pairs.end()), pairs.end());

  constexpr float kFar = std::numeric_limits<float>::infinity();
  std::vector<float> dist(n, kFar);
  std::vector<std::int32_t> local(n, -1);
  std::size_t changed = 0;
  using Item = std::pair<float, std::uint32_t>; // (distance, vertex): ties by vertex id
  for (const auto& [a_seg, b_seg] : pairs) {
    // The side with less area first: its distance bound also bounds the other side's search.
    std::uint32_t sides[2] = {a_seg, b_seg};
    if (seg_area[b_seg] < seg_area[a_seg])
      std::swap(sides[0], sides[1]);
    std::vector<std::uint32_t> settled[2], touched;
    float bound = kFar;
    for (int s = 0; s < 2; ++s) {
      const std::uint32_t x = sides[s], y = sides[1 - s];
      // Geodesic distance from the common boundary: its points start at half their shortest
      // edge across it.
      std::priority_queue<Item, std::vector<Item>, std::greater<Item>> queue;
      const std::size_t first_seed = touched.size();
      for (std::uint32_t p : members[x])
        for (std::uint32_t e = graph.offsets[p]; e < graph.offsets[p + 1]; ++e)
          if (segment[graph.targets[e]] == y && 0.5f * graph.lengths[e] < dist[p]) {
            if (dist[p] == kFar)
              touched.push_back(p);
            dist[p] = 0.5f * graph.lengths[e];
          }
      for (std::size_t i = first_seed; i < touched.size(); ++i)
        queue.emplace(dist[touched[i]], touched[i]);
      const double cap = params.band_fraction * seg_area[x];
      double held = 0.0;
      while (!queue.empty()) {
        const auto [d, p] = queue.top();
        queue.pop();
        if (d > dist[p] || local[p] == -2)
          continue;
        if (d >= bound || held + area(p) > cap) {
          bound = std::min(bound, d); // neither side's band may reach this far
          break;
        }
        local[p] = -2; // settled
        held += area(p);
        settled[s].push_back(p);
        for (std::uint32_t e = graph.offsets[p]; e < graph.offsets[p + 1]; ++e) {
          const std::uint32_t q = graph.targets[e];
          const float dq = d + graph.lengths[e];
          if (segment[q] == x && local[q] != -2 && dq < dist[q]) {
            if (dist[q] == kFar)
              touched.push_back(q);
            dist[q] = dq;
            queue.emplace(dq, q);
          }
        }
      }
    }
    // The band: the settled points of both sides closer than the bound.
    std::vector<std::uint32_t> band;
    for (int s = 0; s < 2; ++s)
      for (std::uint32_t p : settled[s]) {
        if (dist[p] < bound)
          band.push_back(p);
        local[p] = -1;
      }
    for (std::uint32_t p : touched)
      dist[p] = kFar;
    if (band.empty())
      continue;
    std::sort(band.begin(), band.end());
    const auto m = static_cast<std::uint32_t>(band.size());
    for (std::uint32_t i = 0; i < m; ++i)
      local[band[i]] = static_cast<std::int32_t>(i);

    // The network: band points, the source (a_seg outside the band) and the sink (b_seg
    // outside the band); points of other segments take no part.
    MaxFlow flow(m + 2);
    const std::uint32_t source = m, sink = m + 1;
    for (std::uint32_t i = 0; i < m; ++i) {
      const std::uint32_t p = band[i];
      double to_source = 0.0, to_sink = 0.0;
      for (std::uint32_t e = graph.offsets[p]; e < graph.offsets[p + 1]; ++e) {
        const std::uint32_t q = graph.targets[e];
        if (local[q] >= 0) {
          if (q > p)
            flow.addEdge(i, static_cast<std::uint32_t>(local[q]), capacity(e), capacity(e));
        } else if (segment[q] == a_seg) {
          to_source += capacity(e);
        } else if (segment[q] == b_seg) {
          to_sink += capacity(e);
        }
      }
      if (to_source > 0.0)
        flow.addEdge(source, i, to_source, 0.0);
      if (to_sink > 0.0)
        flow.addEdge(i, sink, to_sink, 0.0);
    }
    flow.run(source, sink);
    const std::vector<char> source_side = flow.sourceSide(source);
    std::vector<std::uint32_t> old_label(m);
    std::size_t moved = 0;
    for (std::uint32_t i = 0; i < m; ++i) {
      old_label[i] = segment[band[i]];
      const std::uint32_t label = source_side[i] ? a_seg : b_seg;
      moved += label != old_label[i];
      segment[band[i]] = label;
    }
    for (std::uint32_t p : band)
      local[p] = -1;
    if (moved == 0)
      continue;
    // Members of both segments after the recut.
    std::vector<std::uint32_t> old_a, old_b;
    old_a.swap(members[a_seg]);
    old_b.swap(members[b_seg]);
    for (const auto* list : {&old_a, &old_b})
      for (std::uint32_t p : *list)
        members[segment[p]].push_back(p);
    std::sort(members[a_seg].begin(), members[a_seg].end());
    std::sort(members[b_seg].begin(), members[b_seg].end());
    const std::size_t comp_a = components(a_seg), comp_b = components(b_seg);
    if (comp_a > num_components[a_seg] || comp_b > num_components[b_seg] ||
        members[a_seg].empty() || members[b_seg].empty()) {
      // The recut would split a segment: the pair keeps its old boundary.
      for (std::uint32_t i = 0; i < m; ++i)
        segment[band[i]] = old_label[i];
      members[a_seg].swap(old_a);
      members[b_seg].swap(old_b);
      continue;
    }
    num_components[a_seg] = comp_a;
    num_components[b_seg] = comp_b;
    for (std::uint32_t i = 0; i < m; ++i)
      if (segment[band[i]] != old_label[i]) {
        seg_area[old_label[i]] -= area(band[i]);
        seg_area[segment[band[i]]] += area(band[i]);
      }
    changed += moved;
  }
  return changed;
}

} // namespace pcl_ncut_seg
