// The resolution of the analysis (an extension; see core/subsample.h).
#include <pcl_ncut_seg/core/subsample.h>

#include <flann/algorithms/dist.h>
#include <flann/algorithms/kdtree_single_index.h>
#include <flann/util/result_set.h>

#include <algorithm>
#include <cstring>
#include <numeric>
#include <tuple>
#include <vector>

namespace pcl_ncut_seg {

namespace {

std::uint64_t mix(std::uint64_t z) { // splitmix64's finaliser
  z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
  z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
  return z ^ (z >> 31);
}

/// Per point, 1 for the max_points with the smallest (positionHash(), position): a random subset
/// fixed by the positions alone.
std::vector<char> smallestHashes(const float* raw, std::size_t m, std::size_t max_points) {
  std::vector<std::uint64_t> hash(m);
  for (std::size_t v = 0; v < m; ++v)
    hash[v] = positionHash(raw + 3 * v);
  auto before = [&](std::uint32_t a, std::uint32_t b) {
    if (hash[a] != hash[b])
      return hash[a] < hash[b];
    return std::lexicographical_compare(raw + 3 * a, raw + 3 * a + 3, raw + 3 * b, raw + 3 * b + 3);
  };
  std::vector<std::uint32_t> by_hash(m);
  std::iota(by_hash.begin(), by_hash.end(), 0u);
  std::nth_element(by_hash.begin(), by_hash.begin() + static_cast<std::ptrdiff_t>(max_points),
                   by_hash.end(), before);
  std::vector<char> keep(m, 0);
  for (std::size_t i = 0; i < max_points; ++i)
    keep[by_hash[i]] = 1;
  return keep;
}

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

std::uint64_t positionHash(const float* xyz) {
  std::uint64_t h = 0x9E3779B97F4A7C15ull;
  for (int d = 0; d < 3; ++d) {
    const float v = xyz[d] == 0.0f ? 0.0f : xyz[d]; // -0 and +0 are one position
    std::uint32_t bits;
    std::memcpy(&bits, &v, sizeof bits);
    h = mix(h ^ (bits + 0x9E3779B97F4A7C15ull * static_cast<std::uint64_t>(d + 1)));
  }
  return h;
}

std::size_t subsamplePoints(PreparedPoints& prepared, std::size_t max_points, int num_threads) {
  const std::size_t m = prepared.point.size();
  if (max_points == 0 || m <= max_points)
    return 0;
  const float* raw = prepared.raw.data();
  const std::vector<char> keep = smallestHashes(raw, m, max_points);

  // Kept vertices, renumbered in their Morton order.
  std::vector<std::uint32_t> new_id(m, kNone);
  std::vector<float> kept_raw;
  kept_raw.reserve(3 * max_points);
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
