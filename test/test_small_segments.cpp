/*
 * Open views: small segments joined to their neighbours (core/small_segments.h,
 * SupernodeNCutSegmentation::setViewSmallSegment).
 */
#include <pcl_ncut_seg/core/csr_graph.h>
#include <pcl_ncut_seg/core/small_segments.h>
#include <pcl_ncut_seg/core/supernodes.h>
#include <pcl_ncut_seg/supernode_ncut_segmentation.h>

#include "support/knn_graph.h"
#include "support/shapes.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <optional>
#include <set>

using namespace pcl_ncut_seg;

namespace {

constexpr std::size_t kW = 40, kH = 30;

/// A flat sheet of kW x kH points on a unit grid, row by row, and its kNN graph.
struct Sheet {
  std::vector<float> xyz;
  CsrGraph graph;
  std::vector<double> area; // one unit per point
  Sheet() {
    for (std::size_t y = 0; y < kH; ++y)
      for (std::size_t x = 0; x < kW; ++x)
        xyz.insert(xyz.end(), {static_cast<float>(x), static_cast<float>(y), 0.0f});
    graph = test::kdTreeKnnGraph(xyz, 8);
    area.assign(kW * kH, 1.0);
  }
};

/// Segment 0 left of x = 20, 1 right of it, and `id` on the box [x0, x1] x [y0, y1].
std::vector<std::uint32_t> halvesWithBox(std::size_t x0, std::size_t x1, std::size_t y0,
                                         std::size_t y1, std::uint32_t id) {
  std::vector<std::uint32_t> segment(kW * kH);
  for (std::size_t y = 0; y < kH; ++y)
    for (std::size_t x = 0; x < kW; ++x)
      segment[y * kW + x] = (x >= x0 && x <= x1 && y >= y0 && y <= y1) ? id : (x < 20 ? 0u : 1u);
  return segment;
}

/// Two pieces inside the left half, side by side: segment 2 on [5, 6] x [10, 12] (6 points) and
/// segment 3 on [7, 10] x [10, 12] (12 points).
std::vector<std::uint32_t> twoPieces() {
  std::vector<std::uint32_t> segment = halvesWithBox(5, 10, 10, 12, 3);
  for (std::size_t y = 10; y <= 12; ++y)
    for (std::size_t x = 5; x <= 6; ++x)
      segment[y * kW + x] = 2;
  return segment;
}

} // namespace

TEST(JoinSmallSegments, ASmallPieceJoinsTheNeighbourItSharesMostEdgesWith) {
  const Sheet s;
  // A 3 x 3 piece on the left half, touching the right half along one side only.
  std::vector<std::uint32_t> segment = halvesWithBox(17, 19, 10, 12, 2);
  std::size_t t = 3;
  const std::vector<std::uint32_t> map = joinSmallSegments(s.graph, s.area, 20.0, segment, t);
  ASSERT_EQ(map.size(), 3u);
  EXPECT_EQ(map[0], 0u);
  EXPECT_EQ(map[1], 1u);
  EXPECT_EQ(map[2], 0u);
  EXPECT_EQ(t, 2u);
  EXPECT_EQ(segment, halvesWithBox(17, 19, 10, 12, 0));
  // Moved across, the piece touches the right half more: it joins that one.
  segment = halvesWithBox(20, 22, 10, 12, 2);
  t = 3;
  joinSmallSegments(s.graph, s.area, 20.0, segment, t);
  EXPECT_EQ(t, 2u);
  EXPECT_EQ(segment, halvesWithBox(20, 22, 10, 12, 1));
}

TEST(JoinSmallSegments, TheSmallestJoinsFirstAndTheJoinedOneIsMeasuredAgain) {
  const Sheet s;
  // Two pieces inside the left half, side by side: a (2 x 3 = 6 points) and b (4 x 3 = 12
  // points), each below 15; a touches b along 3 points and the left half along 7.
  std::vector<std::uint32_t> segment = twoPieces();
  std::size_t t = 4;
  const std::vector<std::uint32_t> map = joinSmallSegments(s.graph, s.area, 15.0, segment, t);
  ASSERT_EQ(map.size(), 4u);
  // a, the smallest, joins first: the left half, which holds most of its edges. Then b is
  // still small and joins the left half too.
  EXPECT_EQ(map[2], 0u);
  EXPECT_EQ(map[3], 0u);
  EXPECT_EQ(t, 2u);
  // With a bound of 7, a joins (6 < 7) and b (12) is not small.
  segment = twoPieces();
  t = 4;
  const std::vector<std::uint32_t> map7 = joinSmallSegments(s.graph, s.area, 7.0, segment, t);
  ASSERT_EQ(map7.size(), 4u);
  EXPECT_EQ(t, 3u);
  EXPECT_EQ(map7[0], map7[2]);
  EXPECT_NE(map7[3], map7[0]);
  EXPECT_NE(map7[3], map7[1]);
}

TEST(JoinSmallSegments, AnIslandStaysAndNothingSmallChangesNothing) {
  // Two sheets far apart: the small one touches nothing, so it stays.
  Sheet s;
  std::vector<float> xyz = s.xyz;
  for (std::size_t y = 0; y < 3; ++y)
    for (std::size_t x = 0; x < 3; ++x)
      xyz.insert(xyz.end(), {static_cast<float>(x), static_cast<float>(y), 100.0f});
  const CsrGraph graph = test::kdTreeKnnGraph(xyz, 8);
  std::vector<std::uint32_t> segment(kW * kH, 0);
  for (std::size_t i = 0; i < kW * kH; ++i)
    segment[i] = (i % kW) < 20 ? 0u : 1u;
  segment.resize(kW * kH + 9, 2);
  const std::vector<std::uint32_t> before = segment;
  std::size_t t = 3;
  const std::vector<double> area(segment.size(), 1.0);
  EXPECT_TRUE(joinSmallSegments(graph, area, 20.0, segment, t).empty());
  EXPECT_EQ(segment, before);
  EXPECT_EQ(t, 3u);
  // No segment small: nothing changes.
  EXPECT_TRUE(joinSmallSegments(graph, area, 5.0, segment, t).empty());
  EXPECT_EQ(segment, before);
  // Sizes that do not match the graph: nothing changes, no crash.
  EXPECT_TRUE(joinSmallSegments(graph, std::vector<double>(3, 1.0), 1e9, segment, t).empty());
  EXPECT_TRUE(joinSmallSegments(s.graph, area, 1e9, segment, t).empty());
  EXPECT_EQ(segment, before);
  EXPECT_EQ(t, 3u);
}

namespace {

std::vector<pcl::PointIndices> segmentView(const pcl::PointCloud<pcl::PointXYZ>::Ptr& cloud,
                                           std::optional<double> rim_merge,
                                           std::optional<double> small) {
  pcl::SupernodeNCutSegmentation<pcl::PointXYZ> seg;
  seg.setInputCloud(cloud);
  seg.setNumberOfThreads(2);
  seg.setRimMerge(rim_merge);
  seg.setViewSmallSegment(small);
  std::vector<pcl::PointIndices> out;
  seg.extract(out);
  return out;
}

} // namespace

TEST(ViewSmallSegment, JoinsOnlyWholeSegmentsAndLeavesNoSmallOneInAView) {
  const auto cloud = test::discView(11, 0.02f); // a disc with a bump 2 cm high
  std::size_t valid = 0;
  for (const auto& p : *cloud)
    valid += std::isfinite(p.x);
  // Without the rim merge the view's rim and the bump cut the disc into pieces.
  const std::vector<pcl::PointIndices> off = segmentView(cloud, std::nullopt, std::nullopt);
  const std::vector<pcl::PointIndices> on = segmentView(cloud, std::nullopt, 0.05);
  std::cout << "[ INFO     ] bumpy disc view: " << off.size() << " segments, " << on.size()
            << " with small segments (below 10% of the view) joined\n";
  ASSERT_GT(off.size(), on.size());
  // Whole segments join: each segment without the stage lies in one segment with it.
  std::vector<int> owner(cloud->size(), -1);
  for (std::size_t s = 0; s < on.size(); ++s)
    for (int i : on[s].indices)
      owner[i] = static_cast<int>(s);
  for (const auto& piece : off) {
    std::set<int> owners;
    for (int i : piece.indices)
      owners.insert(owner[i]);
    EXPECT_EQ(owners.size(), 1u);
    EXPECT_NE(*owners.begin(), -1);
  }
  // The points on the disc are evenly spaced in the image: a segment of fewer than half of
  // 10% of them (the area bound, with margin for the points' uneven spacing) is small.
  for (const auto& s : on)
    EXPECT_GE(s.indices.size(), valid / 20);
}

TEST(ViewSmallSegment, AWholeSurfaceIsNoView) {
  const test::LabeledShape hand = test::makeHand(4000, 3);
  pcl::SupernodeNCutSegmentation<pcl::PointXYZ> seg;
  seg.setInputCloud(hand.cloud);
  seg.setNumberOfThreads(2);
  std::vector<pcl::PointIndices> on, off;
  seg.setViewSmallSegment(0.2);
  seg.extract(on);
  seg.setViewSmallSegment(std::nullopt);
  seg.extract(off);
  ASSERT_EQ(on.size(), off.size());
  EXPECT_GT(on.size(), 1u);
  for (std::size_t s = 0; s < on.size(); ++s)
    EXPECT_EQ(on[s].indices, off[s].indices);
}

TEST(ViewSmallSegment, SetterKeepsTheOldValueOnABadOne) {
  pcl::SupernodeNCutSegmentation<pcl::PointXYZ> seg;
  EXPECT_EQ(seg.getViewSmallSegment(), 0.01);
  seg.setViewSmallSegment(-0.1);
  EXPECT_EQ(seg.getViewSmallSegment(), 0.01);
  seg.setViewSmallSegment(0.6);
  EXPECT_EQ(seg.getViewSmallSegment(), 0.01);
  seg.setViewSmallSegment(std::numeric_limits<double>::quiet_NaN());
  EXPECT_EQ(seg.getViewSmallSegment(), 0.01);
  seg.setViewSmallSegment(0.05);
  EXPECT_EQ(seg.getViewSmallSegment(), 0.05);
  seg.setViewSmallSegment(0.0);
  EXPECT_EQ(seg.getViewSmallSegment(), 0.05);
  seg.setViewSmallSegment(std::nullopt);
  EXPECT_EQ(seg.getViewSmallSegment(), std::nullopt);
}

TEST(ViewSmallSegment, TheOpenViewStagesDoNotChangeHowAViewIsAnalysed) {
  // A view is a view whether or not its rim stages run: one start and, on this noisy view, f
  // without the neighbourhood mean of whole surfaces (core/denoise.h). Two segmenters, so that
  // the second analyses the view afresh with the stages off.
  const auto cloud = test::discView(11, 0.02f);
  pcl::SupernodeNCutSegmentation<pcl::PointXYZ> on, off;
  std::vector<pcl::PointIndices> out;
  on.setInputCloud(cloud);
  on.extract(out);
  ASSERT_TRUE(on.getNoiseTest().projected);
  off.setRimMerge(std::nullopt);
  off.setViewSmallSegment(std::nullopt);
  off.setInputCloud(cloud);
  off.extract(out);
  const std::vector<float> with = on.getCentrality(), without = off.getCentrality();
  ASSERT_EQ(with.size(), without.size());
  for (std::size_t i = 0; i < with.size(); ++i) {
    if (std::isfinite(with[i])) {
      ASSERT_EQ(with[i], without[i]) << i;
    }
  }
}
