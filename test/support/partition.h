/*
 * pcl_ncut_seg tests: the invariant every segmentation keeps, as gtest expectations (header
 * only: it needs gtest, which the support library does not link).
 */
#pragma once

#include <pcl/PointIndices.h>
#include <pcl/common/point_tests.h>
#include <pcl/point_cloud.h>
#include <pcl/types.h>

#include <gtest/gtest.h>

#include <algorithm>
#include <cstddef>
#include <vector>

namespace pcl_ncut_seg {
namespace test {

/** \brief Expects that the segments partition the finite points selected by `selected` (all
 * points when null): each in exactly one segment, every other point in none; segments
 * non-empty, sorted, ordered by their smallest index. Returns the label of each point (its
 * segment, -1 for none). */
template <typename PointT>
std::vector<int> expectPartition(const std::vector<pcl::PointIndices>& segments,
                                 const pcl::PointCloud<PointT>& cloud,
                                 const pcl::Indices* selected = nullptr) {
  std::vector<char> want(cloud.size(), selected ? 0 : 1);
  if (selected)
    for (const auto i : *selected)
      want[i] = 1;
  std::vector<int> label(cloud.size(), -1), count(cloud.size(), 0);
  int previous_first = -1;
  for (std::size_t s = 0; s < segments.size(); ++s) {
    const auto& idx = segments[s].indices;
    EXPECT_FALSE(idx.empty()) << "segment " << s << " is empty";
    if (idx.empty())
      continue;
    EXPECT_TRUE(std::is_sorted(idx.begin(), idx.end()));
    EXPECT_GT(idx.front(), previous_first) << "segments not ordered by smallest index";
    previous_first = idx.front();
    for (const auto i : idx) {
      EXPECT_GE(i, 0);
      EXPECT_LT(static_cast<std::size_t>(i), cloud.size());
      if (i < 0 || static_cast<std::size_t>(i) >= cloud.size())
        continue;
      ++count[i];
      label[i] = static_cast<int>(s);
    }
  }
  std::size_t wrong = 0;
  for (std::size_t i = 0; i < cloud.size(); ++i)
    wrong += count[i] != ((want[i] && pcl::isXYZFinite(cloud[i])) ? 1 : 0);
  EXPECT_EQ(wrong, 0u) << "points not in exactly one segment (or segmented but not wanted)";
  return label;
}

} // namespace test
} // namespace pcl_ncut_seg
