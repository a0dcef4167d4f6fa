/*
 * pcl_ncut_seg kit, shared by the tests and bench/: comparing segmentations.
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

/** \brief For one part of a truth labeling: the segment holding most of its points (-1 for a
 * part with no point), and the share of the part's points it holds. */
struct MainSegment {
  int segment = -1;
  double share = 0.0;
};

/** \brief The main segment of each part 0 .. num_parts-1 of `truth` in the labeling `labels`
 * (ties to the smaller segment label). Points labelled negative in either are left out.
 * \throws std::invalid_argument if the sizes differ or a truth label is num_parts or more. */
std::vector<MainSegment> mainSegments(const std::vector<int>& labels, const std::vector<int>& truth,
                                      int num_parts);

/** \brief A baseline segmentation: k clusters of the points by position alone (k-means, Lloyd's
 * iterations until no point changes cluster, at most `iterations`), seeded deterministically by
 * farthest-point sampling from the first point. xyz holds 3 floats per point; returns a label
 * 0 .. k-1 per point. k is clamped to [1, number of points]. */
std::vector<int> kMeansLabels(const std::vector<float>& xyz, int k, int iterations = 100);

} // namespace test
} // namespace pcl_ncut_seg
