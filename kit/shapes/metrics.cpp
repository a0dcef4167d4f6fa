#include "shapes/metrics.h"

#include <algorithm>
#include <cstdint>
#include <limits>
#include <map>
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

std::vector<MainSegment> mainSegments(const std::vector<int>& labels, const std::vector<int>& truth,
                                      int num_parts) {
  if (labels.size() != truth.size())
    throw std::invalid_argument("mainSegments: labelings of " + std::to_string(labels.size()) +
                                " and " + std::to_string(truth.size()) + " points");
  std::vector<std::map<int, std::size_t>> count(num_parts);
  std::vector<std::size_t> size(num_parts, 0);
  for (std::size_t i = 0; i < truth.size(); ++i) {
    if (labels[i] < 0 || truth[i] < 0)
      continue;
    if (truth[i] >= num_parts)
      throw std::invalid_argument("mainSegments: part " + std::to_string(truth[i]) + " of " +
                                  std::to_string(num_parts));
    ++count[truth[i]][labels[i]];
    ++size[truth[i]];
  }
  std::vector<MainSegment> out(num_parts);
  for (int p = 0; p < num_parts; ++p) {
    std::size_t best = 0;
    for (const auto& [segment, c] : count[p])
      if (c > best) {
        best = c;
        out[p].segment = segment;
      }
    out[p].share = size[p] == 0 ? 0.0 : double(best) / double(size[p]);
  }
  return out;
}

std::vector<int> kMeansLabels(const std::vector<float>& xyz, int k, int iterations) {
  const std::size_t n = xyz.size() / 3;
  if (n == 0)
    return {};
  k = std::max(1, std::min<int>(k, static_cast<int>(n)));
  auto sqr = [&](std::size_t i, const double* c) {
    double s = 0;
    for (int d = 0; d < 3; ++d)
      s += (xyz[3 * i + d] - c[d]) * (xyz[3 * i + d] - c[d]);
    return s;
  };
  // Farthest-point seeds: point 0, then each time the point farthest from the seeds so far.
  std::vector<double> centre;
  std::vector<double> nearest(n, std::numeric_limits<double>::infinity());
  std::size_t pick = 0;
  for (int j = 0; j < k; ++j) {
    for (int d = 0; d < 3; ++d)
      centre.push_back(xyz[3 * pick + d]);
    std::size_t farthest = 0;
    for (std::size_t i = 0; i < n; ++i) {
      nearest[i] = std::min(nearest[i], sqr(i, &centre[3 * j]));
      if (nearest[i] > nearest[farthest])
        farthest = i;
    }
    pick = farthest;
  }
  std::vector<int> label(n, -1);
  for (int it = 0; it < iterations; ++it) {
    bool changed = false;
    for (std::size_t i = 0; i < n; ++i) {
      int best = 0;
      double best_d = sqr(i, &centre[0]);
      for (int j = 1; j < k; ++j) {
        const double d = sqr(i, &centre[3 * j]);
        if (d < best_d)
          best = j, best_d = d;
      }
      changed |= label[i] != best;
      label[i] = best;
    }
    if (!changed)
      break;
    std::vector<double> sum(3 * k, 0.0), count(k, 0.0);
    for (std::size_t i = 0; i < n; ++i) {
      ++count[label[i]];
      for (int d = 0; d < 3; ++d)
        sum[3 * label[i] + d] += xyz[3 * i + d];
    }
    for (int j = 0; j < k; ++j)
      if (count[j] > 0)
        for (int d = 0; d < 3; ++d)
          centre[3 * j + d] = sum[3 * j + d] / count[j];
  }
  return label;
}

} // namespace test
} // namespace pcl_ncut_seg
