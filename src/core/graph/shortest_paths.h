/*
 * pcl_ncut_seg: the shortest paths over the kNN graph, hand-written; every geodesic distance the
 * library computes comes from here. BucketDijkstra is eq. (1)'s hot path (centrality/);
 * multiSourceDijkstra() is the exact search of the other stages: ridgeDistance() and
 * splitAtRidges() (cad/), the bands of rim_merge (views/) and of boundary_refinement (cut/).
 * Boost.Graph's Dijkstra runs only as the tests' reference (geodesicDistances(), checked against
 * in test/test_shortest_paths.cpp).
 */
#pragma once

#include "core/graph/csr_graph.h"

#include <cstdint>
#include <functional>
#include <limits>
#include <queue>
#include <utility>
#include <vector>

namespace pcl_ncut_seg {

/** \brief Dijkstra with Dial's bucket queue (buckets of a fixed width of distance), correcting
 * labels within a bucket.
 *
 * The distances it returns equal those of Boost.Graph's Dijkstra (geodesicDistances()) bit for
 * bit: both are the least solution of d(v) = min_u fl(d(u) + w(u, v)), d(source) = 0, in float
 * arithmetic, whatever the order in which vertices are settled. The bucket width is twice the
 * mean edge length, so a bucket holds a thin front of vertices and a search costs O(|E| + D / w)
 * for a graph of geodesic diameter D, with no heap.
 *
 * The front's rows lie all over the graph's arrays, so a search waits mostly on memory: it
 * fetches the rows of the vertices a few places ahead in the bucket before it needs them, and
 * keeps one pending bit per vertex, so that the distances and bits stay in the processor's
 * cache. It relaxes a row without a branch per edge, then queues the improved targets.
 *
 * One object per thread: it holds the queue. The graph must outlive it.
 */
class BucketDijkstra {
public:
  explicit BucketDijkstra(const CsrGraph& graph);

  /** \brief Shortest path lengths from source.
   * \param[in,out] dist   n floats, +infinity on every vertex the search can reach; filled in
   * \param[in] bound      if given, a vertex v with dist[v] >= bound[v] is reached but not
   *                       expanded (the bounded search of farthest-point sampling)
   * \param[out] touched   if given, every vertex whose dist was set is appended to it */
  void run(std::uint32_t source, float* dist, const float* bound = nullptr,
           std::vector<std::uint32_t>* touched = nullptr);

  /** \brief As run() with the same bound for every vertex (a ball of that radius): no array
   * of n bounds to read. */
  void runWithin(std::uint32_t source, float* dist, float bound,
                 std::vector<std::uint32_t>* touched = nullptr);

private:
  enum class Bound { None, PerVertex, Uniform };
  template <Bound kBound, bool kRecord>
  void runImpl(std::uint32_t source, float* dist, const float* bound, float uniform_bound,
               std::vector<std::uint32_t>* touched);

  const CsrGraph& graph_;
  double inv_width_ = 1.0;
  std::size_t mask_ = 0;
  std::vector<std::vector<std::uint32_t>> buckets_;
  /// Bit v: v waits in the bucket of dist[v] (an entry there is not yet scanned).
  std::vector<std::uint64_t> pending_;
};

/** \brief The graph with vertex order[i] renumbered as i. Rows keep their edges in the input's
 * order (no longer sorted by target): enough for searches. */
CsrGraph permuteGraph(const CsrGraph& graph, const std::vector<std::uint32_t>& order);

} // namespace pcl_ncut_seg

namespace pcl_ncut_seg {

/** \brief For every vertex, its two nearest sources on the graph (a two-label Voronoi
 * diagram). A vertex with fewer than two reachable sources gets kNone and +infinity for the
 * missing ones. Equal distances are resolved in a fixed order, so the result is reproducible. */
struct NearestSources {
  struct Labels {
    std::uint32_t first, second; ///< index into the source list
    float first_dist, second_dist;
  };
  std::vector<Labels> at; ///< per vertex (one cache line holds a vertex's labels)
};

/** \brief Multi-source search from sources (vertex ids) keeping two labels per vertex. */
NearestSources nearestTwoSources(const CsrGraph& graph, const std::vector<std::uint32_t>& sources);

} // namespace pcl_ncut_seg

namespace pcl_ncut_seg {

/// What a search does with the vertex it has just settled.
enum class Settle {
  kExpand, ///< relax its edges
  kStop,   ///< end the search here (what is still queued is dropped)
};

/** \brief Exact multi-source Dijkstra over the graph's edge lengths, for the searches that
 * need more than distances: a mask or a bound on the edges, something done per settled vertex
 * in the order settled, the source each vertex is nearest to.
 *
 * A binary heap of (distance, vertex) settles the nearest vertex first, the lowest id among
 * equals, and each vertex once (with owners, again when its owner changes at an equal
 * distance): the order of settling, and so any sum taken in it, is reproducible. Distances are
 * summed in Dist (float: the least solution of d(v) = min_u fl(d(u) + w(u, v)), the same as
 * BucketDijkstra's; double where a band's width is compared with them).
 *
 * Not Boost.Graph's Dijkstra (over a compressed_sparse_row_graph, from a range of sources):
 * pcl_ncut_seg_bench_geodesics times it on the two searches it can express, at 181k points
 * (fandisk, block, hand-fine): its search is as fast as this one from the ridges and faster
 * from the regions' many points, but building its graph from the CsrGraph (7-9 ms) leaves it
 * 5-10 ms slower for ridgeDistance() and no faster for the nearest region. It cannot express
 * the rest cleanly: its heap orders equal distances its own way, not by the lowest id (the
 * bands sum and stop in the order settled), a settled vertex cannot be queued again when a
 * lower owner ties with it, and a stop is an exception thrown from a visitor.
 * \param[in] sources    vertices queued first, in this order, at their dist (finite)
 * \param[in,out] dist   per vertex: the sources' start distances, +infinity where the search is
 *                       to reach; filled in
 * \param[in] reach      reach(p, q, dq) -> bool: whether the edge (p, q) may lower q's distance
 *                       to dq (a mask, a bound); asked only when dq improves on dist[q]
 * \param[in] settle     settle(p, d) -> Settle: called when p is settled at distance d
 * \param[in,out] owner  if given, per vertex the label of its source (kept at the sources,
 *                       anything elsewhere): each vertex takes its nearest source's, the lowest
 *                       label among equally near ones
 * \param[out] touched   if given, every vertex whose dist was lowered from +infinity is appended */
template <typename Dist, typename Reach, typename SettleFn>
void multiSourceDijkstra(const CsrGraph& graph, const std::vector<std::uint32_t>& sources,
                         Dist* dist, Reach reach, SettleFn settle, std::uint32_t* owner = nullptr,
                         std::vector<std::uint32_t>* touched = nullptr) {
  constexpr Dist kInfinity = std::numeric_limits<Dist>::infinity();
  using Item = std::pair<Dist, std::uint32_t>; // the nearest, then the lowest id, on top
  std::priority_queue<Item, std::vector<Item>, std::greater<Item>> queue;
  for (std::uint32_t s : sources)
    queue.emplace(dist[s], s);
  while (!queue.empty()) {
    const auto [d, p] = queue.top();
    queue.pop();
    if (d > dist[p])
      continue; // stale: p was queued again nearer
    if (settle(p, d) == Settle::kStop)
      return;
    for (std::uint32_t e = graph.offsets[p]; e < graph.offsets[p + 1]; ++e) {
      const std::uint32_t q = graph.targets[e];
      const Dist dq = d + graph.lengths[e];
      const bool nearer = dq < dist[q] || (owner && dq == dist[q] && owner[p] < owner[q]);
      if (!nearer || !reach(p, q, dq))
        continue;
      if (touched && dist[q] == kInfinity)
        touched->push_back(q);
      dist[q] = dq;
      if (owner)
        owner[q] = owner[p];
      queue.emplace(dq, q);
    }
  }
}

/// For multiSourceDijkstra(): every edge may be used, every settled vertex is expanded.
struct AnyEdge {
  template <typename Dist> bool operator()(std::uint32_t, std::uint32_t, Dist) const {
    return true;
  }
};
struct ExpandAll {
  template <typename Dist> Settle operator()(std::uint32_t, Dist) const { return Settle::kExpand; }
};

} // namespace pcl_ncut_seg
