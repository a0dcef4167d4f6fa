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
  std::vector<char> sourceSide(std::uint32_t s, std::uint32_t t);
};

/// The push-relabel state of one maximum preflow (FIFO order of active nodes).
class Preflow {
public:
  Preflow(FlowNetwork& net, std::uint32_t s, std::uint32_t t)
      : net_(net), s_(s), t_(t), n_(net.nodes()), height_(n_),
        cur_(net.first.begin(), net.first.end() - 1), excess_(n_, 0.0), queued_(n_, 0) {}

  /// Saturate the source's arcs, then discharge active nodes until none is left.
  void run() {
    globalRelabel();
    saturateSourceArcs();
    while (head_ < queue_.size()) {
      const std::uint32_t u = queue_[head_++];
      queued_[u] = 0;
      discharge(u);
    }
  }

  /// The source side: nodes that do not reach t through residual arcs, i.e. those an exact
  /// relabelling leaves at n (s cannot reach t once the preflow is maximum).
  std::vector<char> sourceSide() {
    globalRelabel();
    std::vector<char> source(n_);
    for (std::uint32_t v = 0; v < n_; ++v)
      source[v] = height_[v] == n_;
    return source;
  }

private:
  /// Exact distances to t over residual arcs; n for nodes that cannot reach it.
  void globalRelabel() {
    const auto& first = net_.first;
    const auto& arc = net_.arc;
    std::fill(height_.begin(), height_.end(), n_);
    std::vector<std::uint32_t> bfs{t_};
    height_[t_] = 0;
    for (std::size_t i = 0; i < bfs.size(); ++i) {
      const std::uint32_t u = bfs[i];
      for (std::uint32_t a = first[u]; a < first[u + 1]; ++a) {
        const std::uint32_t w = arc[a].to;
        if (w != s_ && height_[w] == n_ && arc[arc[a].rev].cap > 0.0) {
          height_[w] = height_[u] + 1;
          bfs.push_back(w);
        }
      }
    }
    std::copy(first.begin(), first.end() - 1, cur_.begin());
  }

  void activate(std::uint32_t v) {
    if (v != s_ && v != t_ && !queued_[v] && excess_[v] > 0.0 && height_[v] < n_) {
      queued_[v] = 1;
      queue_.push_back(v);
    }
  }

  void saturateSourceArcs() {
    auto& arc = net_.arc;
    for (std::uint32_t a = net_.first[s_]; a < net_.first[s_ + 1]; ++a) {
      const double c = arc[a].cap;
      if (!(c > 0.0))
        continue;
      arc[a].cap = 0.0;
      arc[arc[a].rev].cap += c;
      excess_[arc[a].to] += c;
      activate(arc[a].to);
    }
  }

  /// u's new height, one above its lowest residual neighbour's; a global relabelling every
  /// n / 4 relabels, as heights drift from the distances (about twice as fast as every n on a
  /// 1M-point model).
  void relabel(std::uint32_t u) {
    const auto& first = net_.first;
    std::uint32_t h = n_;
    for (std::uint32_t a = first[u]; a < first[u + 1]; ++a)
      if (net_.arc[a].cap > 0.0)
        h = std::min(h, height_[net_.arc[a].to] + 1);
    height_[u] = std::min(h, n_);
    cur_[u] = first[u];
    if (++relabels_ >= n_ / 4 + 1) {
      relabels_ = 0;
      globalRelabel();
      queue_.erase(queue_.begin(), queue_.begin() + static_cast<std::ptrdiff_t>(head_));
      head_ = 0;
    }
  }

  /// Push u's excess along admissible arcs, relabelling u when it has none left.
  void discharge(std::uint32_t u) {
    auto& arc = net_.arc;
    while (excess_[u] > 0.0 && height_[u] < n_) {
      if (cur_[u] == net_.first[u + 1]) {
        relabel(u);
        continue;
      }
      const std::uint32_t a = cur_[u], v = arc[a].to;
      if (arc[a].cap > 0.0 && height_[u] == height_[v] + 1) {
        const double d = std::min(excess_[u], arc[a].cap);
        arc[a].cap -= d;
        arc[arc[a].rev].cap += d;
        excess_[u] -= d;
        excess_[v] += d;
        activate(v);
        if (!(arc[a].cap > 0.0))
          ++cur_[u];
      } else {
        ++cur_[u];
      }
    }
  }

  FlowNetwork& net_;
  const std::uint32_t s_, t_, n_;
  std::vector<std::uint32_t> height_, cur_;
  std::vector<double> excess_;
  std::vector<char> queued_;
  std::vector<std::uint32_t> queue_;
  std::size_t head_ = 0, relabels_ = 0;
};

inline std::vector<char> FlowNetwork::sourceSide(std::uint32_t s, std::uint32_t t) {
  std::vector<double>().swap(to_source); // built: free before the search's own arrays
  std::vector<double>().swap(to_sink);
  Preflow preflow(*this, s, t);
  preflow.run();
  return preflow.sourceSide();
}

} // namespace pcl_ncut_seg
