// Sec. 5.1: the graph of representative and member vertices, weights (7) and (9), conn (8).
#include "core/cut/supernode_graph.h"
#include "core/common/threads.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>

namespace pcl_ncut_seg {

Connectivity supernodeConnectivity(const CsrGraph& graph, const std::vector<float>& f,
                                   const std::vector<std::uint32_t>& label, unsigned num_threads) {
  const std::size_t n = graph.numVertices();
  std::uint32_t l = 0;
  for (std::uint32_t s : label)
    l = std::max(l, s + 1);
  // Group points by supernode, then sum each supernode's edges in a scratch row: O(|E|).
  std::vector<std::uint32_t> start(l + 1, 0), members(n);
  for (std::uint32_t s : label)
    ++start[s + 1];
  std::partial_sum(start.begin(), start.end(), start.begin());
  std::vector<std::uint32_t> fill(start.begin(), start.end() - 1);
  for (std::uint32_t p = 0; p < n; ++p)
    members[fill[label[p]]++] = p;

  // The supernodes' rows are independent sums (each in a fixed order): in parallel, then
  // entered in supernode order, the same for any number of threads.
  std::vector<std::vector<std::pair<std::uint32_t, double>>> found(l);
#pragma omp parallel num_threads(usableThreads(num_threads))
  {
    std::vector<double> row(l, 0.0);
    std::vector<std::uint32_t> touched;
#pragma omp for schedule(dynamic, 1)
    for (std::ptrdiff_t si = 0; si < static_cast<std::ptrdiff_t>(l); ++si) {
      const auto i = static_cast<std::uint32_t>(si);
      touched.clear();
      // Most edges stay inside i: their sum is kept in a register (row[i] in memory would make
      // every addition wait for the previous one's store). Each sum adds in the same order.
      double self = 0.0;
      for (std::uint32_t k = start[i]; k < start[i + 1]; ++k) {
        const std::uint32_t p = members[k];
        for (std::uint32_t e = graph.offsets[p]; e < graph.offsets[p + 1]; ++e) {
          const std::uint32_t q = graph.targets[e];
          const std::uint32_t j = label[q];
          if (j < i)
            continue; // counted from j's side: conn is symmetric on a symmetric graph
          // eq. (8) with the norm of eq. (3); +tiny keeps zero-length edges recorded
          const double d = featureDistance(f[p] - f[q], graph.lengths[e]) + 1e-300;
          if (j == i) {
            self += d;
            continue;
          }
          if (row[j] == 0.0)
            touched.push_back(j);
          row[j] += d;
        }
      }
      if (self != 0.0) {
        touched.push_back(i);
        row[i] = self;
      }
      std::sort(touched.begin(), touched.end());
      auto& out = found[i];
      for (std::uint32_t j : touched) {
        out.emplace_back(j, row[j]);
        row[j] = 0.0;
      }
    }
  }
  Connectivity conn;
  for (std::uint32_t i = 0; i < l; ++i)
    for (const auto& [j, value] : found[i])
      conn.emplace_hint(conn.end(), std::make_pair(i, j), value);
  return conn;
}

namespace {
double lookup(const Connectivity& conn, std::uint32_t i, std::uint32_t j) {
  auto it = conn.find({std::min(i, j), std::max(i, j)});
  return it == conn.end() ? 0.0 : it->second;
}
constexpr double kMinWeight = 1e-200; // keeps every vertex's degree positive (D regular)

/// Each connected component is a surface of its own, as for the centrality (Sec. 4.1): the
/// maxima that normalize eqs. (7) and (9) and the width's unit are taken over its supernodes
/// only, so that the weights within one object do not depend on what else the cloud holds.
/// Per component (indexed by its root supernode) and per supernode, what the weights read.
struct ComponentScales {
  std::vector<std::uint32_t> root;        ///< per supernode, its component's root
  std::vector<double> max_self, max_pair; ///< per root: the largest conn(i, i), conn(i, j)
  std::vector<float> min_h, max_h;        ///< per root: the range of feature heights
  std::vector<double> width;              ///< per supernode, in units of sqrt(total area)
  std::vector<bool> flat;                 ///< per supernode: f_h small against its size

  ComponentScales(const FeatureStats& stats, const Connectivity& conn,
                  const SimilarityParams& params, std::uint32_t l);

private:
  void findComponents(const Connectivity& conn, std::uint32_t l);
};

ComponentScales::ComponentScales(const FeatureStats& stats, const Connectivity& conn,
                                 const SimilarityParams& params, std::uint32_t l)
    : max_self(l, 0.0), max_pair(l, 0.0), min_h(l, std::numeric_limits<float>::infinity()),
      max_h(l, -std::numeric_limits<float>::infinity()), width(l), flat(l, false) {
  findComponents(conn, l);
  for (const auto& [key, value] : conn) {
    double& max = key.first == key.second ? max_self[root[key.first]] : max_pair[root[key.first]];
    max = std::max(max, value);
  }
  std::vector<double> total_area(l, 0.0);
  for (std::uint32_t s = 0; s < l; ++s) {
    total_area[root[s]] += stats.area[s];
    min_h[root[s]] = std::min(min_h[root[s]], stats.height[s]);
    max_h[root[s]] = std::max(max_h[root[s]], stats.height[s]);
  }
  // Feature width is an area over a height, i.e. a length: measure it in units of
  // sqrt(total area) so the weights do not depend on the model's units.
  for (std::uint32_t s = 0; s < l; ++s) {
    const double area = total_area[root[s]];
    const double unit = params.normalize_width && area > 0.0 ? std::sqrt(area) : 1.0;
    width[s] = std::max(static_cast<double>(stats.width[s]) / unit, 1e-300);
  }
  // A supernode is flat when its feature height is small against its size: f_h < e sqrt(f_a)
  // (both lengths). Its width f_a / f_h (eq. 4) is then inflated by a near-zero height: on a
  // plate or a cup wall, neighbouring patches differ in width a hundredfold, and eq. (9) would
  // make their edge exp(-20) or less.
  const double flat_elongation = params.flat_elongation.value_or(0.0);
  for (std::uint32_t s = 0; s < l; ++s)
    flat[s] = stats.height[s] < flat_elongation * std::sqrt(std::max(stats.area[s], 0.0f));
}

/// Supernodes of one component are joined by kNN edges, i.e. by pairs of conn.
void ComponentScales::findComponents(const Connectivity& conn, std::uint32_t l) {
  root.resize(l);
  std::iota(root.begin(), root.end(), 0u);
  auto rootOf = [this](std::uint32_t s) {
    while (root[s] != s)
      s = root[s] = root[root[s]];
    return s;
  };
  for (const auto& [key, value] : conn)
    if (key.first != key.second)
      root[rootOf(key.first)] = rootOf(key.second);
  for (std::uint32_t s = 0; s < l; ++s)
    root[s] = rootOf(s);
}

/// G_s's edges as they are added: r_i - m_i by eq. (7), m_i - m_j by eq. (9), with the trees of
/// member vertices they join so far (union-find over supernodes).
class SupernodeEdges {
public:
  SupernodeEdges(const FeatureStats& stats, const Connectivity& conn,
                 const SimilarityParams& params, const Connectivity* concavity,
                 const std::vector<float>* thickness, std::uint32_t l, WeightedGraph& g)
      : stats_(stats), conn_(conn), params_(params), concavity_(concavity), thickness_(thickness),
        l_(l), g_(g), scales_(stats, conn, params, l), tree_(l) {
    std::iota(tree_.begin(), tree_.end(), 0u);
  }

  /// eq. (7): r_i - m_i.
  void addRepresentativeEdges() {
    for (std::uint32_t i = 0; i < l_; ++i) {
      const double self = scales_.max_self[scales_.root[i]];
      const double ratio = self > 0.0 ? lookup(conn_, i, i) / self : 0.0;
      const double w = std::exp(-(1.0 - ratio) / (params_.beta * scales_.width[i]));
      g_.edges.push_back({i, l_ + i, std::max(w, kMinWeight)});
    }
  }

  /// eq. (9) between each supernode and the one created at the saddle where it terminates.
  void addSaddleEdges(const Supernodes& sn) {
    for (std::uint32_t i = 0; i < l_; ++i) {
      const std::uint32_t p = sn.parent[i];
      if (p == kNone)
        continue;
      g_.edges.push_back({l_ + std::min(i, p), l_ + std::max(i, p), similarity(i, p)});
      tree_[find(i)] = find(p);
    }
  }

  /// Adjacency::All: every kNN-adjacent pair not yet joined at a saddle (the saddle edges are
  /// parent-child) whose contact is a large enough share of the smaller total contact.
  void addAdjacentEdges(const Supernodes& sn) {
    std::vector<double> contact(l_, 0.0);
    for (const auto& [key, value] : conn_)
      if (key.first != key.second) {
        contact[key.first] += value;
        contact[key.second] += value;
      }
    for (const auto& [key, value] : conn_) {
      const auto [i, j] = key;
      if (i == j || sn.parent[i] == j || sn.parent[j] == i)
        continue;
      if (value < kAdjacentShare * std::min(contact[i], contact[j]))
        continue;
      g_.edges.push_back({l_ + i, l_ + j, similarity(i, j)});
      tree_[find(i)] = find(j);
    }
  }

  /// Trees of supernodes that meet at no saddle (the fraction rule of Sec. 4.2 can keep them
  /// apart) would be cut at zero cost: join them where they are most connected point-wise.
  void joinSeparateTrees() {
    std::vector<std::pair<double, std::pair<std::uint32_t, std::uint32_t>>> candidates;
    for (const auto& [key, value] : conn_)
      if (key.first != key.second)
        candidates.push_back({value, key});
    std::sort(candidates.begin(), candidates.end(), [](const auto& a, const auto& b) {
      return a.first > b.first || (a.first == b.first && a.second < b.second);
    });
    for (const auto& [value, key] : candidates) {
      const std::uint32_t a = find(key.first), b = find(key.second);
      if (a == b)
        continue;
      tree_[a] = b;
      g_.edges.push_back({l_ + key.first, l_ + key.second, similarity(key.first, key.second)});
    }
  }

private:
  /// eq. (9) between m_i and m_j of one component.
  double similarity(std::uint32_t i, std::uint32_t j) const {
    const std::uint32_t c = scales_.root[i];
    const double max_dh = static_cast<double>(scales_.max_h[c]) - scales_.min_h[c];
    const double pair = scales_.max_pair[c];
    const double d1 = max_dh > 0.0 ? std::abs(stats_.height[i] - stats_.height[j]) / max_dh : 0.0;
    const double d2 = pair > 0.0 ? 1.0 - lookup(conn_, i, j) / pair : 1.0;
    const std::vector<double>& width = scales_.width;
    // Flat patches (an extension): between two supernodes that are both flat, their widths
    // say nothing about a part boundary, so the width ratio does not weaken their edge.
    const double width_ratio = scales_.flat[i] && scales_.flat[j]
                                   ? 1.0
                                   : std::min(width[i], width[j]) / std::max(width[i], width[j]);
    const double alpha_ij = std::max(params_.alpha2 * width_ratio * thicknessRatio(i, j), 1e-300);
    // Concave contact (an extension): a weaker edge, so that cuts follow concave creases.
    const double concavity_weight = params_.concavity.value_or(0.0);
    const double crease =
        concavity_weight > 0.0 && concavity_ ? concavity_weight * lookup(*concavity_, i, j) : 0.0;
    return std::max(std::exp(-d1 / params_.alpha1 - d2 / alpha_ij - crease), kMinWeight);
  }

  /// min/max of the two supernodes' thickness (core/cut/thickness.h): a part that is thinner or
  /// thicker than its neighbour meets it at a weaker edge, like a narrower one in eq. (9).
  double thicknessRatio(std::uint32_t i, std::uint32_t j) const {
    if (!thickness_ || !params_.thickness)
      return 1.0;
    const double a = (*thickness_)[i], b = (*thickness_)[j];
    if (!(a > 0.0) || !(b > 0.0))
      return 1.0;
    return std::min(a, b) / std::max(a, b);
  }

  std::uint32_t find(std::uint32_t s) {
    while (tree_[s] != s)
      s = tree_[s] = tree_[tree_[s]];
    return s;
  }

  const FeatureStats& stats_;
  const Connectivity& conn_;
  const SimilarityParams& params_;
  const Connectivity* concavity_;
  const std::vector<float>* thickness_;
  const std::uint32_t l_;
  WeightedGraph& g_;
  const ComponentScales scales_;
  std::vector<std::uint32_t> tree_;
};
} // namespace

WeightedGraph buildSupernodeGraph(const Supernodes& sn, const FeatureStats& stats,
                                  const Connectivity& conn, const SimilarityParams& params,
                                  const Connectivity* concavity,
                                  const std::vector<float>* thickness) {
  const auto l = static_cast<std::uint32_t>(sn.size());
  WeightedGraph g;
  g.num_vertices = 2 * l;
  if (l == 0)
    return g;
  SupernodeEdges edges(stats, conn, params, concavity, thickness, l, g);
  edges.addRepresentativeEdges();
  edges.addSaddleEdges(sn);
  if (params.adjacency == Adjacency::All)
    edges.addAdjacentEdges(sn);
  if (params.adjacency != Adjacency::Saddles)
    edges.joinSeparateTrees();
  return g;
}

} // namespace pcl_ncut_seg
