// Joining kNN components separated by sampling gaps (an extension; see README).
#include "core/graph/bridging.h"
#include "core/common/geometry.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <map>
#include <numeric>
#include <tuple>

namespace pcl_ncut_seg {

namespace {
/// Occupied cells of a uniform grid: per cell its points (a range of one sorted array), its
/// component (kMixed when it holds more than one) and how many steps around it hold no other
/// component. Most cells hold one component and lie among cells of that component only: a
/// point there has no other component within one or two cells and skips the search, and no
/// point reads the points of a cell of its own component.
class CellGrid {
public:
  static constexpr std::uint32_t kNoCell = std::numeric_limits<std::uint32_t>::max();
  static constexpr std::uint32_t kMixed = std::numeric_limits<std::uint32_t>::max();

  CellGrid(const float* xyz, std::size_t n, double cell, const std::vector<std::uint32_t>& comp)
      : coords_(3 * n) {
    for (std::size_t i = 0; i < 3 * n; ++i) {
      const double c = std::floor(xyz[i] / cell);
      coords_[i] = static_cast<std::int64_t>(std::max(-1e15, std::min(1e15, c)));
    }
    order_.resize(n);
    std::iota(order_.begin(), order_.end(), 0u);
    auto key = [this](std::uint32_t v) {
      return std::tie(coords_[3 * v], coords_[3 * v + 1], coords_[3 * v + 2]);
    };
    std::sort(order_.begin(), order_.end(), [&](std::uint32_t a, std::uint32_t b) {
      return key(a) < key(b) || (key(a) == key(b) && a < b);
    });
    for (std::uint32_t i = 0; i < n; ++i)
      if (i == 0 || key(order_[i]) != key(order_[i - 1])) {
        begin_.push_back(i);
        component_.push_back(comp[order_[i]]);
      } else if (comp[order_[i]] != component_.back()) {
        component_.back() = kMixed;
      }
    begin_.push_back(static_cast<std::uint32_t>(n));
    std::size_t size = 16;
    while (size < 2 * numCells())
      size *= 2;
    table_.assign(size, kNoCell);
    for (std::uint32_t i = 0; i < numCells(); ++i) {
      const std::uint32_t v = order_[begin_[i]];
      std::size_t slot = hash(coord(v, 0), coord(v, 1), coord(v, 2));
      while (table_[slot] != kNoCell)
        slot = (slot + 1) & (table_.size() - 1);
      table_[slot] = i;
    }
    pure_.assign(numCells(), kUnknown);
  }

  std::uint32_t numCells() const { return static_cast<std::uint32_t>(component_.size()); }
  std::int64_t coord(std::uint32_t v, int d) const { return coords_[3 * v + d]; }
  std::uint32_t component(std::uint32_t i) const { return component_[i]; }
  /// Steps (at most 2) within which every occupied cell holds cell i's component only;
  /// measured on first use (most cells belong to the component that is never scanned).
  std::uint8_t pureSteps(std::uint32_t i) {
    if (pure_[i] == kUnknown)
      pure_[i] = pureStepsOf(i);
    return pure_[i];
  }
  struct Range {
    const std::uint32_t *b, *e;
    const std::uint32_t* begin() const { return b; }
    const std::uint32_t* end() const { return e; }
  };
  Range points(std::uint32_t i) const {
    return {order_.data() + begin_[i], order_.data() + begin_[i + 1]};
  }

  /// The occupied cell at (x, y, z), or kNoCell.
  std::uint32_t find(std::int64_t x, std::int64_t y, std::int64_t z) const {
    for (std::size_t slot = hash(x, y, z);; slot = (slot + 1) & (table_.size() - 1)) {
      const std::uint32_t i = table_[slot];
      if (i == kNoCell)
        return kNoCell;
      const std::uint32_t v = order_[begin_[i]];
      if (coord(v, 0) == x && coord(v, 1) == y && coord(v, 2) == z)
        return i;
    }
  }

private:
  std::size_t hash(std::int64_t x, std::int64_t y, std::int64_t z) const {
    std::uint64_t h = static_cast<std::uint64_t>(x) * 0x9E3779B97F4A7C15ull;
    h ^= static_cast<std::uint64_t>(y) * 0xC2B2AE3D27D4EB4Full + (h << 6) + (h >> 2);
    h ^= static_cast<std::uint64_t>(z) * 0x165667B19E3779F9ull + (h << 6) + (h >> 2);
    h ^= h >> 29;
    return static_cast<std::size_t>(h) & (table_.size() - 1);
  }

  static constexpr std::uint8_t kUnknown = 0xFF;

  std::uint8_t pureStepsOf(std::uint32_t i) const {
    if (component_[i] == kMixed)
      return 0;
    const std::uint32_t v = order_[begin_[i]];
    const std::int64_t cx = coord(v, 0), cy = coord(v, 1), cz = coord(v, 2);
    std::uint8_t steps = 0;
    for (std::int64_t sp = 1; sp <= 2; ++sp) {
      for (std::int64_t x = cx - sp; x <= cx + sp; ++x)
        for (std::int64_t y = cy - sp; y <= cy + sp; ++y)
          for (std::int64_t z = cz - sp; z <= cz + sp; ++z) {
            const std::uint32_t j = find(x, y, z);
            if (j != kNoCell && component_[j] != component_[i])
              return steps;
          }
      steps = static_cast<std::uint8_t>(sp);
    }
    return steps;
  }

  std::vector<std::int64_t> coords_; ///< per point, its cell's x, y, z
  std::vector<std::uint32_t> order_; ///< the points by cell (then by index)
  std::vector<std::uint32_t> begin_; ///< cell i: order_[begin_[i], begin_[i + 1])
  std::vector<std::uint32_t> component_;
  std::vector<std::uint8_t> pure_;
  std::vector<std::uint32_t> table_; ///< open addressing: cell ids, kNoCell when free
};

/// A candidate bridge: length, p, q (p < q); tuples compare shortest first, then by points.
using Candidate = std::tuple<double, std::uint32_t, std::uint32_t>;

/// kNN radius of each vertex: its longest graph edge.
std::vector<double> knnRadii(const CsrGraph& graph) {
  const std::size_t n = graph.numVertices();
  std::vector<double> radius(n, 0.0);
  for (std::size_t v = 0; v < n; ++v)
    for (std::uint32_t e = graph.offsets[v]; e < graph.offsets[v + 1]; ++e)
      radius[v] = std::max(radius[v], static_cast<double>(graph.lengths[e]));
  return radius;
}

/// The median of the positive, finite reaches (the grid's cell size); 0 when there is none.
double medianReach(const std::vector<double>& reach) {
  std::vector<double> positive;
  for (double r : reach)
    if (r > 0.0 && std::isfinite(r))
      positive.push_back(r);
  if (positive.empty())
    return 0.0;
  std::nth_element(positive.begin(), positive.begin() + positive.size() / 2, positive.end());
  return positive[positive.size() / 2];
}

/// The shortest admissible pair per pair of components: no longer than either point's reach
/// (each point that looks, looks within its own, so a pair is found from either point).
class ShortestPairs {
public:
  ShortestPairs(const float* xyz, const std::vector<std::uint32_t>& comp,
                const std::vector<double>& reach, double cell, CellGrid& grid)
      : xyz_(xyz), comp_(comp), reach_(reach), cell_(cell), grid_(grid) {}

  /// Every pair p can reach, in the cells within its reach.
  void lookAround(std::uint32_t p) {
    const double span = std::ceil(reach_[p] / cell_);
    if (std::pow(2.0 * span + 1.0, 3) > static_cast<double>(grid_.numCells())) {
      // A reach wider than the occupied grid: every occupied cell.
      for (std::uint32_t i = 0; i < grid_.numCells(); ++i)
        if (grid_.component(i) != comp_[p])
          for (std::uint32_t q : grid_.points(i))
            consider(p, q);
      return;
    }
    const auto s = static_cast<std::int64_t>(span);
    const std::int64_t cx = grid_.coord(p, 0), cy = grid_.coord(p, 1), cz = grid_.coord(p, 2);
    const std::uint32_t own = grid_.find(cx, cy, cz);
    if (grid_.component(own) == comp_[p] && s <= grid_.pureSteps(own))
      return; // only p's own component within reach
    for (std::int64_t x = cx - s; x <= cx + s; ++x)
      for (std::int64_t y = cy - s; y <= cy + s; ++y)
        for (std::int64_t z = cz - s; z <= cz + s; ++z) {
          const std::uint32_t i = grid_.find(x, y, z);
          if (i == CellGrid::kNoCell || grid_.component(i) == comp_[p])
            continue;
          for (std::uint32_t q : grid_.points(i))
            consider(p, q);
        }
  }

  /// The pairs found, shortest first.
  std::vector<Candidate> sorted() const {
    std::vector<Candidate> candidates;
    for (const auto& [pair, c] : shortest_)
      candidates.push_back(c);
    std::sort(candidates.begin(), candidates.end());
    return candidates;
  }

private:
  void consider(std::uint32_t p, std::uint32_t q) {
    if (comp_[q] == comp_[p])
      return;
    const double d = pointDistance<double>(xyz_, p, q);
    if (!(d <= std::min(reach_[p], reach_[q])))
      return;
    const auto pair = std::minmax(comp_[p], comp_[q]);
    const Candidate c(d, std::min(p, q), std::max(p, q));
    const auto it = shortest_.find(pair);
    if (it == shortest_.end())
      shortest_.emplace(pair, c);
    else if (c < it->second)
      it->second = c;
  }

  const float* xyz_;
  const std::vector<std::uint32_t>& comp_;
  const std::vector<double>& reach_;
  const double cell_;
  CellGrid& grid_;
  std::map<std::pair<std::uint32_t, std::uint32_t>, Candidate> shortest_;
};

/// Bridges chosen by Kruskal over the components: candidates shortest first, each joining two
/// components not yet joined.
struct Bridges {
  std::vector<std::pair<std::uint32_t, std::uint32_t>> ends;
  std::vector<float> length;
};

Bridges kruskalBridges(const std::vector<Candidate>& candidates,
                       const std::vector<std::uint32_t>& comp, std::size_t num_comps,
                       const std::vector<double>& radius, std::vector<double>* bridge_ratios) {
  std::vector<std::uint32_t> parent(num_comps);
  std::iota(parent.begin(), parent.end(), 0u);
  auto find = [&](std::uint32_t c) {
    while (parent[c] != c)
      c = parent[c] = parent[parent[c]];
    return c;
  };
  Bridges out;
  for (const auto& [d, p, q] : candidates) {
    const std::uint32_t a = find(comp[p]), b = find(comp[q]);
    if (a == b)
      continue;
    parent[a] = b;
    out.ends.emplace_back(p, q);
    out.length.push_back(static_cast<float>(d));
    if (bridge_ratios)
      bridge_ratios->push_back(d / std::min(radius[p], radius[q]));
  }
  return out;
}

/// The graph with the bridges as edges (both directions), rows sorted by target.
CsrGraph withBridges(const CsrGraph& graph, const Bridges& bridges) {
  const std::size_t n = graph.numVertices();
  std::vector<std::vector<std::pair<std::uint32_t, float>>> extra(n);
  for (std::size_t i = 0; i < bridges.ends.size(); ++i) {
    extra[bridges.ends[i].first].emplace_back(bridges.ends[i].second, bridges.length[i]);
    extra[bridges.ends[i].second].emplace_back(bridges.ends[i].first, bridges.length[i]);
  }
  CsrGraph out;
  out.offsets.assign(n + 1, 0);
  for (std::size_t v = 0; v < n; ++v)
    out.offsets[v + 1] = out.offsets[v] + graph.degree(static_cast<std::uint32_t>(v)) +
                         static_cast<std::uint32_t>(extra[v].size());
  out.targets.reserve(out.offsets[n]);
  out.lengths.reserve(out.offsets[n]);
  std::vector<std::pair<std::uint32_t, float>> row;
  for (std::size_t v = 0; v < n; ++v) {
    row.assign(extra[v].begin(), extra[v].end());
    for (std::uint32_t e = graph.offsets[v]; e < graph.offsets[v + 1]; ++e)
      row.emplace_back(graph.targets[e], graph.lengths[e]);
    std::sort(row.begin(), row.end());
    for (const auto& [t, len] : row) {
      out.targets.push_back(t);
      out.lengths.push_back(len);
    }
  }
  return out;
}

} // namespace

std::size_t bridgeComponents(CsrGraph& graph, const float* xyz, double max_gap,
                             std::vector<double>* bridge_ratios) {
  const std::size_t n = graph.numVertices();
  if (n < 2 || !(max_gap > 0.0))
    return 0;
  std::vector<std::uint32_t> comp;
  const std::size_t num_comps = connectedComponents(graph, comp);
  if (num_comps < 2)
    return 0;

  const std::vector<double> radius = knnRadii(graph);
  std::vector<double> reach(n);
  for (std::size_t v = 0; v < n; ++v)
    reach[v] = max_gap * radius[v];
  const double cell = medianReach(reach);
  if (cell == 0.0)
    return 0; // every component is a single point or coincident points: no scale to bridge by

  // Uniform grid of cell size `cell`: the points sorted by cell, each occupied cell a range of
  // them, found through an open-addressing table on its integer coordinates.
  CellGrid grid(xyz, n, cell, comp);
  // A pair lies within both points' reach, so it is found from either side: the points of the
  // largest component (most of a view or a scan) need not look (ties: the smallest id).
  std::vector<std::size_t> size(num_comps, 0);
  for (std::uint32_t c : comp)
    ++size[c];
  const auto largest =
      static_cast<std::uint32_t>(std::max_element(size.begin(), size.end()) - size.begin());
  ShortestPairs pairs(xyz, comp, reach, cell, grid);
  for (std::uint32_t p = 0; p < n; ++p)
    if (comp[p] != largest && reach[p] > 0.0 && std::isfinite(reach[p]))
      pairs.lookAround(p);

  const Bridges bridges = kruskalBridges(pairs.sorted(), comp, num_comps, radius, bridge_ratios);
  if (bridges.ends.empty())
    return 0;
  graph = withBridges(graph, bridges);
  return bridges.ends.size();
}

} // namespace pcl_ncut_seg
