// The short-cut stopping rule for the hierarchy of Sec. 5.2 (see core/cut/short_cut.h).
#include "core/cut/short_cut.h"
#include "core/supernodes/supernodes.h"

#include <algorithm>
#include <cmath>

namespace pcl_ncut_seg {

namespace {
constexpr double kPi = 3.14159265358979323846;
} // namespace

NeckMeasure::NeckMeasure(const CsrGraph& graph, const std::vector<std::uint32_t>& label,
                         std::size_t num_supernodes, bool vote)
    : area_(num_supernodes, 0.0), vote_(vote) {
  const std::size_t n = graph.numVertices();
  std::vector<double> radius(n, 0.0);
  std::vector<std::uint32_t> fringe(n, kNone); // per point, its fringe index
  std::vector<std::uint32_t> voters;
  for (std::uint32_t p = 0; p < n; ++p) {
    double sum = 0.0;
    bool voter = false;
    for (std::uint32_t e = graph.offsets[p]; e < graph.offsets[p + 1]; ++e) {
      sum += graph.lengths[e];
      voter = voter || label[graph.targets[e]] != label[p];
    }
    const std::uint32_t deg = graph.degree(p);
    radius[p] = deg > 0 ? sum / deg : 0.0;
    area_[label[p]] += kPi * radius[p] * radius[p];
    if (voter) {
      fringe[p] = static_cast<std::uint32_t>(voters.size());
      voters.push_back(p);
    }
  }
  num_voters_ = voters.size();
  std::vector<std::uint32_t> points = voters; // per fringe index, its point
  for (std::uint32_t p = 0; p < n; ++p)
    if (fringe[p] == kNone)
      for (std::uint32_t e = graph.offsets[p]; e < graph.offsets[p + 1]; ++e)
        if (fringe[graph.targets[e]] != kNone && fringe[graph.targets[e]] < num_voters_) {
          fringe[p] = static_cast<std::uint32_t>(points.size());
          points.push_back(p);
          break;
        }
  // A voter keeps all its neighbours (all in the fringe); any other fringe point only its
  // voters: its other neighbours share its supernode and no vote moves them.
  fringe_offsets_.push_back(0);
  for (std::size_t i = 0; i < points.size(); ++i) {
    const std::uint32_t p = points[i];
    fringe_label_.push_back(label[p]);
    fringe_radius_.push_back(radius[p]);
    for (std::uint32_t e = graph.offsets[p]; e < graph.offsets[p + 1]; ++e) {
      const std::uint32_t j = fringe[graph.targets[e]];
      if (j != kNone && (i < num_voters_ || j < num_voters_))
        fringe_neighbours_.push_back(j);
    }
    fringe_offsets_.push_back(static_cast<std::uint32_t>(fringe_neighbours_.size()));
  }
}

double NeckMeasure::neck(const std::vector<std::int8_t>& side) const {
  auto sideOf = [&side](std::uint32_t s) -> std::int8_t {
    return s < side.size() && side[s] >= 0 ? (side[s] != 0) : -1;
  };
  double area[2] = {0.0, 0.0}, length[2] = {0.0, 0.0};
  for (std::uint32_t s = 0; s < area_.size(); ++s)
    if (const std::int8_t t = sideOf(s); t >= 0)
      area[t] += area_[s];
  // The vote, from the sides before it (all voters at once); a voter that changes side takes
  // its area along.
  const std::size_t m = fringe_label_.size();
  std::vector<std::int8_t> voted(m);
  for (std::size_t i = 0; i < m; ++i)
    voted[i] = sideOf(fringe_label_[i]);
  for (std::size_t i = 0; vote_ && i < num_voters_; ++i) {
    const std::int8_t own = sideOf(fringe_label_[i]);
    if (own < 0)
      continue;
    int count[2] = {0, 0};
    ++count[own];
    for (std::uint32_t k = fringe_offsets_[i]; k < fringe_offsets_[i + 1]; ++k) {
      const std::int8_t s = sideOf(fringe_label_[fringe_neighbours_[k]]);
      if (s >= 0)
        ++count[s];
    }
    const std::int8_t now = count[1] > count[0] ? 1 : count[0] > count[1] ? 0 : own;
    if (now != own) {
      const double a = kPi * fringe_radius_[i] * fringe_radius_[i];
      area[own] -= a;
      area[now] += a;
      voted[i] = now;
    }
  }
  for (std::size_t i = 0; i < m; ++i) {
    const std::int8_t s = voted[i];
    if (s < 0)
      continue;
    for (std::uint32_t k = fringe_offsets_[i]; k < fringe_offsets_[i + 1]; ++k) {
      const std::int8_t t = voted[fringe_neighbours_[k]];
      if (t >= 0 && t != s) {
        length[s] += 2.0 * fringe_radius_[i];
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
