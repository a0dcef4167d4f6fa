// The medoid of several segmentations (see core/centrality/starts.h).
#include "core/centrality/starts.h"

#include <algorithm>

namespace pcl_ncut_seg {

namespace {
/// Sum over runs of equal keys of C(run, 2); keys sorted in place.
std::uint64_t pairsWithin(std::vector<std::uint64_t>& keys) {
  std::sort(keys.begin(), keys.end());
  std::uint64_t pairs = 0;
  for (std::size_t i = 0; i < keys.size();) {
    std::size_t j = i + 1;
    while (j < keys.size() && keys[j] == keys[i])
      ++j;
    const std::uint64_t run = j - i;
    pairs += run * (run - 1) / 2;
    i = j;
  }
  return pairs;
}
} // namespace

std::vector<std::uint32_t> centralRanks(const float* xyz, std::size_t n,
                                        const std::vector<std::uint32_t>& component) {
  const std::size_t c = component.size() == n && n > 0
                            ? 1 + *std::max_element(component.begin(), component.end())
                            : 1;
  std::vector<double> centre(3 * c, 0.0);
  if (c > 1) {
    std::vector<std::size_t> count(c, 0);
    for (std::size_t v = 0; v < n; ++v) {
      ++count[component[v]];
      for (int i = 0; i < 3; ++i)
        centre[3 * component[v] + i] += xyz[3 * v + i];
    }
    for (std::size_t k = 0; k < c; ++k)
      for (int i = 0; i < 3; ++i)
        centre[3 * k + i] /= static_cast<double>(count[k]);
  }
  std::vector<std::pair<double, std::uint32_t>> by_distance(n);
  for (std::size_t v = 0; v < n; ++v) {
    const double* o = centre.data() + (c > 1 ? 3 * component[v] : 0);
    const double x = xyz[3 * v] - o[0], y = xyz[3 * v + 1] - o[1], z = xyz[3 * v + 2] - o[2];
    by_distance[v] = {x * x + y * y + z * z, static_cast<std::uint32_t>(v)};
  }
  std::sort(by_distance.begin(), by_distance.end());
  std::vector<std::uint32_t> rank(n);
  for (std::size_t r = 0; r < n; ++r)
    rank[by_distance[r].second] = static_cast<std::uint32_t>(r);
  return rank;
}

std::uint64_t pairDisagreements(const std::vector<std::uint32_t>& a,
                                const std::vector<std::uint32_t>& b) {
  const std::size_t n = std::min(a.size(), b.size());
  if (n == 0)
    return 0;
  const std::uint64_t ta = 1u + *std::max_element(a.begin(), a.begin() + n);
  const std::uint64_t tb = 1u + *std::max_element(b.begin(), b.begin() + n);
  if (ta * tb <= n + 4096) {
    // Few labels (segments): pairs counted from the table of label pairs, in O(n), no sort.
    std::vector<std::uint64_t> count_a(ta, 0), count_b(tb, 0), joint(ta * tb, 0);
    for (std::size_t i = 0; i < n; ++i) {
      ++count_a[a[i]];
      ++count_b[b[i]];
      ++joint[a[i] * tb + b[i]];
    }
    const auto pairs = [](const std::vector<std::uint64_t>& counts) {
      std::uint64_t sum = 0;
      for (const std::uint64_t c : counts)
        if (c > 1)
          sum += c * (c - 1) / 2;
      return sum;
    };
    return pairs(count_a) + pairs(count_b) - 2 * pairs(joint);
  }
  std::vector<std::uint64_t> keys(a.begin(), a.begin() + n);
  const std::uint64_t together_a = pairsWithin(keys);
  keys.assign(b.begin(), b.begin() + n);
  const std::uint64_t together_b = pairsWithin(keys);
  for (std::size_t i = 0; i < n; ++i)
    keys[i] = (std::uint64_t(a[i]) << 32) | b[i];
  const std::uint64_t together_both = pairsWithin(keys);
  return together_a + together_b - 2 * together_both;
}

std::size_t medoidPartition(const std::vector<const std::vector<std::uint32_t>*>& partitions,
                            const std::vector<std::uint32_t>& weights) {
  const std::size_t m = partitions.size();
  auto weight = [&](std::size_t i) { return i < weights.size() ? weights[i] : 1u; };
  std::vector<std::uint64_t> sum(m, 0);
  for (std::size_t i = 0; i < m; ++i)
    for (std::size_t j = i + 1; j < m; ++j) {
      const std::uint64_t d = pairDisagreements(*partitions[i], *partitions[j]);
      sum[i] += weight(j) * d;
      sum[j] += weight(i) * d;
    }
  return static_cast<std::size_t>(std::min_element(sum.begin(), sum.end()) - sum.begin());
}

} // namespace pcl_ncut_seg
