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
double ratio(double cut, double volume) {
  if (volume > 0.0)
    return cut / volume;
  return cut > 0.0 ? std::numeric_limits<double>::infinity() : 0.0;
}

/// The subgraph induced by a vertex subset, in local ids. Member vertices (m_i) are those with
/// a global id >= num_supernodes.
struct Local {
  std::vector<std::uint32_t> ids; // local -> global
  std::vector<std::vector<std::pair<std::uint32_t, double>>> adj;
  std::vector<double> degree;
  std::size_t num_supernodes;

  Local(const WeightedGraph& g, const std::vector<std::uint32_t>& subset,
        std::size_t num_supernodes)
      : ids(subset), num_supernodes(num_supernodes) {
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
  std::size_t size() const { return ids.size(); }
  bool isMember(std::uint32_t local) const { return ids[local] >= num_supernodes; }
};

/// The connected components of the subset, and which of them hold a member vertex.
struct Components {
  std::vector<std::int32_t> of; ///< per local vertex, its component
  std::vector<bool> has_member; ///< per component
};

Components componentsOf(const Local& g) {
  const std::size_t c = g.size();
  Components comps;
  comps.of.assign(c, -1);
  for (std::uint32_t s = 0; s < c; ++s) {
    if (comps.of[s] >= 0)
      continue;
    const auto id = static_cast<std::int32_t>(comps.has_member.size());
    comps.has_member.push_back(false);
    std::vector<std::uint32_t> stack{s};
    comps.of[s] = id;
    while (!stack.empty()) {
      const std::uint32_t v = stack.back();
      stack.pop_back();
      comps.has_member[id] = comps.has_member[id] || g.isMember(v);
      for (const auto& [u, w] : g.adj[v])
        if (comps.of[u] < 0) {
          comps.of[u] = id;
          stack.push_back(u);
        }
    }
  }
  return comps;
}

/// A disconnected subset's split at NCut 0: V1 is the component of the first member vertex.
/// Vertex-only strays (a representative without its member) ride along with V1.
std::vector<bool> splitAlongComponents(const Local& g, const Components& comps) {
  const std::size_t c = g.size();
  std::vector<bool> side_v1(c, false);
  std::int32_t first = -1;
  for (std::uint32_t i = 0; i < c && first < 0; ++i)
    if (g.isMember(i))
      first = comps.of[i];
  for (std::uint32_t i = 0; i < c; ++i)
    side_v1[i] = comps.of[i] == first || !comps.has_member[comps.of[i]];
  return side_v1;
}

/// The component that carries the members (the core of a spectral split), in local ids, and
/// each local vertex's position in it (-1 outside).
struct Core {
  std::vector<std::uint32_t> vertices;
  std::vector<std::int64_t> pos;

  Core(const Local& g, const Components& comps) : pos(g.size(), -1) {
    for (std::uint32_t i = 0; i < g.size(); ++i)
      if (comps.has_member[comps.of[i]])
        vertices.push_back(i);
    for (std::size_t i = 0; i < vertices.size(); ++i)
      pos[vertices[i]] = static_cast<std::int64_t>(i);
  }
  std::size_t size() const { return vertices.size(); }
};

/// Eq. (10) on the core: (D - W) y = lambda D y through the symmetric D^-1/2 W D^-1/2, whose
/// second largest eigenvector z gives y = D^-1/2 z. False if the solver fails.
bool fiedlerVector(const Local& g, const Core& core, Eigen::VectorXd& y) {
  const std::size_t k = core.size();
  Eigen::MatrixXd m = Eigen::MatrixXd::Zero(k, k);
  Eigen::VectorXd inv_sqrt_d(k);
  for (std::size_t i = 0; i < k; ++i)
    inv_sqrt_d[i] = 1.0 / std::sqrt(g.degree[core.vertices[i]]);
  for (std::size_t i = 0; i < k; ++i)
    for (const auto& [u, w] : g.adj[core.vertices[i]])
      m(i, core.pos[u]) += w * inv_sqrt_d[i] * inv_sqrt_d[core.pos[u]];
  Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> solver(m);
  if (solver.info() != Eigen::Success)
    return false;
  y = inv_sqrt_d.cwiseProduct(solver.eigenvectors().col(k - 2));
  return true;
}

/// The best split of the core along y: V1 = its first `moved` vertices in ascending y.
struct SweepResult {
  std::vector<std::uint32_t> order; ///< core positions in ascending y (ties by position)
  std::size_t moved = 0;            ///< 0: no split value leaves members on both sides
  double ncut = std::numeric_limits<double>::infinity();
};

/// Sweep the uniform split values gamma (v in V1 iff y_v < gamma, Sec. 5.2) for the lowest
/// NCut with members on both sides; if none leaves members on both sides (a tiny cluster of
/// values at one end), every gap between consecutive values.
SweepResult sweepSplitValues(const Local& g, const Core& core, const Eigen::VectorXd& y,
                             std::size_t members, int num_splits) {
  const std::size_t k = core.size();
  SweepResult out;
  out.order.resize(k);
  std::vector<std::uint32_t>& order = out.order;
  std::iota(order.begin(), order.end(), 0u);
  std::sort(order.begin(), order.end(), [&](std::uint32_t a, std::uint32_t b) {
    return y[a] < y[b] || (y[a] == y[b] && a < b);
  });
  const double lo = y[order.front()], hi = y[order.back()];
  if (!(hi > lo))
    return out;
  double total = 0.0;
  for (std::size_t i = 0; i < k; ++i)
    total += g.degree[core.vertices[i]];
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
        vol1 += g.degree[core.vertices[v]];
        members1 += g.isMember(core.vertices[v]);
        for (const auto& [u, w] : g.adj[core.vertices[v]])
          cut += in1[core.pos[u]] ? -w : w;
      }
      const bool both_sides = members1 > 0 && members1 < members; // both must hold points
      if (both_sides) {
        // The cut is summed edge by edge as vertices move: a free cut can round below zero.
        const double free_or_cut = std::max(cut, 0.0);
        const double ncut = ratio(free_or_cut, vol1) + ratio(free_or_cut, total - vol1);
        if (ncut < out.ncut) {
          out.ncut = ncut;
          out.moved = moved;
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
    if (out.moved > 0)
      break;
  }
  return out;
}
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
  const Local g(graph, subset, num_supernodes);
  const std::size_t c = subset.size();
  std::size_t members = 0;
  for (std::uint32_t i = 0; i < c; ++i)
    members += g.isMember(i);
  if (members < 2)
    return out;

  // Components of the subset: a disconnected subset splits at NCut 0.
  const Components comps = componentsOf(g);
  std::vector<bool> side_v1;
  if (std::count(comps.has_member.begin(), comps.has_member.end(), true) >= 2) {
    side_v1 = splitAlongComponents(g, comps);
    out.ncut = 0.0;
  } else {
    // One component carries the members: split it along its Fiedler vector.
    const Core core(g, comps);
    Eigen::VectorXd y;
    if (!fiedlerVector(g, core, y))
      return out;
    const SweepResult sweep = sweepSplitValues(g, core, y, members, num_splits);
    if (sweep.moved == 0)
      return out;
    side_v1.assign(c, false);
    for (std::size_t i = 0; i < sweep.moved; ++i)
      side_v1[core.vertices[sweep.order[i]]] = true;
    // Strays have no edge in the subset, so their side does not change the NCut.
    for (std::uint32_t i = 0; i < c; ++i)
      if (!comps.has_member[comps.of[i]])
        side_v1[i] = true;
    out.ncut = sweep.ncut;
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
  auto bestFirst = [&](int max_leaves, double cap) {
    for (int leaves = 1; leaves < max_leaves; ++leaves) {
      int best = -1;
      for (std::size_t i = 0; i < h.nodes.size(); ++i)
        if (h.nodes[i].left < 0 && h.nodes[i].has_split &&
            (best < 0 || h.nodes[i].ncut < h.nodes[best].ncut))
          best = static_cast<int>(i);
      if (best < 0 || h.nodes[best].ncut > cap)
        break;
      const double neck = split_neck ? split_neck(splits[best].v1, splits[best].v2) : 0.0;
      worth.resize(h.nodes.size(), 0.0);
      worth[best] =
          splitWorth(h.nodes[best].ncut, neck, kNeckExponent, params.neck_bound, kNeckFloor);
      split(best);
    }
  };
  if (params.rule == StoppingRule::ShortCut) {
    bestFirst(std::max(params.max_segments, 1), params.threshold);
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
