#include "eval_model.h"

#include <set>

namespace pcl_ncut_seg {
namespace eval {

SegmentationScores againstHumans(const std::vector<int>& labels,
                                 const std::vector<std::vector<int>>& humans,
                                 const std::vector<double>& area) {
  SegmentationScores sum;
  for (const auto& h : humans)
    sum += pcl_ncut_seg::compareSegmentations(labels, h, area);
  return sum / static_cast<double>(humans.size());
}

SegmentationScores humansAgainstEachOther(const std::vector<std::vector<int>>& humans,
                                          const std::vector<double>& area, double* segments) {
  SegmentationScores sum;
  double segs = 0;
  for (std::size_t i = 0; i < humans.size(); ++i) {
    std::vector<std::vector<int>> others;
    for (std::size_t j = 0; j < humans.size(); ++j)
      if (j != i)
        others.push_back(humans[j]);
    sum += againstHumans(humans[i], others, area);
    segs += static_cast<double>(countSegments(humans[i]));
  }
  if (segments)
    *segments = segs / static_cast<double>(humans.size());
  return sum / static_cast<double>(humans.size());
}

std::size_t countSegments(const std::vector<int>& labels) {
  std::set<int> s;
  for (int l : labels)
    s.insert(l < 0 ? -1 : l);
  return s.size();
}

double secondsSince(std::chrono::steady_clock::time_point since) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - since).count();
}

std::vector<int> segmentsToLabels(const std::vector<pcl::PointIndices>& segments, std::size_t n) {
  std::vector<int> labels(n, -1);
  for (std::size_t s = 0; s < segments.size(); ++s)
    for (const auto i : segments[s].indices)
      labels[static_cast<std::size_t>(i)] = static_cast<int>(s);
  return labels;
}

} // namespace eval
} // namespace pcl_ncut_seg
