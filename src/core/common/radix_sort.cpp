#include "core/common/radix_sort.h"

#include <array>
#include <numeric>

namespace pcl_ncut_seg {

std::vector<std::uint32_t> stableOrderByKey(const std::vector<std::uint32_t>& key) {
  const std::size_t n = key.size();
  constexpr int kPasses = 3; // 11 + 11 + 10 bits
  // The three passes' bucket starts, counted in one pass over the keys in index order: the
  // later passes read the keys in the order of the one before, at random.
  std::vector<std::array<std::size_t, 2049>> start(kPasses);
  for (auto& s : start)
    s.fill(0);
  for (std::uint32_t k : key)
    for (int pass = 0; pass < kPasses; ++pass)
      ++start[pass][((k >> (11 * pass)) & 2047u) + 1];
  std::vector<std::uint32_t> order(n), other(n);
  std::iota(order.begin(), order.end(), 0u);
  for (int pass = 0; pass < kPasses; ++pass) {
    const int shift = 11 * pass;
    auto& s = start[pass];
    for (std::size_t b = 0; b < 2048; ++b)
      s[b + 1] += s[b];
    for (std::uint32_t i : order)
      other[s[(key[i] >> shift) & 2047u]++] = i;
    order.swap(other);
  }
  return order;
}

std::vector<std::uint32_t> descendingOrder(const std::vector<float>& value) {
  std::vector<std::uint32_t> key(value.size());
  for (std::size_t i = 0; i < value.size(); ++i)
    key[i] = descendingKey(value[i]);
  return stableOrderByKey(key);
}

} // namespace pcl_ncut_seg
