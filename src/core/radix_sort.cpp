#include <pcl_ncut_seg/core/radix_sort.h>

#include <numeric>

namespace pcl_ncut_seg {

std::vector<std::uint32_t> stableOrderByKey(const std::vector<std::uint32_t>& key) {
  const std::size_t n = key.size();
  std::vector<std::uint32_t> order(n), other(n);
  std::iota(order.begin(), order.end(), 0u);
  for (int shift = 0; shift < 32; shift += 11) {
    std::vector<std::size_t> start(2049, 0);
    for (std::uint32_t i : order)
      ++start[((key[i] >> shift) & 2047u) + 1];
    for (std::size_t b = 0; b < 2048; ++b)
      start[b + 1] += start[b];
    for (std::uint32_t i : order)
      other[start[(key[i] >> shift) & 2047u]++] = i;
    order.swap(other);
  }
  return order;
}

} // namespace pcl_ncut_seg
