// The short-cut stopping rule for the hierarchy of Sec. 5.2 (see core/short_cut.h).
#include <pcl_ncut_seg/core/short_cut.h>

#include <algorithm>
#include <cmath>

namespace pcl_ncut_seg {

namespace {
constexpr double kPi = 3.14159265358979323846;
} // namespace

NeckMeasure::NeckMeasure(const CsrGraph& graph, const std::vector<std::uint32_t>& label,
                         std::size_t num_supernodes)
    : area_(num_supernodes, 0.0) {
  const std::size_t n = graph.numVertices();
  border_offsets_.push_back(0);
  std::vector<std::uint32_t> others;
  for (std::size_t p = 0; p < n; ++p) {
    double sum = 0.0;
    const std::uint32_t deg = graph.degree(static_cast<std::uint32_t>(p));
    others.clear();
    for (std::uint32_t e = graph.offsets[p]; e < graph.offsets[p + 1]; ++e) {
      sum += graph.lengths[e];
      const std::uint32_t t = label[graph.targets[e]];
      if (t != label[p])
        others.push_back(t);
    }
    const double r = deg > 0 ? sum / deg : 0.0;
    area_[label[p]] += kPi * r * r;
    if (others.empty())
      continue;
    std::sort(others.begin(), others.end());
    others.erase(std::unique(others.begin(), others.end()), others.end());
    border_label_.push_back(label[p]);
    border_length_.push_back(2.0 * r);
    border_neighbours_.insert(border_neighbours_.end(), others.begin(), others.end());
    border_offsets_.push_back(static_cast<std::uint32_t>(border_neighbours_.size()));
  }
}

double NeckMeasure::neck(const std::vector<std::int8_t>& side) const {
  double area[2] = {0.0, 0.0}, length[2] = {0.0, 0.0};
  for (std::size_t s = 0; s < area_.size() && s < side.size(); ++s)
    if (side[s] >= 0)
      area[side[s] != 0] += area_[s];
  for (std::size_t b = 0; b < border_label_.size(); ++b) {
    const std::uint32_t s = border_label_[b];
    if (s >= side.size() || side[s] < 0)
      continue;
    for (std::uint32_t i = border_offsets_[b]; i < border_offsets_[b + 1]; ++i) {
      const std::uint32_t t = border_neighbours_[i];
      if (t < side.size() && side[t] >= 0 && side[t] != side[s]) {
        length[side[s] != 0] += border_length_[b];
        break;
      }
    }
  }
  const double smaller = std::min(area[0], area[1]);
  if (!(smaller > 0.0))
    return 0.0;
  return 0.5 * (length[0] + length[1]) / std::sqrt(smaller);
}

double splitWorth(double ncut, double neck, double exponent, double bound, double floor) {
  return std::log(bound) - std::log(std::max(ncut, std::max(floor, 1e-300))) -
         exponent * std::log(std::max(neck, 1.0));
}

std::vector<bool> shortCutKeep(const std::vector<double>& worth, const std::vector<int>& left,
                               const std::vector<int>& right) {
  const std::size_t n = left.size();
  std::vector<double> value(n, 0.0);
  for (std::size_t i = n; i-- > 0;)
    if (left[i] >= 0)
      value[i] = std::max(0.0, worth[i] + value[left[i]] + value[right[i]]);
  std::vector<bool> keep(n, false);
  for (std::size_t i = 0; i < n; ++i)
    keep[i] = left[i] >= 0 && value[i] > 0.0;
  for (std::size_t i = 0; i < n; ++i) // parents first: a split below a dropped one is dropped
    if (left[i] >= 0 && !keep[i]) {
      keep[left[i]] = false;
      keep[right[i]] = false;
    }
  return keep;
}

} // namespace pcl_ncut_seg
