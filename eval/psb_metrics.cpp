// The benchmark's metrics from the area-weighted contingency table of two labelings.
#include "psb_metrics.h"

#include <algorithm>
#include <map>
#include <stdexcept>
#include <unordered_map>
#include <utility>

namespace pcl_ncut_seg {
namespace {

/** \brief Labels renumbered 0..k-1 in order of first appearance; every negative label -> one
 * shared segment. */
std::vector<std::size_t> compact(const std::vector<int>& labels, std::size_t& count) {
  std::unordered_map<int, std::size_t> id;
  std::vector<std::size_t> out(labels.size());
  for (std::size_t f = 0; f < labels.size(); ++f) {
    const int key = labels[f] < 0 ? -1 : labels[f];
    out[f] = id.emplace(key, id.size()).first->second;
  }
  count = id.size();
  return out;
}

double choose2(double n) {
  return n * (n - 1.0) / 2.0;
}

} // namespace

SegmentationScores compareSegmentations(const std::vector<int>& segmentation,
                                        const std::vector<int>& reference,
                                        const std::vector<double>& area) {
  const std::size_t n = segmentation.size();
  if (reference.size() != n || (!area.empty() && area.size() != n))
    throw std::invalid_argument("compareSegmentations: one label and one area per face");
  if (n == 0)
    throw std::invalid_argument("compareSegmentations: no faces");

  std::vector<double> weight(n, 1.0);
  double total = 0.0;
  if (!area.empty()) {
    for (std::size_t f = 0; f < n; ++f) {
      if (!(area[f] >= 0.0))
        throw std::invalid_argument("compareSegmentations: negative or NaN area");
      total += area[f];
    }
    if (total > 0.0)
      weight = area;
  }
  total = 0.0;
  for (double w : weight)
    total += w;

  std::size_t k1 = 0, k2 = 0;
  const std::vector<std::size_t> s1 = compact(segmentation, k1);
  const std::vector<std::size_t> s2 = compact(reference, k2);

  // Contingency table: face counts (Rand index) and areas (the others).
  std::map<std::pair<std::size_t, std::size_t>, std::pair<double, double>> cell;
  std::vector<double> count1(k1, 0), count2(k2, 0), area1(k1, 0), area2(k2, 0);
  for (std::size_t f = 0; f < n; ++f) {
    auto& c = cell[{s1[f], s2[f]}];
    c.first += 1;
    c.second += weight[f];
    count1[s1[f]] += 1;
    count2[s2[f]] += 1;
    area1[s1[f]] += weight[f];
    area2[s2[f]] += weight[f];
  }

  SegmentationScores s;
  // Rand index: pairs together in both + pairs apart in both, over all pairs.
  if (n >= 2) {
    double same1 = 0, same2 = 0, same12 = 0;
    for (double c : count1)
      same1 += choose2(c);
    for (double c : count2)
      same2 += choose2(c);
    for (const auto& [key, c] : cell)
      same12 += choose2(c.first);
    const double pairs = choose2(static_cast<double>(n));
    const double agree = pairs - same1 - same2 + 2.0 * same12;
    s.rand_index_error = 1.0 - agree / pairs;
  }

  // Directional Hamming distances from the largest overlap of each segment.
  std::vector<double> best_for_1(k1, 0), best_for_2(k2, 0);
  for (const auto& [key, c] : cell) {
    best_for_1[key.first] = std::max(best_for_1[key.first], c.second);
    best_for_2[key.second] = std::max(best_for_2[key.second], c.second);
  }
  double covered2 = 0, covered1 = 0;
  for (double b : best_for_2)
    covered2 += b;
  for (double b : best_for_1)
    covered1 += b;
  s.hamming_rm = std::max(0.0, (total - covered2) / total);
  s.hamming_rf = std::max(0.0, (total - covered1) / total);
  s.hamming = 0.5 * (s.hamming_rm + s.hamming_rf);

  // Consistency errors: every face of a cell has the same E(S1,S2,f) and E(S2,S1,f).
  double sum12 = 0, sum21 = 0, local = 0;
  for (const auto& [key, c] : cell) {
    const double a1 = area1[key.first], a2 = area2[key.second];
    const double e12 = a1 > 0 ? (a1 - c.second) / a1 : 0.0;
    const double e21 = a2 > 0 ? (a2 - c.second) / a2 : 0.0;
    sum12 += c.second * e12;
    sum21 += c.second * e21;
    local += c.second * std::min(e12, e21);
  }
  s.gce = std::max(0.0, std::min(sum12, sum21) / total);
  s.lce = std::max(0.0, local / total);
  return s;
}

SegmentationScores& operator+=(SegmentationScores& a, const SegmentationScores& b) {
  a.rand_index_error += b.rand_index_error;
  a.hamming += b.hamming;
  a.hamming_rm += b.hamming_rm;
  a.hamming_rf += b.hamming_rf;
  a.gce += b.gce;
  a.lce += b.lce;
  return a;
}

SegmentationScores operator/(SegmentationScores a, double d) {
  a.rand_index_error /= d;
  a.hamming /= d;
  a.hamming_rm /= d;
  a.hamming_rf /= d;
  a.gce /= d;
  a.lce /= d;
  return a;
}

std::string psbCategory(int id) {
  static const char* const names[] = {"Human", "Cup",     "Glasses", "Airplane", "Ant",
                                      "Chair", "Octopus", "Table",   "Teddy",    "Hand",
                                      "Plier", "Fish",    "Bird",    "Spring",   "Armadillo",
                                      "Bust",  "Mech",    "Bearing", "Vase",     "Fourleg"};
  if (id < 1 || id > 400)
    return {};
  return names[(id - 1) / 20];
}

} // namespace pcl_ncut_seg
