// The resolution of the analysis (an extension; see core/subsample.h).
#include <pcl_ncut_seg/core/subsample.h>

#include <flann/algorithms/dist.h>
#include <flann/algorithms/kdtree_single_index.h>
#include <flann/util/result_set.h>

#include <algorithm>
#include <cmath>
#include <numeric>
#include <vector>

namespace pcl_ncut_seg {

namespace {

std::uint64_t mix(std::uint64_t z) { // splitmix64's finaliser, to spread cube keys
  z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
  z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
  return z ^ (z >> 31);
}

/// Open-addressing table from a cube's key to a slot (keys are never 0: see CubeGrid::key).
class CubeTable {
public:
  explicit CubeTable(std::size_t capacity) {
    std::size_t size = 16;
    while (size < 2 * capacity)
      size *= 2;
    keys_.assign(size, 0);
    slots_.assign(size, 0);
  }
  /// The slot of key, inserting it with the next free slot number if it is new.
  std::uint32_t slot(std::uint64_t key) {
    const std::size_t mask = keys_.size() - 1;
    for (std::size_t i = mix(key) & mask;; i = (i + 1) & mask) {
      if (keys_[i] == key)
        return slots_[i];
      if (keys_[i] == 0) {
        keys_[i] = key;
        slots_[i] = count_;
        return count_++;
      }
    }
  }
  std::uint32_t count() const { return count_; }

private:
  std::vector<std::uint64_t> keys_;
  std::vector<std::uint32_t> slots_;
  std::uint32_t count_ = 0;
};

/// Cubes of one edge length from the points' lower bounding corner (so they move with the
/// points), 21 bits per axis.
struct CubeGrid {
  float lo[3];
  double edge;
  std::uint64_t key(const float* p) const {
    std::uint64_t k = 1; // a leading 1: no key is 0
    for (int d = 0; d < 3; ++d)
      k = (k << 21) | static_cast<std::uint64_t>((p[d] - lo[d]) / edge);
    return k;
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

/// Per point, its cube's number (numbered as first met); returns the number of cubes.
std::size_t occupiedCubes(const float* raw, std::size_t m, const CubeGrid& grid,
                          std::vector<std::uint32_t>& cube) {
  CubeTable table(m);
  cube.resize(m);
  for (std::size_t v = 0; v < m; ++v)
    cube[v] = table.slot(grid.key(raw + 3 * v));
  return table.count();
}

} // namespace

std::vector<char> evenSubset(const float* raw, std::size_t m, std::size_t max_points,
                             double* cube_edge) {
  std::vector<char> keep(m, 0);
  if (m == 0 || max_points == 0)
    return keep;
  CubeGrid grid{{raw[0], raw[1], raw[2]}, 0.0};
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
  const double min_edge = std::max(extent / double((1u << 21) - 2), 1e-30);
  grid.edge = std::max(std::sqrt(diagonal / static_cast<double>(max_points)), min_edge);
  std::vector<std::uint32_t> cube; // per point, its cube under the current edge
  std::size_t cubes = occupiedCubes(raw, m, grid, cube);
  for (int step = 0; step < 8 && (cubes > max_points || cubes < 0.97 * max_points); ++step) {
    if (cubes < max_points && grid.edge <= min_edge)
      break;
    grid.edge = std::max(grid.edge * std::sqrt(double(cubes) / double(max_points)), min_edge);
    cubes = occupiedCubes(raw, m, grid, cube);
  }
  while (cubes > max_points) {
    grid.edge *= 1.01;
    cubes = occupiedCubes(raw, m, grid, cube);
  }
  // In each cube, the point nearest its centre (ties by position: no order matters).
  std::vector<std::uint32_t> best(cubes, kNone);
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
  for (std::uint32_t b : best)
    keep[b] = 1;
  if (cube_edge)
    *cube_edge = grid.edge;
  return keep;
}

namespace {

/// Per point, the new id of its nearest kept point (its own for a kept one), by FLANN's exact
/// single kd-tree over the kept points (as knn.cpp); the same for any number of threads.
std::vector<std::uint32_t> nearestKept(const float* raw, std::size_t m,
                                       const std::vector<char>& keep,
                                       const std::vector<std::uint32_t>& new_id,
                                       std::vector<float>& kept_raw, int num_threads) {
  using Index = flann::KDTreeSingleIndex<flann::L2_Simple<float>>;
  Index index(flann::Matrix<float>(kept_raw.data(), kept_raw.size() / 3, 3),
              flann::KDTreeSingleIndexParams(15));
  index.buildIndex();
  const flann::SearchParams search(-1, 0.0f, true);
  std::vector<std::uint32_t> nearest(m);
#pragma omp parallel num_threads(num_threads)
  {
    flann::KNNSimpleResultSet<float> result(1);
    std::size_t id = 0;
    float dist = 0.0f;
#pragma omp for schedule(dynamic, 4096)
    for (std::ptrdiff_t sv = 0; sv < static_cast<std::ptrdiff_t>(m); ++sv) {
      const auto v = static_cast<std::size_t>(sv);
      if (keep[v]) {
        nearest[v] = new_id[v];
        continue;
      }
      result.clear();
      index.findNeighbors(result, raw + 3 * v, search);
      result.copy(&id, &dist, 1, false);
      nearest[v] = static_cast<std::uint32_t>(id);
    }
  }
  return nearest;
}

} // namespace

std::size_t subsamplePoints(PreparedPoints& prepared, std::size_t max_points, int num_threads) {
  const std::size_t m = prepared.point.size();
  if (max_points == 0 || m <= max_points)
    return 0;
  const float* raw = prepared.raw.data();
  const std::vector<char> keep = evenSubset(raw, m, max_points);
  const auto kept = static_cast<std::size_t>(std::count(keep.begin(), keep.end(), 1));

  // Kept vertices, renumbered in their Morton order.
  std::vector<std::uint32_t> new_id(m, kNone);
  std::vector<float> kept_raw;
  kept_raw.reserve(3 * kept);
  std::uint32_t next = 0;
  for (std::size_t v = 0; v < m; ++v)
    if (keep[v]) {
      new_id[v] = next++;
      kept_raw.insert(kept_raw.end(), raw + 3 * v, raw + 3 * v + 3);
    }
  const std::vector<std::uint32_t> nearest =
      nearestKept(raw, m, keep, new_id, kept_raw, num_threads);
  // Copies of any vertex follow it to its nearest kept point; dropped vertices become copies.
  for (auto& copy : prepared.copies)
    copy.second = nearest[copy.second];
  for (std::size_t v = 0; v < m; ++v)
    if (!keep[v])
      prepared.copies.emplace_back(prepared.point[v], nearest[v]);
  // Compact the per-vertex arrays to the kept vertices.
  PointSet& set = prepared.set;
  std::size_t w = 0;
  for (std::size_t v = 0; v < m; ++v) {
    if (!keep[v])
      continue;
    for (int d = 0; d < 3; ++d)
      prepared.raw[3 * w + d] = prepared.raw[3 * v + d];
    prepared.point[w] = prepared.point[v];
    if (!set.order.empty())
      set.order[w] = set.order[v];
    ++w;
  }
  prepared.raw.resize(3 * w);
  prepared.raw.shrink_to_fit();
  centrePoints(prepared); // as preparePoints() centres the kept points alone
  prepared.point.resize(w);
  if (!set.order.empty()) { // dense ranks again, in the same order
    set.order.resize(w);
    std::vector<std::uint32_t> by_rank(w);
    std::iota(by_rank.begin(), by_rank.end(), 0u);
    std::sort(by_rank.begin(), by_rank.end(),
              [&](std::uint32_t a, std::uint32_t b) { return set.order[a] < set.order[b]; });
    for (std::size_t r = 0; r < w; ++r)
      set.order[by_rank[r]] = static_cast<std::uint32_t>(r);
  }
  return m - w;
}

} // namespace pcl_ncut_seg
