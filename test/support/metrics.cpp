#include "support/metrics.h"

#include <cstdint>
#include <stdexcept>
#include <string>
#include <unordered_map>

namespace pcl_ncut_seg {
namespace test {

namespace {

double pairs(double count) {
  return count * (count - 1.0) / 2.0;
}

/** \brief Dense ids for arbitrary labels, in order of first appearance. */
std::uint32_t denseId(std::unordered_map<int, std::uint32_t>& ids, int label) {
  return ids.emplace(label, static_cast<std::uint32_t>(ids.size())).first->second;
}

} // namespace

double randIndex(const std::vector<int>& a, const std::vector<int>& b) {
  if (a.size() != b.size())
    throw std::invalid_argument("randIndex: labelings of " + std::to_string(a.size()) + " and " +
                                std::to_string(b.size()) + " points");
  std::unordered_map<int, std::uint32_t> ids_a, ids_b;
  std::vector<double> count_a, count_b;
  std::unordered_map<std::uint64_t, double> table; // (id_a, id_b) -> points
  double n = 0;
  for (std::size_t i = 0; i < a.size(); ++i) {
    if (a[i] < 0 || b[i] < 0)
      continue;
    const std::uint32_t ia = denseId(ids_a, a[i]), ib = denseId(ids_b, b[i]);
    count_a.resize(ids_a.size(), 0.0);
    count_b.resize(ids_b.size(), 0.0);
    ++count_a[ia];
    ++count_b[ib];
    ++table[(std::uint64_t(ia) << 32) | ib];
    ++n;
  }
  if (n < 2)
    return 1.0;
  // Pairs together in a, in b, and in both; disagreements are together in exactly one.
  double together_a = 0, together_b = 0, together_both = 0;
  for (double c : count_a)
    together_a += pairs(c);
  for (double c : count_b)
    together_b += pairs(c);
  for (const auto& cell : table)
    together_both += pairs(cell.second);
  const double disagreements = together_a + together_b - 2.0 * together_both;
  return 1.0 - disagreements / pairs(n);
}

std::vector<int> segmentsToLabels(const std::vector<pcl::PointIndices>& segments, std::size_t n) {
  std::vector<int> labels(n, -1);
  for (std::size_t s = 0; s < segments.size(); ++s) {
    for (const auto index : segments[s].indices) {
      if (index < 0 || static_cast<std::size_t>(index) >= n)
        throw std::out_of_range("segmentsToLabels: index " + std::to_string(index) +
                                " outside a cloud of " + std::to_string(n) + " points");
      labels[index] = static_cast<int>(s);
    }
  }
  return labels;
}

} // namespace test
} // namespace pcl_ncut_seg
