/*
 * The short-cut stopping rule (core/cut/short_cut.h, StoppingParams::neck_bound,
 * SupernodeNCutSegmentation::setNeckBound).
 */
#include "core/cut/normalized_cut.h"
#include "core/cut/short_cut.h"
#include <pcl_ncut_seg/supernode_ncut_segmentation.h>

#include "support/graphs.h"
#include <shapes/shapes.h>

#include <gtest/gtest.h>

#include <cmath>
#include <iostream>
#include <limits>

using namespace pcl_ncut_seg;
using test::memberGraph;

namespace {

// A w x h grid of points with unit spacing and 4-neighbour edges of length 1, so that every
// point has r(p) = 1; label[p] = column of p / band.
CsrGraph grid(int w, int h) {
  CsrGraph g;
  g.offsets.push_back(0);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      const int nx[4] = {x - 1, x + 1, x, x}, ny[4] = {y, y, y - 1, y + 1};
      for (int i = 0; i < 4; ++i)
        if (nx[i] >= 0 && nx[i] < w && ny[i] >= 0 && ny[i] < h) {
          g.targets.push_back(static_cast<std::uint32_t>(ny[i] * w + nx[i]));
          g.lengths.push_back(1.0f);
        }
      g.offsets.push_back(static_cast<std::uint32_t>(g.targets.size()));
    }
  return g;
}

} // namespace

TEST(ShortCut, NeckIsTheBoundaryOverTheSmallerSidesSize) {
  // 10 x 10 grid, supernode = column. Each point is a disc of radius 1 (area pi), and each
  // boundary point adds 2 to its side's boundary length.
  const CsrGraph g = grid(10, 10);
  std::vector<std::uint32_t> label(100);
  for (std::uint32_t p = 0; p < 100; ++p)
    label[p] = p % 10;
  const NeckMeasure measure(g, label, 10, false);
  const double pi = std::acos(-1.0);
  std::vector<std::int8_t> side(10);
  // Halves: a boundary of 10 points on each side (length 20), 50 points a side.
  for (int s = 0; s < 10; ++s)
    side[s] = s < 5 ? 0 : 1;
  EXPECT_NEAR(measure.neck(side), 20.0 / std::sqrt(50 * pi), 1e-9);
  // The vote of a noisy cloud leaves a straight boundary as it is.
  EXPECT_NEAR(NeckMeasure(g, label, 10, true).neck(side), 20.0 / std::sqrt(50 * pi), 1e-9);
  // A strip of 2 columns against 8: the same boundary, a smaller side: a longer neck.
  for (int s = 0; s < 10; ++s)
    side[s] = s < 2 ? 0 : 1;
  EXPECT_NEAR(measure.neck(side), 20.0 / std::sqrt(20 * pi), 1e-9);
  // Only the supernodes of the split part count: columns 0-3 split as 0-1 | 2-3.
  for (int s = 0; s < 10; ++s)
    side[s] = s < 2 ? 0 : (s < 4 ? 1 : -1);
  EXPECT_NEAR(measure.neck(side), 20.0 / std::sqrt(20 * pi), 1e-9);
  // Sides that do not touch have no boundary.
  for (int s = 0; s < 10; ++s)
    side[s] = s == 0 ? 0 : (s == 5 ? 1 : -1);
  EXPECT_EQ(measure.neck(side), 0.0);
}

TEST(ShortCut, OnANoisyCloudTheNeckIsMeasuredAfterAVote) {
  // 10 x 10 grid, supernode 0 left of x = 5 and supernode 1 right of it, but for two points
  // of supernode 0 at (6, 2) and (6, 6) among those of 1: the fringe of a noisy cloud.
  const CsrGraph g = grid(10, 10);
  std::vector<std::uint32_t> label(100);
  for (std::uint32_t p = 0; p < 100; ++p) {
    const std::uint32_t x = p % 10, y = p / 10;
    label[p] = x < 5 || (x == 6 && y % 4 == 2) ? 0 : 1;
  }
  const double pi = std::acos(-1.0);
  const std::vector<std::int8_t> side = {0, 1};
  // Without the vote: side 0 has 12 boundary points (column 4 and the two, length 24), side 1
  // has 16 (column 5 and 3 more around each of the two, length 32) and 48 points.
  EXPECT_NEAR(NeckMeasure(g, label, 2, false).neck(side), 28.0 / std::sqrt(48 * pi), 1e-9);
  // The vote moves both to side 1 (4 of their 5 votes): the straight boundary's neck.
  EXPECT_NEAR(NeckMeasure(g, label, 2, true).neck(side), 20.0 / std::sqrt(50 * pi), 1e-9);
}

TEST(ShortCut, WorthWeighsTheNcutByTheNeck) {
  // worth = log(0.25 / max(ncut, 1e-3)) - 3 log(max(neck, 1)).
  EXPECT_NEAR(splitWorth(0.05, 1.0, 3.0, 0.25, 1e-3), std::log(5.0), 1e-12);
  EXPECT_NEAR(splitWorth(0.05, 3.0, 3.0, 0.25, 1e-3), std::log(5.0) - 3 * std::log(3.0), 1e-12);
  // NCuts below the floor count as the floor; necks below 1 (separate components) as 1.
  EXPECT_NEAR(splitWorth(1e-9, 0.0, 3.0, 0.25, 1e-3), std::log(250.0), 1e-12);
  EXPECT_LT(splitWorth(0.5, 1.0, 3.0, 0.25, 1e-3), 0.0);
}

TEST(ShortCut, KeepsTheSubtreeWithTheHighestSumOfWorths) {
  // Node 0 splits into 1 and 2, node 1 into 3 and 4, node 2 into 5 and 6; 3-6 are leaves.
  const std::vector<int> left = {1, 3, 5, -1, -1, -1, -1}, right = {2, 4, 6, -1, -1, -1, -1};
  using Keep = std::vector<bool>;
  auto keep = [&](std::vector<double> worth) {
    worth.resize(7, 0.0);
    return shortCutKeep(worth, left, right);
  };
  // Every split worth it: all kept.
  EXPECT_EQ(keep({1, 1, 1}), (Keep{true, true, true, false, false, false, false}));
  // A dear root is kept when the splits below it make up for it...
  EXPECT_EQ(keep({-1.5, 1, 1}), (Keep{true, true, true, false, false, false, false}));
  // ... and not otherwise; nothing below a dropped split is kept.
  EXPECT_EQ(keep({-2.5, 1, 1}), Keep(7, false));
  // A worthless split in one branch is dropped whatever the other branch is worth (a running
  // sum over the best-first order would keep it when a worthy split came after it).
  EXPECT_EQ(keep({1, -0.5, 2}), (Keep{true, false, true, false, false, false, false}));
  // Nothing worth making; no split at all.
  EXPECT_EQ(keep({-1, -1, -1}), Keep(7, false));
  EXPECT_EQ(shortCutKeep({0.0}, {-1}, {-1}), Keep{false});
  EXPECT_TRUE(shortCutKeep({}, {}, {}).empty());
}

TEST(ShortCut, WeighsEachSplitOfTheHierarchyByItsNeck) {
  // Three tight pairs in a chain joined by weak edges: two cheap splits (three parts), then
  // dear ones.
  const WeightedGraph g =
      memberGraph(6, {{0, 1, 1.0}, {2, 3, 1.0}, {4, 5, 1.0}, {1, 2, 1e-3}, {3, 4, 1e-3}});
  StoppingParams p;
  p.threshold = 2.0;
  p.rule = StoppingRule::ShortCut;
  int calls = 0;
  double neck_value = 1.0;
  const SplitNeckFn neck = [&](const std::vector<std::uint32_t>& v1,
                               const std::vector<std::uint32_t>& v2) {
    ++calls;
    EXPECT_FALSE(v1.empty());
    EXPECT_FALSE(v2.empty());
    return neck_value;
  };
  // Short boundaries: the cheap splits are worth it, the dear ones (NCut about 1) are not.
  EXPECT_EQ(buildHierarchy(g, 6, p, neck).leaves().size(), 3u);
  EXPECT_GT(calls, 0);
  // Long boundaries (neck 10): no split is worth its boundary.
  neck_value = 10.0;
  EXPECT_EQ(buildHierarchy(g, 6, p, neck).leaves().size(), 1u);
  // A higher bound accepts them again, and the threshold still bounds every split.
  p.neck_bound = 1e4;
  EXPECT_EQ(buildHierarchy(g, 6, p, neck).leaves().size(), 6u);
  p.threshold = 0.01;
  EXPECT_EQ(buildHierarchy(g, 6, p, neck).leaves().size(), 3u);
  // Without a neck measure the NCut alone weighs, as with short boundaries.
  p.threshold = 2.0;
  p.neck_bound = 0.25;
  EXPECT_EQ(buildHierarchy(g, 6, p).leaves().size(), 3u);
}

TEST(ShortCut, SettersRejectBadValues) {
  pcl::SupernodeNCutSegmentation<pcl::PointXYZ> seg;
  EXPECT_EQ(seg.getNeckBound(), 0.25);
  seg.setNeckBound(0.5);
  for (double bad : {0.0, -0.1, std::numeric_limits<double>::quiet_NaN(),
                     std::numeric_limits<double>::infinity()}) {
    seg.setNeckBound(bad);
    EXPECT_EQ(seg.getNeckBound(), 0.5);
  }
  // A bad value changes no rule either.
  EXPECT_EQ(seg.getStoppingRule(), pcl_ncut_seg::StoppingRule::ShortCut);
}

TEST(ShortCut, TheOptionReachesTheSegmentation) {
  // A generated hand: the fingers are cut off across their narrow bases. A bound no split
  // reaches leaves one segment.
  const auto hand = pcl_ncut_seg::test::makeHand(4000, 1);
  pcl::SupernodeNCutSegmentation<pcl::PointXYZ> seg;
  seg.setInputCloud(hand.cloud);
  std::vector<pcl::PointIndices> segments;
  seg.extract(segments);
  const std::size_t by_default = segments.size();
  seg.setNeckBound(1e-12);
  seg.extract(segments);
  EXPECT_EQ(segments.size(), 1u);
  std::cout << "generated hand (6 parts): " << by_default << " segments with the short-cut rule\n";
  EXPECT_GE(by_default, 6u);
}
