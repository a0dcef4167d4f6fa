// Sec. 5.2: Shi-Malik spectral bisection, NCut of eq. (5) (corrected), recursive hierarchy.
#include "core/cut/normalized_cut.h"

#include "core/cut/short_cut.h"

#include <Eigen/Dense>

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>

namespace pcl_ncut_seg {

namespace {
/// Short-cut rule: NCuts below this count as this (no worth grows without bound).
constexpr double kNeckFloor = 1e-3;

double ratio(double cut, double volume) {
  if (volume > 0.0)
    return cut / volume;
  return cut > 0.0 ? std::numeric_limits<double>::infinity() : 0.0;
}

/// The subgraph induced by a vertex subset, in local ids.
struct Local {
  std::vector<std::uint32_t> ids; // local -> global
  std::vector<std::vector<std::pair<std::uint32_t, double>>> adj;
  std::vector<double> degree;

  Local(const WeightedGraph& g, const std::vector<std::uint32_t>& subset) : ids(subset) {
    std::vector<std::int64_t> local(g.num_vertices, -1);
    for (std::size_t i = 0; i < ids.size(); ++i)
      local[ids[i]] = static_cast<std::int64_t>(i);
    adj.resize(ids.size());
    degree.assign(ids.size(), 0.0);
    for (const auto& e : g.edges) {
      const std::int64_t a = local[e.a], b = local[e.b];
      if (a < 0 || b < 0 || a == b)
        continue;
      adj[a].emplace_back(static_cast<std::uint32_t>(b), e.w);
      adj[b].emplace_back(static_cast<std::uint32_t>(a), e.w);
      degree[a] += e.w;
      degree[b] += e.w;
    }
  }
};
} // namespace

double normalizedCut(const WeightedGraph& graph, const std::vector<std::uint32_t>& subset,
                     const std::vector<bool>& in_v1) {
  std::vector<char> inside(graph.num_vertices, 0);
  for (std::uint32_t v : subset)
    inside[v] = 1;
  double cut = 0.0, vol1 = 0.0, vol2 = 0.0;
  for (const auto& e : graph.edges) {
    if (!inside[e.a] || !inside[e.b] || e.a == e.b)
      continue;
    (in_v1[e.a] ? vol1 : vol2) += e.w;
    (in_v1[e.b] ? vol1 : vol2) += e.w;
    if (in_v1[e.a] != in_v1[e.b])
      cut += e.w;
  }
  return ratio(cut, vol1) + ratio(cut, vol2); // asso(V1, V) = vol1, asso(V2, V) = vol2
}

Bisection bisect(const WeightedGraph& graph, std::size_t num_supernodes,
                 const std::vector<std::uint32_t>& subset, int num_splits) {
  Bisection out;
  const Local g(graph, subset);
  const std::size_t c = subset.size();
  auto is_member = [&](std::uint32_t local) { return g.ids[local] >= num_supernodes; };
  std::size_t members = 0;
  for (std::uint32_t i = 0; i < c; ++i)
    members += is_member(i);
  if (members < 2)
    return out;

  // Components of the subset: a disconnected subset splits at NCut 0.
  std::vector<std::int32_t> comp(c, -1);
  std::vector<bool> comp_has_member;
  for (std::uint32_t s = 0; s < c; ++s) {
    if (comp[s] >= 0)
      continue;
    const auto id = static_cast<std::int32_t>(comp_has_member.size());
    comp_has_member.push_back(false);
    std::vector<std::uint32_t> stack{s};
    comp[s] = id;
    while (!stack.empty()) {
      const std::uint32_t v = stack.back();
      stack.pop_back();
      comp_has_member[id] = comp_has_member[id] || is_member(v);
      for (const auto& [u, w] : g.adj[v])
        if (comp[u] < 0) {
          comp[u] = id;
          stack.push_back(u);
        }
    }
  }
  std::vector<bool> side_v1(c, false);
  const std::size_t member_comps =
      static_cast<std::size_t>(std::count(comp_has_member.begin(), comp_has_member.end(), true));
  if (member_comps >= 2) {
    std::int32_t first = -1;
    for (std::uint32_t i = 0; i < c && first < 0; ++i)
      if (is_member(i))
        first = comp[i];
    // Vertex-only strays (a representative without its member) ride along with V1.
    for (std::uint32_t i = 0; i < c; ++i)
      side_v1[i] = comp[i] == first || !comp_has_member[comp[i]];
    out.ncut = 0.0;
  } else {
    // One component carries the members: solve (D - W) y = lambda D y on it (eq. 10) through
    // the symmetric D^-1/2 W D^-1/2, whose second largest eigenvector z gives y = D^-1/2 z.
    std::vector<std::uint32_t> core;
    for (std::uint32_t i = 0; i < c; ++i)
      if (comp_has_member[comp[i]])
        core.push_back(i);
    const std::size_t k = core.size();
    std::vector<std::int64_t> pos(c, -1);
    for (std::size_t i = 0; i < k; ++i)
      pos[core[i]] = static_cast<std::int64_t>(i);
    Eigen::MatrixXd m = Eigen::MatrixXd::Zero(k, k);
    Eigen::VectorXd inv_sqrt_d(k);
    for (std::size_t i = 0; i < k; ++i)
      inv_sqrt_d[i] = 1.0 / std::sqrt(g.degree[core[i]]);
    for (std::size_t i = 0; i < k; ++i)
      for (const auto& [u, w] : g.adj[core[i]])
        m(i, pos[u]) += w * inv_sqrt_d[i] * inv_sqrt_d[pos[u]];
    Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> solver(m);
    if (solver.info() != Eigen::Success)
      return out;
    const Eigen::VectorXd y = inv_sqrt_d.cwiseProduct(solver.eigenvectors().col(k - 2));

    // Sweep the uniform split values gamma: v in V1 iff y_v < gamma.
    std::vector<std::uint32_t> order(k);
    std::iota(order.begin(), order.end(), 0u);
    std::sort(order.begin(), order.end(), [&](std::uint32_t a, std::uint32_t b) {
      return y[a] < y[b] || (y[a] == y[b] && a < b);
    });
    const double lo = y[order.front()], hi = y[order.back()];
    if (!(hi > lo))
      return out;
    double total = 0.0;
    for (std::size_t i = 0; i < k; ++i)
      total += g.degree[core[i]];
    // Uniform split values as in the paper; if none leaves points on both sides (a tiny
    // cluster of values at one end), every gap between consecutive values.
    std::size_t best_moved = 0;
    double best = std::numeric_limits<double>::infinity();
    for (const bool every_gap : {false, true}) {
      std::vector<bool> in1(k, false);
      double cut = 0.0, vol1 = 0.0;
      std::size_t moved = 0, members1 = 0;
      const std::size_t steps = every_gap ? k - 1 : static_cast<std::size_t>(num_splits);
      for (std::size_t t = 1; t <= steps; ++t) {
        const double gamma = lo + (hi - lo) * t / (num_splits + 1.0);
        while (moved < k && (every_gap ? moved < t : y[order[moved]] < gamma)) {
          const std::uint32_t v = order[moved++];
          in1[v] = true;
          vol1 += g.degree[core[v]];
          members1 += is_member(core[v]);
          for (const auto& [u, w] : g.adj[core[v]])
            cut += in1[pos[u]] ? -w : w;
        }
        const bool both_sides = members1 > 0 && members1 < members; // both must hold points
        if (both_sides) {
          const double ncut = ratio(cut, vol1) + ratio(cut, total - vol1);
          if (ncut < best) {
            best = ncut;
            best_moved = moved;
          }
        }
        // Split values that move no vertex give the same NCut again: skip them, so that a huge
        // number of split values costs no more than one per vertex. One value short of the
        // next vertex's, which leaves room for rounding.
        if (moved == k)
          break; // every vertex in V1: no further value leaves points on both sides
        if (!every_gap) {
          const double next =
              std::floor((y[order[moved]] - lo) / (hi - lo) * (num_splits + 1.0)) - 1.0;
          if (next > static_cast<double>(t))
            t = static_cast<std::size_t>(std::min(next, static_cast<double>(steps)));
        }
      }
      if (best_moved > 0)
        break;
    }
    if (best_moved == 0)
      return out;
    for (std::size_t i = 0; i < best_moved; ++i)
      side_v1[core[order[i]]] = true;
    // Strays have no edge in the subset, so their side does not change the NCut.
    for (std::uint32_t i = 0; i < c; ++i)
      if (!comp_has_member[comp[i]])
        side_v1[i] = true;
    out.ncut = best;
  }
  // Canonical orientation: V1 holds the subset's smallest vertex.
  if (!side_v1[0])
    side_v1.flip();
  for (std::uint32_t i = 0; i < c; ++i)
    (side_v1[i] ? out.v1 : out.v2).push_back(g.ids[i]);
  out.valid = true;
  return out;
}

std::vector<int> Hierarchy::leaves() const {
  std::vector<int> out;
  for (std::size_t i = 0; i < nodes.size(); ++i)
    if (nodes[i].left < 0)
      out.push_back(static_cast<int>(i));
  std::sort(out.begin(), out.end(),
            [&](int a, int b) { return nodes[a].vertices.front() < nodes[b].vertices.front(); });
  return out;
}

namespace {
/// The hierarchy with only the splits the short-cut rule keeps (shortCutKeep()); nodes keep
/// their creation order (parents first).
Hierarchy keptSplits(const Hierarchy& h, std::vector<double> worth) {
  const std::size_t n = h.nodes.size();
  worth.resize(n, 0.0);
  std::vector<int> left(n), right(n);
  for (std::size_t i = 0; i < n; ++i) {
    left[i] = h.nodes[i].left;
    right[i] = h.nodes[i].right;
  }
  const std::vector<bool> keep = shortCutKeep(worth, left, right);
  Hierarchy out;
  std::vector<int> id(n, -1);
  for (std::size_t i = 0; i < n; ++i) {
    const int parent = h.nodes[i].parent;
    if (parent >= 0 && !keep[parent])
      continue; // below a dropped split (or the dropped split's children)
    const int at = parent >= 0 ? id[parent] : -1;
    id[i] = static_cast<int>(out.nodes.size());
    out.nodes.push_back(h.nodes[i]);
    out.nodes.back().parent = at;
    out.nodes.back().left = out.nodes.back().right = -1;
    if (at >= 0) // the left child is created first
      (out.nodes[at].left < 0 ? out.nodes[at].left : out.nodes[at].right) = id[i];
  }
  return out;
}
} // namespace

Hierarchy buildHierarchy(const WeightedGraph& graph, std::size_t num_supernodes,
                         const StoppingParams& params, const SplitNeckFn& split_neck) {
  Hierarchy h;
  if (graph.num_vertices == 0)
    return h;
  std::vector<Bisection> splits;
  auto add = [&](std::vector<std::uint32_t> vertices, int parent) {
    Hierarchy::Node node;
    node.vertices = std::move(vertices);
    node.parent = parent;
    Bisection b = bisect(graph, num_supernodes, node.vertices, kSplitValues);
    node.has_split = b.valid;
    node.ncut = b.ncut;
    h.nodes.push_back(std::move(node));
    splits.push_back(std::move(b));
    return static_cast<int>(h.nodes.size() - 1);
  };
  auto split = [&](int i) {
    const int left = add(std::move(splits[i].v1), i);
    const int right = add(std::move(splits[i].v2), i);
    h.nodes[i].left = left;
    h.nodes[i].right = right;
  };
  std::vector<std::uint32_t> all(graph.num_vertices);
  std::iota(all.begin(), all.end(), 0u);
  add(std::move(all), -1);

  // Best splits first: the leaf whose bisection has the lowest NCut (at most `cap`).
  std::vector<double> worth; // short-cut rule: per node, its split's worth
  auto bestFirst = [&](int max_leaves, double cap, bool weigh) {
    for (int leaves = 1; leaves < max_leaves; ++leaves) {
      int best = -1;
      for (std::size_t i = 0; i < h.nodes.size(); ++i)
        if (h.nodes[i].left < 0 && h.nodes[i].has_split &&
            (best < 0 || h.nodes[i].ncut < h.nodes[best].ncut))
          best = static_cast<int>(i);
      if (best < 0 || h.nodes[best].ncut > cap)
        break;
      if (weigh) {
        const double neck = split_neck ? split_neck(splits[best].v1, splits[best].v2) : 0.0;
        worth.resize(h.nodes.size(), 0.0);
        worth[best] =
            splitWorth(h.nodes[best].ncut, neck, kNeckExponent, params.neck_bound, kNeckFloor);
      }
      split(best);
    }
  };
  if (params.rule == StoppingRule::Count) {
    bestFirst(params.segments, std::numeric_limits<double>::infinity(), false);
  } else if (params.rule == StoppingRule::ShortCut) {
    bestFirst(std::max(params.max_segments, 1), params.threshold, true);
    return keptSplits(h, worth); // core/cut/short_cut.h
  } else {
    // Recursive bisection until NCut exceeds the threshold.
    std::vector<int> stack{0};
    while (!stack.empty()) {
      const int i = stack.back();
      stack.pop_back();
      if (!h.nodes[i].has_split || h.nodes[i].ncut > params.threshold)
        continue;
      split(i);
      stack.push_back(h.nodes[i].right);
      stack.push_back(h.nodes[i].left);
    }
  }
  return h;
}

} // namespace pcl_ncut_seg
