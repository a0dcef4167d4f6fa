#include "view_scoring.h"

#include <algorithm>
#include <unordered_map>
#include <utility>

namespace pcl_ncut_seg {

std::vector<std::size_t> seenFaces(const std::vector<std::int64_t>& pixel_face) {
  std::vector<std::size_t> seen;
  for (const std::int64_t f : pixel_face)
    if (f >= 0)
      seen.push_back(static_cast<std::size_t>(f));
  std::sort(seen.begin(), seen.end());
  seen.erase(std::unique(seen.begin(), seen.end()), seen.end());
  return seen;
}

std::vector<int> faceLabelsFromPixels(const std::vector<std::int64_t>& pixel_face,
                                      const std::vector<int>& pixel_label,
                                      const std::vector<std::size_t>& seen) {
  std::unordered_map<std::size_t, std::size_t> position;
  for (std::size_t i = 0; i < seen.size(); ++i)
    position[seen[i]] = i;
  // (face position, label) pairs, sorted: each face's votes are a run, each label a sub-run.
  std::vector<std::pair<std::size_t, int>> votes;
  for (std::size_t p = 0; p < pixel_face.size(); ++p)
    if (pixel_face[p] >= 0)
      votes.emplace_back(position.at(static_cast<std::size_t>(pixel_face[p])), pixel_label[p]);
  std::sort(votes.begin(), votes.end());
  std::vector<int> labels(seen.size(), -1);
  std::vector<std::size_t> best(seen.size(), 0);
  for (std::size_t i = 0; i < votes.size();) {
    std::size_t j = i;
    while (j < votes.size() && votes[j] == votes[i])
      ++j;
    const auto [face, label] = votes[i];
    // Runs come in increasing label order: a strictly larger count wins, so ties keep the
    // smallest label; a labelled run always beats the unlabelled one.
    if (label >= 0 && (labels[face] < 0 || j - i > best[face])) {
      labels[face] = label;
      best[face] = j - i;
    }
    i = j;
  }
  return labels;
}

} // namespace pcl_ncut_seg
