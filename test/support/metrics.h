/*
 * pcl_ncut_seg tests: comparing segmentations.
 */
#pragma once

#include <pcl/PointIndices.h>

#include <cstddef>
#include <vector>

namespace pcl_ncut_seg {
namespace test {

/** \brief Rand index of two labelings: the fraction of point pairs on which they agree (both
 * in one segment, or both apart). Labels are arbitrary ints; a point with a negative label in
 * either labeling is left out. Exact, from the contingency table, in O(n + table size).
 * Returns 1 when fewer than two points count.
 * \throws std::invalid_argument if the sizes differ. */
double randIndex(const std::vector<int>& a, const std::vector<int>& b);

/** \brief Label each of n points with the index of its segment; -1 for points in none. A point
 * listed in several segments gets the last one (check partitions separately).
 * \throws std::out_of_range for an index outside [0, n). */
std::vector<int> segmentsToLabels(const std::vector<pcl::PointIndices>& segments, std::size_t n);

} // namespace test
} // namespace pcl_ncut_seg
