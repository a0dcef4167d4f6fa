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

/// Per dropped point (keep[v] == 0), (v, its nearest kept vertex) by FLANN's exact single
/// kd-tree over the kept vertices (as knn.cpp), in index order; the same for any threads.
std::vector<std::pair<std::uint32_t, std::uint32_t>> nearestKept(const float* xyz, std::size_t n,
                                                                 const std::vector<char>& keep,
                                                                 std::vector<float>& kept_raw,
                                                                 int num_threads) {
  using Index = flann::KDTreeSingleIndex<flann::L2_Simple<float>>;
  Index index(flann::Matrix<float>(kept_raw.data(), kept_raw.size() / 3, 3),
              flann::KDTreeSingleIndexParams(15));
  index.buildIndex();
  const flann::SearchParams search(-1, 0.0f, true);
  std::vector<std::pair<std::uint32_t, std::uint32_t>> copies;
  copies.reserve(n - kept_raw.size() / 3);
  for (std::size_t v = 0; v < n; ++v)
    if (!keep[v])
      copies.emplace_back(static_cast<std::uint32_t>(v), 0u);
#pragma omp parallel num_threads(num_threads)
  {
    flann::KNNSimpleResultSet<float> result(1);
    std::size_t id = 0;
    float dist = 0.0f;
#pragma omp for schedule(dynamic, 4096)
    for (std::ptrdiff_t i = 0; i < static_cast<std::ptrdiff_t>(copies.size()); ++i) {
      result.clear();
      index.findNeighbors(result, xyz + 3 * std::size_t(copies[i].first), search);
      result.copy(&id, &dist, 1, false);
      copies[i].second = static_cast<std::uint32_t>(id);
    }
  }
  return copies;
}

} // namespace

PreparedPoints prepareAtResolution(std::vector<float> xyz, std::size_t max_points,
                                   int num_threads) {
  const std::size_t n = xyz.size() / 3;
  if (max_points == 0 || n <= max_points)
    return preparePoints(std::move(xyz));
  // The subset first, so that only the kept points are sorted along the Morton curve. Copies
  // of a position share its cube; the first of them in index order is kept, if any.
  const std::vector<char> keep = evenSubset(xyz.data(), n, max_points);
  std::vector<std::uint32_t> kept_index;
  std::vector<float> kept_xyz;
  for (std::size_t v = 0; v < n; ++v)
    if (keep[v]) {
      kept_index.push_back(static_cast<std::uint32_t>(v));
      kept_xyz.insert(kept_xyz.end(), xyz.begin() + 3 * v, xyz.begin() + 3 * v + 3);
    }
  const MortonBox box = mortonBox(xyz.data(), n);
  PreparedPoints out = preparePoints(std::move(kept_xyz), &box);
  for (std::uint32_t& p : out.point)
    p = kept_index[p];
  out.copies = nearestKept(xyz.data(), n, keep, out.raw, num_threads);
  return out;
}

} // namespace pcl_ncut_seg
