/*
 * pcl_ncut_seg: a minimum s-t cut of a small network in CSR form, for the boundary refinement
 * (core/cut/boundary_refinement.h).
 */
#pragma once

#include <algorithm>
#include <cstdint>
#include <vector>

namespace pcl_ncut_seg {

/// Minimum s-t cut of a small network (a band of points and two terminals) in CSR form, by
/// push-relabel (FIFO, with global relabelling; Goldberg and Tarjan): only the first phase,
/// the maximum preflow, is needed for the cut. Sequential, so the cut is the same whatever the
/// number of threads. Each undirected edge is two arcs, each the other's reverse.
struct FlowNetwork {
  /// An arc with its residual capacity and its reverse (together: one cache line per arc).
  struct Arc {
    double cap;
    std::uint32_t to, rev;
  };
  std::vector<std::uint32_t> first; ///< size nodes + 1
  std::vector<Arc> arc;
  std::vector<std::uint32_t> next_arc;    ///< per node, where addPair() puts its next arc
  std::vector<double> to_source, to_sink; ///< building: per inner node, its terminal capacities

  std::uint32_t nodes() const { return static_cast<std::uint32_t>(first.size() - 1); }

  /// Building a network of m inner nodes 0..m-1, the source m and the sink m + 1: count each
  /// inner node's arcs to other inner nodes in first[i + 1] and add up its capacities to the
  /// terminals in to_source[i] and to_sink[i]; then allocateArcs(), and per inner node its
  /// addPair() calls and addTerminalArcs().
  void reset(std::uint32_t m) {
    first.assign(m + 3, 0);
    to_source.assign(m, 0.0);
    to_sink.assign(m, 0.0);
  }

  /// Adds the terminal arcs to the counts, turns the counts into offsets and makes room for the
  /// arcs.
  void allocateArcs() {
    const auto m = static_cast<std::uint32_t>(to_source.size());
    for (std::uint32_t i = 0; i < m; ++i) {
      if (to_source[i] > 0.0) {
        ++first[i + 1];
        ++first[m + 1];
      }
      if (to_sink[i] > 0.0) {
        ++first[i + 1];
        ++first[m + 2];
      }
    }
    for (std::size_t v = 0; v + 1 < first.size(); ++v)
      first[v + 1] += first[v];
    arc.resize(first.back());
    next_arc.assign(first.begin(), first.end() - 1);
  }

  /// Inner node i's arcs from the source and to the sink (those of positive capacity).
  void addTerminalArcs(std::uint32_t i) {
    const auto m = static_cast<std::uint32_t>(to_source.size());
    if (to_source[i] > 0.0)
      addPair(m, i, to_source[i], 0.0);
    if (to_sink[i] > 0.0)
      addPair(i, m + 1, to_sink[i], 0.0);
  }

  /// The arcs u -> v and v -> u, each the other's reverse.
  void addPair(std::uint32_t u, std::uint32_t v, double cap_uv, double cap_vu) {
    const std::uint32_t a = next_arc[u]++, b = next_arc[v]++;
    arc[a] = {cap_uv, v, b};
    arc[b] = {cap_vu, u, a};
  }

  /// The nodes that cannot reach t in the residual network after a maximum preflow from s.
  std::vector<char> sourceSide(std::uint32_t s, std::uint32_t t) {
    std::vector<double>().swap(to_source); // built: free before the search's own arrays
    std::vector<double>().swap(to_sink);
    const std::uint32_t n = nodes();
    std::vector<std::uint32_t> height(n), cur(first.begin(), first.end() - 1);
    std::vector<double> excess(n, 0.0);
    std::vector<char> queued(n, 0);
    std::vector<std::uint32_t> queue;
    std::size_t head = 0;
    // Exact distances to t over residual arcs; n for nodes that cannot reach it.
    auto globalRelabel = [&]() {
      std::fill(height.begin(), height.end(), n);
      std::vector<std::uint32_t> bfs{t};
      height[t] = 0;
      for (std::size_t i = 0; i < bfs.size(); ++i) {
        const std::uint32_t u = bfs[i];
        for (std::uint32_t a = first[u]; a < first[u + 1]; ++a) {
          const std::uint32_t w = arc[a].to;
          if (w != s && height[w] == n && arc[arc[a].rev].cap > 0.0) {
            height[w] = height[u] + 1;
            bfs.push_back(w);
          }
        }
      }
      std::copy(first.begin(), first.end() - 1, cur.begin());
    };
    auto activate = [&](std::uint32_t v) {
      if (v != s && v != t && !queued[v] && excess[v] > 0.0 && height[v] < n) {
        queued[v] = 1;
        queue.push_back(v);
      }
    };
    globalRelabel();
    for (std::uint32_t a = first[s]; a < first[s + 1]; ++a) {
      const double c = arc[a].cap;
      if (!(c > 0.0))
        continue;
      arc[a].cap = 0.0;
      arc[arc[a].rev].cap += c;
      excess[arc[a].to] += c;
      activate(arc[a].to);
    }
    std::size_t relabels = 0;
    while (head < queue.size()) {
      const std::uint32_t u = queue[head++];
      queued[u] = 0;
      while (excess[u] > 0.0 && height[u] < n) {
        if (cur[u] == first[u + 1]) {
          std::uint32_t h = n;
          for (std::uint32_t a = first[u]; a < first[u + 1]; ++a)
            if (arc[a].cap > 0.0)
              h = std::min(h, height[arc[a].to] + 1);
          height[u] = std::min(h, n);
          cur[u] = first[u];
          if (++relabels >= n / 4 + 1) {
            // Heights drift from the distances: recompute them (every n / 4 relabels: about
            // twice as fast as every n on a 1M-point model).
            relabels = 0;
            globalRelabel();
            queue.erase(queue.begin(), queue.begin() + static_cast<std::ptrdiff_t>(head));
            head = 0;
          }
          continue;
        }
        const std::uint32_t a = cur[u], v = arc[a].to;
        if (arc[a].cap > 0.0 && height[u] == height[v] + 1) {
          const double d = std::min(excess[u], arc[a].cap);
          arc[a].cap -= d;
          arc[arc[a].rev].cap += d;
          excess[u] -= d;
          excess[v] += d;
          activate(v);
          if (!(arc[a].cap > 0.0))
            ++cur[u];
        } else {
          ++cur[u];
        }
      }
    }
    // The sink side: nodes that reach t through residual arcs, i.e. those an exact relabelling
    // leaves below n (s cannot reach t once the preflow is maximum).
    globalRelabel();
    std::vector<char> source(n);
    for (std::uint32_t v = 0; v < n; ++v)
      source[v] = height[v] == n;
    return source;
  }
};

} // namespace pcl_ncut_seg
