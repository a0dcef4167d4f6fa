// The oracles of eval_oracle.h: the merge of a segmentation onto a person's, and k-means.
#include "eval_oracle.h"

#include <algorithm>
#include <limits>
#include <map>
#include <random>
#include <stdexcept>
#include <utility>

namespace pcl_ncut_seg {
namespace eval {

const std::vector<const char*> kOracleMethods = {"oracle", "kmeans_oracle"};

const char* const kOracleNote =
    "oracle and kmeans_oracle READ THE PEOPLE'S SEGMENTATIONS: each segment of the finest level "
    "(or of k-means with as many segments) is merged into the person's segment it overlaps most, "
    "for each person, then scored against that person. A diagnostic bound, not a method: choose "
    "no default by it.";

bool isOracleMethod(const std::string& method) {
  for (const char* m : kOracleMethods)
    if (method == m)
      return true;
  return false;
}

std::vector<int> mergeOnto(const std::vector<int>& segmentation, const std::vector<int>& person,
                           const std::vector<double>& area) {
  const std::size_t n = segmentation.size();
  if (person.size() != n || (!area.empty() && area.size() != n))
    throw std::invalid_argument("mergeOnto: one label and one area per face");
  double total = 0;
  for (std::size_t f = 0; f < area.size(); ++f)
    total += area[f];
  const bool by_area = !area.empty() && total > 0;
  // Per segment, per person's label: (area, faces) of their overlap.
  std::map<int, std::map<int, std::pair<double, std::size_t>>> overlap;
  for (std::size_t f = 0; f < n; ++f) {
    auto& o = overlap[std::max(segmentation[f], -1)][std::max(person[f], -1)];
    o.first += by_area ? area[f] : 1.0;
    o.second += 1;
  }
  std::map<int, int> into;
  for (const auto& [segment, row] : overlap) {
    auto best = row.begin(); // the smallest label first: a tie keeps it
    for (auto it = row.begin(); it != row.end(); ++it)
      if (it->second > best->second)
        best = it;
    into[segment] = best->first;
  }
  std::vector<int> merged(n);
  for (std::size_t f = 0; f < n; ++f)
    merged[f] = into[std::max(segmentation[f], -1)];
  return merged;
}

SegmentationScores oracleAgainstHumans(const std::vector<int>& segmentation,
                                       const std::vector<std::vector<int>>& humans,
                                       const std::vector<double>& area) {
  SegmentationScores sum;
  for (const auto& h : humans)
    sum += compareSegmentations(mergeOnto(segmentation, h, area), h, area);
  return sum / static_cast<double>(std::max<std::size_t>(humans.size(), 1));
}

namespace {

/** A number in [0, 1) from the generator's raw bits (the same on every platform, unlike
 * std::uniform_real_distribution). */
double unit(std::mt19937_64& rng) {
  return static_cast<double>(rng() >> 11) * (1.0 / 9007199254740992.0);
}

double squaredDistance(const std::vector<float>& xyz, std::size_t i, const double* c) {
  double s = 0;
  for (int a = 0; a < 3; ++a) {
    const double d = static_cast<double>(xyz[3 * i + a]) - c[a];
    s += d * d;
  }
  return s;
}

/** k-means++: the first centre uniform, each next one drawn with probability proportional to
 * the squared distance to the nearest centre so far. */
std::vector<double> seedCentres(const std::vector<float>& xyz, std::size_t n, std::size_t k,
                                std::mt19937_64& rng) {
  std::vector<double> centres;
  std::vector<double> nearest(n, std::numeric_limits<double>::infinity());
  std::size_t pick = std::min(n - 1, static_cast<std::size_t>(unit(rng) * static_cast<double>(n)));
  for (std::size_t c = 0; c < k; ++c) {
    for (int a = 0; a < 3; ++a)
      centres.push_back(xyz[3 * pick + a]);
    double sum = 0;
    for (std::size_t i = 0; i < n; ++i) {
      nearest[i] = std::min(nearest[i], squaredDistance(xyz, i, &centres[3 * c]));
      sum += nearest[i];
    }
    if (!(sum > 0)) // every point on a centre: the rest start on the first points
      pick = std::min(n - 1, c + 1);
    else {
      double target = unit(rng) * sum;
      pick = n - 1;
      for (std::size_t i = 0; i < n; ++i)
        if ((target -= nearest[i]) < 0) {
          pick = i;
          break;
        }
    }
  }
  return centres;
}

/** Each point's nearest centre (ties: the lower); whether any label changed. */
bool assign(const std::vector<float>& xyz, const std::vector<double>& centres,
            std::vector<int>& labels) {
  bool changed = false;
  const std::size_t k = centres.size() / 3;
  for (std::size_t i = 0; i < labels.size(); ++i) {
    int best = 0;
    double best_d = squaredDistance(xyz, i, &centres[0]);
    for (std::size_t c = 1; c < k; ++c) {
      const double d = squaredDistance(xyz, i, &centres[3 * c]);
      if (d < best_d) {
        best_d = d;
        best = static_cast<int>(c);
      }
    }
    changed |= labels[i] != best;
    labels[i] = best;
  }
  return changed;
}

/** The centres as their points' means; an empty cluster moves to the point farthest from its
 * own centre (and takes it). */
void update(const std::vector<float>& xyz, std::vector<double>& centres, std::vector<int>& labels) {
  const std::size_t k = centres.size() / 3;
  std::vector<double> sum(3 * k, 0);
  std::vector<std::size_t> count(k, 0);
  for (std::size_t i = 0; i < labels.size(); ++i) {
    const std::size_t c = static_cast<std::size_t>(labels[i]);
    for (int a = 0; a < 3; ++a)
      sum[3 * c + a] += xyz[3 * i + a];
    ++count[c];
  }
  for (std::size_t c = 0; c < k; ++c) {
    if (count[c] > 0) {
      for (int a = 0; a < 3; ++a)
        centres[3 * c + a] = sum[3 * c + a] / static_cast<double>(count[c]);
      continue;
    }
    std::size_t far = 0;
    double far_d = -1;
    for (std::size_t i = 0; i < labels.size(); ++i) {
      const double d =
          count[static_cast<std::size_t>(labels[i])] > 1
              ? squaredDistance(xyz, i, &centres[3 * static_cast<std::size_t>(labels[i])])
              : -1;
      if (d > far_d) {
        far_d = d;
        far = i;
      }
    }
    if (far_d < 0)
      continue; // no cluster has two points to spare
    --count[static_cast<std::size_t>(labels[far])];
    labels[far] = static_cast<int>(c);
    count[c] = 1;
    for (int a = 0; a < 3; ++a)
      centres[3 * c + a] = xyz[3 * far + a];
  }
}

} // namespace

std::vector<int> kmeansLabels(const std::vector<float>& xyz, std::size_t k, std::uint64_t seed,
                              int max_iterations) {
  const std::size_t n = xyz.size() / 3;
  if (n == 0 || k == 0)
    return std::vector<int>(n, 0);
  k = std::min(k, n);
  std::mt19937_64 rng(seed);
  std::vector<double> centres = seedCentres(xyz, n, k, rng);
  std::vector<int> labels(n, -1);
  for (int it = 0; it < max_iterations && assign(xyz, centres, labels); ++it)
    update(xyz, centres, labels);
  return labels;
}

} // namespace eval
} // namespace pcl_ncut_seg
