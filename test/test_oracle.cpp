/*
 * The finest level's oracles (eval/eval_oracle.h): the merge of a segmentation onto a
 * person's, scored against that person, and the k-means control, on examples small enough to
 * check by hand.
 */
#include "eval_oracle.h"

#include <gtest/gtest.h>

#include <cstddef>
#include <cstdint>
#include <set>
#include <stdexcept>
#include <vector>

namespace {

using pcl_ncut_seg::compareSegmentations;
using pcl_ncut_seg::eval::kmeansLabels;
using pcl_ncut_seg::eval::mergeOnto;
using pcl_ncut_seg::eval::oracleAgainstHumans;

/** n points along the x axis at x = 0, 1, ..., n - 1 (a strip of faces' centroids). */
std::vector<float> line(std::size_t n) {
  std::vector<float> xyz;
  for (std::size_t i = 0; i < n; ++i)
    xyz.insert(xyz.end(), {static_cast<float>(i), 0.f, 0.f});
  return xyz;
}

/** Faces 0..n-1 split at the given cuts: face f's label is how many cuts are <= f. */
std::vector<int> cutAt(std::size_t n, const std::vector<std::size_t>& cuts) {
  std::vector<int> labels(n, 0);
  for (std::size_t f = 0; f < n; ++f)
    for (std::size_t c : cuts)
      labels[f] += f >= c ? 1 : 0;
  return labels;
}

TEST(Oracle, ARefinementMergesBackToThePersonAndScoresZero) {
  const std::vector<int> person = {5, 5, 5, 9, 9, 2, 2, 2};
  const std::vector<int> finer = {0, 1, 1, 2, 3, 4, 4, 7}; // refines person
  const std::vector<double> area = {1, 2, 1, 1, 3, 1, 1, 2};
  EXPECT_EQ(mergeOnto(finer, person, area), person);
  const auto s = oracleAgainstHumans(finer, {person}, area);
  EXPECT_EQ(s.rand_index_error, 0);
  EXPECT_EQ(s.hamming, 0);
  EXPECT_EQ(s.gce, 0);
  // Scored as it is, the finer segmentation is not 0: the merge is what the oracle adds.
  EXPECT_GT(compareSegmentations(finer, person, area).rand_index_error, 0.1);
}

TEST(Oracle, EachPersonIsMergedOntoSeparately) {
  // Two people who disagree, and a segmentation that refines both: 0 against each, while the
  // people score more than 0 against each other.
  const std::vector<int> a = {0, 0, 0, 1, 1, 1}, b = {0, 0, 1, 1, 2, 2};
  const std::vector<int> finer = {0, 0, 1, 2, 3, 3};
  EXPECT_EQ(oracleAgainstHumans(finer, {a, b}, {}).rand_index_error, 0);
  EXPECT_GT(compareSegmentations(a, b, {}).rand_index_error, 0);
}

TEST(Oracle, MergesByAreaNotByFaces) {
  // Segment 0 holds three faces of person's 1 (area 1 each) and one of person's 2 (area 5).
  const std::vector<int> seg = {0, 0, 0, 0, 1}, person = {1, 1, 1, 2, 2};
  EXPECT_EQ(mergeOnto(seg, person, {1, 1, 1, 5, 1}), (std::vector<int>{2, 2, 2, 2, 2}));
  EXPECT_EQ(mergeOnto(seg, person, {}), (std::vector<int>{1, 1, 1, 1, 2}));
  // Zero area everywhere: every face weighs 1, as in the metrics.
  EXPECT_EQ(mergeOnto(seg, person, {0, 0, 0, 0, 0}), (std::vector<int>{1, 1, 1, 1, 2}));
}

TEST(Oracle, TiesAndUnassignedFacesAreDecidedOneWay) {
  // An even split of area goes to the larger overlap in faces, then to the smaller label.
  EXPECT_EQ(mergeOnto({0, 0, 0}, {4, 3, 3}, {2, 1, 1}), (std::vector<int>{3, 3, 3}));
  EXPECT_EQ(mergeOnto({0, 0}, {4, 3}, {1, 1}), (std::vector<int>{3, 3}));
  // Every negative label is one segment, in the segmentation and in the person's.
  EXPECT_EQ(mergeOnto({-1, -2, 0, 0}, {7, 7, -1, -3}, {}), (std::vector<int>{7, 7, -1, -1}));
  EXPECT_THROW(mergeOnto({0, 1}, {0}, {}), std::invalid_argument);
  EXPECT_THROW(mergeOnto({0, 1}, {0, 1}, {1}), std::invalid_argument);
}

TEST(Oracle, KMeansFindsSeparateClustersWithAFixedSeed) {
  // Three tight clusters far apart: k-means++ and Lloyd's find them whatever the seed.
  std::vector<float> xyz;
  for (int c = 0; c < 3; ++c)
    for (int i = 0; i < 20; ++i)
      xyz.insert(xyz.end(), {100.f * c + 0.1f * i, 50.f * (c % 2), 0.01f * i});
  for (std::uint64_t seed : {1u, 2u, 99u}) {
    const std::vector<int> labels = kmeansLabels(xyz, 3, seed);
    ASSERT_EQ(labels.size(), 60u);
    EXPECT_EQ(std::set<int>(labels.begin(), labels.end()).size(), 3u);
    for (int c = 0; c < 3; ++c)
      for (int i = 1; i < 20; ++i)
        EXPECT_EQ(labels[20 * c + i], labels[20 * c]) << seed;
    EXPECT_EQ(kmeansLabels(xyz, 3, seed), labels); // deterministic
  }
  // More segments than points: one per point. Identical points, and none: no failure.
  const std::vector<int> each = kmeansLabels(line(4), 10, 7);
  EXPECT_EQ(std::set<int>(each.begin(), each.end()).size(), 4u);
  const std::vector<int> same = kmeansLabels(std::vector<float>(30, 1.f), 3, 7);
  EXPECT_EQ(same.size(), 10u);
  EXPECT_TRUE(kmeansLabels({}, 3, 7).empty());
}

TEST(Oracle, TheKMeansControlMissesBoundariesAFinerCutHolds) {
  // A strip of 100 faces; the person cuts at 30 and 70. A finer cut with those boundaries
  // (and more) merges back to 0; k-means into as many segments cuts evenly, and its merge
  // cannot place a boundary at 30 or 70 exactly.
  const std::size_t n = 100;
  const std::vector<int> person = cutAt(n, {30, 70});
  const std::vector<int> finer = cutAt(n, {15, 30, 50, 70, 85});
  const std::vector<int> kmeans = kmeansLabels(line(n), 6, 1);
  EXPECT_EQ(std::set<int>(kmeans.begin(), kmeans.end()).size(), 6u);
  EXPECT_EQ(oracleAgainstHumans(finer, {person}, {}).rand_index_error, 0);
  const auto control = oracleAgainstHumans(kmeans, {person}, {});
  EXPECT_GT(control.rand_index_error, 0.01);
  EXPECT_GT(control.hamming, 0.01);
  // Still far better than k-means scored as it is: the merge removes the extra cuts.
  EXPECT_LT(control.rand_index_error, compareSegmentations(kmeans, person, {}).rand_index_error);
}

} // namespace
