// The resolution of the analysis (an extension; see core/graph/subsample.h).
#include "core/graph/subsample.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>
#include <vector>

namespace pcl_ncut_seg {

namespace {

std::uint64_t mix(std::uint64_t z) { // splitmix64's finaliser, to spread cube keys
  z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
  z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
  return z ^ (z >> 31);
}

/// Open-addressing table from a cube's key to a slot, numbered as first met (keys are never 0:
/// see CubeGrid::key). It grows as cubes come, so that a cloud of many points per cube does
/// not pay for a table of one slot per point.
class CubeTable {
public:
  explicit CubeTable(std::size_t capacity) { resize(capacity); }
  /// The slot of key, inserting it with the next free slot number if it is new.
  std::uint32_t slot(std::uint64_t key) {
    const std::size_t mask = keys_.size() - 1;
    for (std::size_t i = mix(key) & mask;; i = (i + 1) & mask) {
      if (keys_[i] == key)
        return slots_[i];
      if (keys_[i] == 0) {
        keys_[i] = key;
        slots_[i] = static_cast<std::uint32_t>(key_of_.size());
        key_of_.push_back(key);
        if (2 * key_of_.size() > keys_.size())
          resize(key_of_.size());
        return static_cast<std::uint32_t>(key_of_.size() - 1);
      }
    }
  }
  /// The slot of key, or kNone.
  std::uint32_t find(std::uint64_t key) const {
    const std::size_t mask = keys_.size() - 1;
    for (std::size_t i = mix(key) & mask;; i = (i + 1) & mask) {
      if (keys_[i] == key)
        return slots_[i];
      if (keys_[i] == 0)
        return kNone;
    }
  }
  std::uint32_t count() const { return static_cast<std::uint32_t>(key_of_.size()); }
  std::uint64_t keyOf(std::uint32_t slot) const { return key_of_[slot]; }

private:
  void resize(std::size_t capacity) {
    std::size_t size = 16;
    while (size < 2 * capacity)
      size *= 2;
    keys_.assign(size, 0);
    slots_.assign(size, 0);
    const std::size_t mask = size - 1;
    for (std::uint32_t s = 0; s < key_of_.size(); ++s) {
      std::size_t i = mix(key_of_[s]) & mask;
      while (keys_[i] != 0)
        i = (i + 1) & mask;
      keys_[i] = key_of_[s];
      slots_[i] = s;
    }
  }

  std::vector<std::uint64_t> keys_, key_of_;
  std::vector<std::uint32_t> slots_;
};

constexpr int kBits = 21; // per axis of a cube's key
constexpr std::int64_t kMaxCell = (std::int64_t(1) << kBits) - 1;

/// Cubes of one edge length from the points' lower bounding corner (so they move with the
/// points), 21 bits per axis.
struct CubeGrid {
  float lo[3];
  double edge;
  std::uint64_t key(const float* p) const {
    std::uint64_t k = 1; // a leading 1: no key is 0
    for (int d = 0; d < 3; ++d)
      k = (k << kBits) | static_cast<std::uint64_t>((p[d] - lo[d]) / edge);
    return k;
  }
  static std::uint64_t key(const std::int64_t cell[3]) {
    std::uint64_t k = 1;
    for (int d = 0; d < 3; ++d)
      k = (k << kBits) | static_cast<std::uint64_t>(cell[d]);
    return k;
  }
  static void cellOf(std::uint64_t key, std::int64_t cell[3]) {
    for (int d = 2; d >= 0; --d, key >>= kBits)
      cell[d] = static_cast<std::int64_t>(key & std::uint64_t(kMaxCell));
  }
  double toCentre(const float* p) const { // squared distance to the centre of p's cube
    double s = 0.0;
    for (int d = 0; d < 3; ++d) {
      const double c = (std::floor((p[d] - lo[d]) / edge) + 0.5) * edge + lo[d];
      s += (p[d] - c) * (p[d] - c);
    }
    return s;
  }
};

/// Per point, its cube's slot in the returned table.
CubeTable occupiedCubes(const float* raw, std::size_t m, std::size_t expected, const CubeGrid& grid,
                        std::vector<std::uint32_t>& cube) {
  CubeTable table(std::min(m, expected));
  cube.resize(m);
  for (std::size_t v = 0; v < m; ++v)
    cube[v] = table.slot(grid.key(raw + 3 * v));
  return table;
}

/// evenSubset()'s grid, with per point its cube and per cube its kept point.
struct EvenCubes {
  CubeGrid grid{{0, 0, 0}, 0.0};
  CubeTable table{0};
  std::vector<std::uint32_t> cube, kept;
};

EvenCubes evenCubes(const float* raw, std::size_t m, std::size_t max_points) {
  EvenCubes out;
  CubeGrid& grid = out.grid;
  grid = CubeGrid{{raw[0], raw[1], raw[2]}, 0.0};
  float hi[3] = {raw[0], raw[1], raw[2]};
  for (std::size_t v = 0; v < m; ++v)
    for (int d = 0; d < 3; ++d) {
      grid.lo[d] = std::min(grid.lo[d], raw[3 * v + d]);
      hi[d] = std::max(hi[d], raw[3 * v + d]);
    }
  double extent = 0.0, diagonal = 0.0;
  for (int d = 0; d < 3; ++d) {
    extent = std::max(extent, static_cast<double>(hi[d]) - grid.lo[d]);
    diagonal +=
        (static_cast<double>(hi[d]) - grid.lo[d]) * (static_cast<double>(hi[d]) - grid.lo[d]);
  }
  // A surface fills about (size / edge)^2 cubes: a few steps of edge *= sqrt(cubes / target)
  // reach between 97% and 100% of max_points; the edge never gets so small that a coordinate
  // needs more than 21 bits.
  const double min_edge = std::max(extent / double(kMaxCell - 1), 1e-30);
  grid.edge = std::max(std::sqrt(diagonal / static_cast<double>(max_points)), min_edge);
  std::vector<std::uint32_t>& cube = out.cube; // per point, its cube under the current edge
  out.table = occupiedCubes(raw, m, 2 * max_points, grid, cube);
  std::size_t cubes = out.table.count();
  for (int step = 0; step < 8 && (cubes > max_points || cubes < 0.97 * max_points); ++step) {
    if (cubes < max_points && grid.edge <= min_edge)
      break;
    grid.edge = std::max(grid.edge * std::sqrt(double(cubes) / double(max_points)), min_edge);
    out.table = occupiedCubes(raw, m, 2 * max_points, grid, cube);
    cubes = out.table.count();
  }
  while (cubes > max_points) {
    grid.edge *= 1.01;
    out.table = occupiedCubes(raw, m, 2 * max_points, grid, cube);
    cubes = out.table.count();
  }
  // In each cube, the point nearest its centre (ties by position: no order matters).
  std::vector<std::uint32_t>& best = out.kept;
  best.assign(cubes, kNone);
  std::vector<double> best_distance(cubes, 0.0);
  for (std::size_t v = 0; v < m; ++v) {
    const std::uint32_t c = cube[v];
    const double distance = grid.toCentre(raw + 3 * v);
    const std::uint32_t b = best[c];
    if (b == kNone || distance < best_distance[c] ||
        (distance == best_distance[c] &&
         std::lexicographical_compare(raw + 3 * v, raw + 3 * v + 3, raw + 3 * b,
                                      raw + 3 * b + 3))) {
      best[c] = static_cast<std::uint32_t>(v);
      best_distance[c] = distance;
    }
  }
  return out;
}

/// The vertices of the kept points of the cubes within `reach` cubes of cell (vertex[c]: the
/// vertex of cube c's kept point).
void keptAround(const EvenCubes& cubes, const std::vector<std::uint32_t>& vertex,
                const std::int64_t cell[3], int reach, std::vector<std::uint32_t>& out) {
  out.clear();
  std::int64_t at[3];
  for (at[0] = cell[0] - reach; at[0] <= cell[0] + reach; ++at[0])
    for (at[1] = cell[1] - reach; at[1] <= cell[1] + reach; ++at[1])
      for (at[2] = cell[2] - reach; at[2] <= cell[2] + reach; ++at[2]) {
        if (std::min({at[0], at[1], at[2]}) < 0 || std::max({at[0], at[1], at[2]}) > kMaxCell)
          continue;
        const std::uint32_t c = cubes.table.find(CubeGrid::key(at));
        if (c != kNone)
          out.push_back(vertex[c]);
      }
}

/// A candidate kept point: its position and vertex.
struct Candidate {
  float x, y, z;
  std::uint32_t vertex;
};

/// The nearest of the candidates to p, ties to the smaller vertex; d2 its squared distance.
std::uint32_t nearestOf(const Candidate* begin, const Candidate* end, const float* p, double& d2) {
  std::uint32_t best = kNone;
  d2 = std::numeric_limits<double>::infinity();
  for (const Candidate* q = begin; q != end; ++q) {
    const double dx = double(p[0]) - q->x, dy = double(p[1]) - q->y, dz = double(p[2]) - q->z;
    const double s = dx * dx + dy * dy + dz * dz;
    if (s < d2 || (s == d2 && q->vertex < best)) {
      d2 = s;
      best = q->vertex;
    }
  }
  return best;
}

/// Per dropped point, (point, the vertex of its nearest kept point), in index order: one pass
/// over the points, in their order (their memory is read once, in sequence). The kept points
/// of a point's cube's 3 x 3 x 3 block are its candidates; any other kept point lies beyond
/// the block's border, so the nearest candidate is the nearest kept point when it is no
/// farther than that border. Otherwise (rarely: an even subset keeps each cube's point nearest
/// its centre) the 5 x 5 x 5 block, which always holds it: the point's own cube's kept point is
/// within sqrt(3) edges. Ties to the smaller vertex.
std::vector<std::pair<std::uint32_t, std::uint32_t>>
nearestKept(const float* raw, std::size_t n, const EvenCubes& cubes,
            const std::vector<std::uint32_t>& vertex, const float* raw_vertex, int num_threads) {
  const std::size_t c = cubes.kept.size();
  const auto candidate = [&](std::uint32_t u) {
    const float* q = raw_vertex + 3 * std::size_t(u);
    return Candidate{q[0], q[1], q[2], u};
  };
  // Per cube, the kept points of its block: at most 27, found in parallel, then packed.
  std::vector<std::uint32_t> block27(27 * c);
  std::vector<std::size_t> begin(c + 1, 0);
#pragma omp parallel num_threads(num_threads)
  {
    std::vector<std::uint32_t> block;
#pragma omp for schedule(static, 1024)
    for (std::ptrdiff_t ci = 0; ci < static_cast<std::ptrdiff_t>(c); ++ci) {
      std::int64_t cell[3];
      CubeGrid::cellOf(cubes.table.keyOf(static_cast<std::uint32_t>(ci)), cell);
      keptAround(cubes, vertex, cell, 1, block);
      std::copy(block.begin(), block.end(), block27.begin() + 27 * ci);
      begin[ci + 1] = block.size();
    }
  }
  std::partial_sum(begin.begin(), begin.end(), begin.begin());
  std::vector<Candidate> flat(begin[c]);
#pragma omp parallel for num_threads(num_threads) schedule(static, 1024)
  for (std::ptrdiff_t ci = 0; ci < static_cast<std::ptrdiff_t>(c); ++ci)
    for (std::size_t j = 0; j < begin[ci + 1] - begin[ci]; ++j)
      flat[begin[ci] + j] = candidate(block27[27 * ci + j]);
  std::vector<std::uint32_t>().swap(block27);
  std::vector<std::uint32_t> nearest(n, kNone);
  const CubeGrid& grid = cubes.grid;
#pragma omp parallel num_threads(num_threads)
  {
    std::vector<std::uint32_t> block;
    std::vector<Candidate> wide;
#pragma omp for schedule(static, 65536)
    for (std::ptrdiff_t vi = 0; vi < static_cast<std::ptrdiff_t>(n); ++vi) {
      const auto v = static_cast<std::uint32_t>(vi);
      const std::uint32_t cube = cubes.cube[v];
      if (v == cubes.kept[cube])
        continue;
      const float* p = raw + 3 * std::size_t(v);
      std::int64_t cell[3];
      CubeGrid::cellOf(cubes.table.keyOf(cube), cell);
      double margin = 1.0; // to the nearer face of its cube, in edges
      for (int d = 0; d < 3; ++d) {
        const double f = (p[d] - grid.lo[d]) / grid.edge - static_cast<double>(cell[d]);
        margin = std::min({margin, f, 1.0 - f});
      }
      const double border = grid.edge * (1.0 + std::max(margin, 0.0)) * (1.0 - 1e-9);
      double d2 = 0.0;
      std::uint32_t best =
          nearestOf(flat.data() + begin[cube], flat.data() + begin[cube + 1], p, d2);
      if (!(d2 <= border * border)) {
        keptAround(cubes, vertex, cell, 2, block);
        wide.clear();
        for (const std::uint32_t u : block)
          wide.push_back(candidate(u));
        best = nearestOf(wide.data(), wide.data() + wide.size(), p, d2);
      }
      nearest[v] = best;
    }
  }
  std::vector<std::pair<std::uint32_t, std::uint32_t>> copies;
  copies.reserve(n - c);
  for (std::size_t v = 0; v < n; ++v)
    if (nearest[v] != kNone)
      copies.emplace_back(static_cast<std::uint32_t>(v), nearest[v]);
  return copies;
}

} // namespace

std::vector<char> evenSubset(const float* raw, std::size_t m, std::size_t max_points,
                             double* cube_edge) {
  std::vector<char> keep(m, 0);
  if (m == 0 || max_points == 0)
    return keep;
  const EvenCubes cubes = evenCubes(raw, m, max_points);
  for (std::uint32_t b : cubes.kept)
    keep[b] = 1;
  if (cube_edge)
    *cube_edge = cubes.grid.edge;
  return keep;
}

PreparedPoints prepareAtResolution(std::vector<float> xyz, std::size_t max_points,
                                   int num_threads) {
  const std::size_t n = xyz.size() / 3;
  if (max_points == 0 || n <= max_points)
    return preparePoints(std::move(xyz));
  // The subset first, so that only the kept points are sorted along the Morton curve. Copies
  // of a position share its cube; the first of them in index order is kept, if any.
  const EvenCubes cubes = evenCubes(xyz.data(), n, max_points);
  std::vector<std::uint32_t> kept_index(cubes.kept);
  std::sort(kept_index.begin(), kept_index.end());
  std::vector<float> kept_xyz;
  kept_xyz.reserve(3 * kept_index.size());
  for (const std::uint32_t v : kept_index)
    kept_xyz.insert(kept_xyz.end(), xyz.begin() + 3 * v, xyz.begin() + 3 * v + 3);
  const MortonBox box = mortonBox(xyz.data(), n);
  PreparedPoints out = preparePoints(std::move(kept_xyz), &box);
  for (std::uint32_t& p : out.point)
    p = kept_index[p];
  std::vector<std::uint32_t> vertex(cubes.kept.size()); // per cube, its kept point's vertex
  for (std::uint32_t v = 0; v < out.point.size(); ++v)
    vertex[cubes.cube[out.point[v]]] = v;
  out.copies = nearestKept(xyz.data(), n, cubes, vertex, out.raw.data(), num_threads);
  return out;
}

} // namespace pcl_ncut_seg
