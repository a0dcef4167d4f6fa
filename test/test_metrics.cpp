/*
 * The benchmark's metrics (eval/psb_metrics.h) on small examples computed by hand, including
 * the degenerate segmentations: one segment, and one segment per face.
 */
#include "psb_metrics.h"

#include <gtest/gtest.h>

#include <stdexcept>
#include <vector>

namespace {

using pcl_ncut_seg::compareSegmentations;
using pcl_ncut_seg::SegmentationScores;

void expectScores(const SegmentationScores& s, double ri, double rm, double rf, double gce,
                  double lce) {
  EXPECT_NEAR(s.rand_index_error, ri, 1e-12);
  EXPECT_NEAR(s.hamming_rm, rm, 1e-12);
  EXPECT_NEAR(s.hamming_rf, rf, 1e-12);
  EXPECT_NEAR(s.hamming, (rm + rf) / 2, 1e-12);
  EXPECT_NEAR(s.gce, gce, 1e-12);
  EXPECT_NEAR(s.lce, lce, 1e-12);
}

TEST(Metrics, IdenticalUpToRenamingScoresZero) {
  const std::vector<int> a = {0, 0, 1, 1, 2}, b = {7, 7, 3, 3, -4};
  expectScores(compareSegmentations(a, b, {}), 0, 0, 0, 0, 0);
  expectScores(compareSegmentations(a, b, {1, 2, 3, 4, 5}), 0, 0, 0, 0, 0);
}

TEST(Metrics, FourFacesByHand) {
  // Segmentation {0,1}{2,3} against reference {0,1,2}{3}, faces of equal area.
  // Pairs: 6; together in S: 2, in R: 3, in both: 1 -> agree 6 - 2 - 3 + 2 = 3, RI 1/2.
  // Rm: R's {0,1,2} best overlap 2, {3} 1 -> missed 1 of 4. Rf: S's {0,1} 2, {2,3} 1 -> 1/4.
  // E(S,R,f) = 0, 0, 1/2, 1/2 (sum 1); E(R,S,f) = 1/3, 1/3, 2/3, 0 (sum 4/3).
  // GCE = min(1, 4/3) / 4 = 1/4; LCE = (0 + 0 + 1/2 + 0) / 4 = 1/8.
  expectScores(compareSegmentations({0, 0, 1, 1}, {0, 0, 0, 1}, {}), 0.5, 0.25, 0.25, 0.25, 0.125);
}

TEST(Metrics, AreaWeightsHammingAndConsistencyButNotRand) {
  // As above with areas 3, 1, 1, 1 (total 6). S's segments weigh 4 and 2, R's 5 and 1.
  // Rm: {0,1,2} best overlap 4, {3} 1 -> 1/6. Rf: {0,1} 4, {2,3} 1 -> 1/6.
  // E(S,R,f) = 0, 0, 1/2, 1/2 -> weighted sum 1; E(R,S,f) = 1/5, 1/5, 4/5, 0 -> 3/5 + 1/5 + 4/5.
  // GCE = min(1, 8/5) / 6 = 1/6; LCE = (1 * 1/2) / 6 = 1/12. The Rand index counts faces.
  expectScores(compareSegmentations({0, 0, 1, 1}, {0, 0, 0, 1}, {3, 1, 1, 1}), 0.5, 1.0 / 6,
               1.0 / 6, 1.0 / 6, 1.0 / 12);
}

TEST(Metrics, MissingAndFalseAlarmRatesDiffer) {
  // S = {0,1}{2,3}{4,5}, R = {0}{1}{2}{3,4,5}.
  // Rm: R's segments best overlaps 1, 1, 1, 2 -> missed 1 of 6. Rf: S's 1, 1, 2 -> 2 of 6.
  // RI: together in S 3, in R 3, in both 1 -> agree 15 - 3 - 3 + 2 = 11, error 4/15.
  // E(S,R,f) = 1/2, 1/2, 1/2, 1/2, 0, 0 (sum 2); E(R,S,f) = 0, 0, 0, 2/3, 1/3, 1/3 (sum 4/3).
  // GCE = (4/3) / 6 = 2/9; LCE = (0 + 0 + 0 + 1/2 + 0 + 0) / 6 = 1/12.
  expectScores(compareSegmentations({0, 0, 1, 1, 2, 2}, {0, 1, 3, 2, 2, 2}, {}), 4.0 / 15, 1.0 / 6,
               1.0 / 3, 2.0 / 9, 1.0 / 12);
}

TEST(Metrics, OneSegment) {
  // Everything in one segment against R = {0,1}{2}{3}: RI agrees only on the pair {0,1}.
  // Nothing of R is missed (Rm 0); the segment covers R's largest part, 2 of 4 (Rf 1/2).
  // A refinement of the other segmentation has GCE = LCE = 0: R refines S.
  expectScores(compareSegmentations({4, 4, 4, 4}, {0, 0, 1, 2}, {}), 5.0 / 6, 0, 0.5, 0, 0);
  // By area (1, 1, 1, 5): Rf = 1 - 5/8.
  expectScores(compareSegmentations({4, 4, 4, 4}, {0, 0, 1, 2}, {1, 1, 1, 5}), 5.0 / 6, 0, 3.0 / 8,
               0, 0);
}

TEST(Metrics, OneSegmentPerFace) {
  // Every face alone against R = {0,1}{2}{3}: RI disagrees only on the pair {0,1}.
  // R's {0,1} keeps one of its faces (Rm 1/4); nothing is extra (Rf 0); S refines R.
  expectScores(compareSegmentations({0, 1, 2, 3}, {0, 0, 1, 2}, {}), 1.0 / 6, 0.25, 0, 0, 0);
  // By area (1, 3, 1, 1): the larger face of {0,1} is kept, the other (1 of 6) is missed.
  expectScores(compareSegmentations({0, 1, 2, 3}, {0, 0, 1, 2}, {1, 3, 1, 1}), 1.0 / 6, 1.0 / 6, 0,
               0, 0);
}

TEST(Metrics, UnassignedFacesFormOneSegment) {
  // Negative labels (faces in no segment), whatever their value, are one segment together.
  const SegmentationScores a = compareSegmentations({-1, -2, 0, 0}, {5, 5, 7, 7}, {});
  expectScores(a, 0, 0, 0, 0, 0);
  const SegmentationScores b = compareSegmentations({-1, -1, -1, 0}, {0, 0, 1, 2}, {});
  const SegmentationScores c = compareSegmentations({9, 9, 9, 0}, {0, 0, 1, 2}, {});
  expectScores(b, c.rand_index_error, c.hamming_rm, c.hamming_rf, c.gce, c.lce);
}

TEST(Metrics, DegenerateInputs) {
  // One face: nothing to disagree about.
  expectScores(compareSegmentations({3}, {1}, {2.0}), 0, 0, 0, 0, 0);
  // All areas zero: every face weighs 1.
  const SegmentationScores z = compareSegmentations({0, 0, 1, 1}, {0, 0, 0, 1}, {0, 0, 0, 0});
  expectScores(z, 0.5, 0.25, 0.25, 0.25, 0.125);
  EXPECT_THROW(compareSegmentations({0, 1}, {0}, {}), std::invalid_argument);
  EXPECT_THROW(compareSegmentations({0, 1}, {0, 1}, {1}), std::invalid_argument);
  EXPECT_THROW(compareSegmentations({}, {}, {}), std::invalid_argument);
  EXPECT_THROW(compareSegmentations({0, 1}, {0, 1}, {1, -1}), std::invalid_argument);
}

TEST(Metrics, AreSymmetricWhereTheDefinitionsAre) {
  // RI, GCE, LCE are symmetric; swapping the arguments swaps Rm and Rf.
  const std::vector<int> a = {0, 0, 1, 1, 2, 2, 2}, b = {0, 1, 1, 1, 2, 3, 3};
  const std::vector<double> area = {1, 2, 3, 1, 2, 3, 1};
  const SegmentationScores ab = compareSegmentations(a, b, area);
  const SegmentationScores ba = compareSegmentations(b, a, area);
  EXPECT_NEAR(ab.rand_index_error, ba.rand_index_error, 1e-12);
  EXPECT_NEAR(ab.gce, ba.gce, 1e-12);
  EXPECT_NEAR(ab.lce, ba.lce, 1e-12);
  EXPECT_NEAR(ab.hamming_rm, ba.hamming_rf, 1e-12);
  EXPECT_NEAR(ab.hamming_rf, ba.hamming_rm, 1e-12);
  EXPECT_LE(ab.lce, ab.gce);
}

TEST(Metrics, Categories) {
  EXPECT_EQ(pcl_ncut_seg::psbCategory(1), "Human");
  EXPECT_EQ(pcl_ncut_seg::psbCategory(20), "Human");
  EXPECT_EQ(pcl_ncut_seg::psbCategory(181), "Hand");
  EXPECT_EQ(pcl_ncut_seg::psbCategory(400), "Fourleg");
  EXPECT_EQ(pcl_ncut_seg::psbCategory(0), "");
  EXPECT_EQ(pcl_ncut_seg::psbCategory(401), "");
}

} // namespace
