// Joining kNN components separated by sampling gaps (an extension; see README).
#include <pcl_ncut_seg/core/bridging.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <map>
#include <numeric>
#include <tuple>
#include <unordered_map>

namespace pcl_ncut_seg {

namespace {
double distance(const float* xyz, std::size_t a, std::size_t b) {
  const float* pa = xyz + 3 * a;
  const float* pb = xyz + 3 * b;
  const double dx = pa[0] - pb[0], dy = pa[1] - pb[1], dz = pa[2] - pb[2];
  return std::sqrt(dx * dx + dy * dy + dz * dz);
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

  // kNN radius of each vertex: its longest graph edge.
  std::vector<double> radius(n, 0.0);
  for (std::size_t v = 0; v < n; ++v)
    for (std::uint32_t e = graph.offsets[v]; e < graph.offsets[v + 1]; ++e)
      radius[v] = std::max(radius[v], static_cast<double>(graph.lengths[e]));
  std::vector<double> reach(n);
  for (std::size_t v = 0; v < n; ++v)
    reach[v] = max_gap * radius[v];
  std::vector<double> positive;
  for (double r : reach)
    if (r > 0.0 && std::isfinite(r))
      positive.push_back(r);
  if (positive.empty())
    return 0; // every component is a single point or coincident points: no scale to bridge by
  std::nth_element(positive.begin(), positive.begin() + positive.size() / 2, positive.end());
  const double cell = positive[positive.size() / 2];

  // Uniform grid of cell size `cell`; each vertex looks for other components within its reach.
  auto coord = [&](std::size_t v, int d) {
    const double c = std::floor(xyz[3 * v + d] / cell);
    return static_cast<std::int64_t>(std::max(-1e15, std::min(1e15, c)));
  };
  auto key = [](std::int64_t x, std::int64_t y, std::int64_t z) {
    return (static_cast<std::uint64_t>(x) * 73856093u) ^
           (static_cast<std::uint64_t>(y) * 19349663u) ^
           (static_cast<std::uint64_t>(z) * 83492791u);
  };
  // Most cells hold one component and lie among cells of that component only: a vertex there
  // has no other component within one or two cells and skips the search, and no vertex reads
  // the points of a cell of its own component (the result is the same, without the scan).
  constexpr std::uint32_t kMixed = std::numeric_limits<std::uint32_t>::max();
  struct Cell {
    std::vector<std::uint32_t> points;
    std::uint32_t component = kMixed; ///< of all its points, or kMixed
    std::uint8_t pure_steps = 0;      ///< every cell within this many steps (<= 2): empty or same
  };
  std::unordered_map<std::uint64_t, Cell> grid;
  for (std::size_t v = 0; v < n; ++v)
    grid[key(coord(v, 0), coord(v, 1), coord(v, 2))].points.push_back(
        static_cast<std::uint32_t>(v));
  for (auto& [cell_key, c] : grid) {
    const std::uint32_t f = c.points.front();
    c.component = comp[f];
    for (std::uint32_t q : c.points) // two cells under one key (a hash collision): mixed
      if (comp[q] != comp[f] || coord(q, 0) != coord(f, 0) || coord(q, 1) != coord(f, 1) ||
          coord(q, 2) != coord(f, 2))
        c.component = kMixed;
  }
  for (auto& [cell_key, c] : grid) {
    if (c.component == kMixed)
      continue;
    const std::uint32_t f = c.points.front();
    const std::int64_t cx = coord(f, 0), cy = coord(f, 1), cz = coord(f, 2);
    for (std::int64_t sp = 1; sp <= 2; ++sp) {
      bool same = true;
      for (std::int64_t x = cx - sp; x <= cx + sp && same; ++x)
        for (std::int64_t y = cy - sp; y <= cy + sp && same; ++y)
          for (std::int64_t z = cz - sp; z <= cz + sp && same; ++z) {
            const auto it = grid.find(key(x, y, z));
            same = it == grid.end() || it->second.component == c.component;
          }
      if (!same)
        break;
      c.pure_steps = static_cast<std::uint8_t>(sp);
    }
  }

  // The shortest admissible pair per pair of components.
  using Candidate = std::tuple<double, std::uint32_t, std::uint32_t>; // length, p, q (p < q)
  std::map<std::pair<std::uint32_t, std::uint32_t>, Candidate> shortest;
  auto consider = [&](std::size_t p, std::uint32_t q) {
    if (q <= p || comp[q] == comp[p])
      return;
    const double d = distance(xyz, p, q);
    if (!(d <= std::max(reach[p], reach[q])))
      return;
    const auto pair = std::minmax(comp[p], comp[q]);
    const Candidate c(d, static_cast<std::uint32_t>(p), q);
    const auto it = shortest.find(pair);
    if (it == shortest.end())
      shortest.emplace(pair, c);
    else if (c < it->second)
      it->second = c;
  };
  for (std::size_t p = 0; p < n; ++p) {
    if (!(reach[p] > 0.0) || !std::isfinite(reach[p]))
      continue;
    const double span = std::ceil(reach[p] / cell);
    if (std::pow(2.0 * span + 1.0, 3) > static_cast<double>(grid.size())) {
      // A reach wider than the occupied grid: every occupied cell.
      for (const auto& [cell_key, c] : grid)
        for (std::uint32_t q : c.points)
          consider(p, q);
      continue;
    }
    const auto s = static_cast<std::int64_t>(span);
    const std::int64_t cx = coord(p, 0), cy = coord(p, 1), cz = coord(p, 2);
    const Cell& own = grid.find(key(cx, cy, cz))->second;
    if (own.component == comp[p] && s <= own.pure_steps)
      continue; // only p's own component within reach
    for (std::int64_t x = cx - s; x <= cx + s; ++x)
      for (std::int64_t y = cy - s; y <= cy + s; ++y)
        for (std::int64_t z = cz - s; z <= cz + s; ++z) {
          const auto it = grid.find(key(x, y, z));
          if (it == grid.end() || it->second.component == comp[p])
            continue;
          for (std::uint32_t q : it->second.points)
            consider(p, q);
        }
  }
  std::vector<Candidate> candidates;
  for (const auto& [pair, c] : shortest)
    candidates.push_back(c);
  std::sort(candidates.begin(), candidates.end());

  // Kruskal over the components.
  std::vector<std::uint32_t> parent(num_comps);
  std::iota(parent.begin(), parent.end(), 0u);
  auto find = [&](std::uint32_t c) {
    while (parent[c] != c)
      c = parent[c] = parent[parent[c]];
    return c;
  };
  std::vector<std::pair<std::uint32_t, std::uint32_t>> bridges;
  std::vector<float> bridge_length;
  for (const auto& [d, p, q] : candidates) {
    const std::uint32_t a = find(comp[p]), b = find(comp[q]);
    if (a == b)
      continue;
    parent[a] = b;
    bridges.emplace_back(p, q);
    bridge_length.push_back(static_cast<float>(d));
    if (bridge_ratios)
      bridge_ratios->push_back(d / std::max(radius[p], radius[q]));
  }
  if (bridges.empty())
    return 0;

  // Rebuild the CSR rows with the bridges (both directions), rows sorted by target.
  std::vector<std::vector<std::pair<std::uint32_t, float>>> extra(n);
  for (std::size_t i = 0; i < bridges.size(); ++i) {
    extra[bridges[i].first].emplace_back(bridges[i].second, bridge_length[i]);
    extra[bridges[i].second].emplace_back(bridges[i].first, bridge_length[i]);
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
  graph = std::move(out);
  return bridges.size();
}

} // namespace pcl_ncut_seg
