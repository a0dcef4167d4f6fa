/*
 * Open views: small segments joined to their neighbours unless a limb's neck holds them
 * (core/views/small_segments.h, the second half of SupernodeNCutSegmentation::setRimMerge's stage).
 */
#include "core/cut/short_cut.h"
#include "core/graph/csr_graph.h"
#include "core/supernodes/supernodes.h"
#include "core/views/small_segments.h"
#include <pcl_ncut_seg/supernode_ncut_segmentation.h>

#include "support/knn_graph.h"
#include <shapes/shapes.h>

#include <gtest/gtest.h>

#include <pcl/io/pcd_io.h>

#include <cmath>
#include <filesystem>
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
  const std::vector<std::uint32_t> map = joinSmallSegments(s.graph, s.area, 20.0, 0.0, segment, t);
  ASSERT_EQ(map.size(), 3u);
  EXPECT_EQ(map[0], 0u);
  EXPECT_EQ(map[1], 1u);
  EXPECT_EQ(map[2], 0u);
  EXPECT_EQ(t, 2u);
  EXPECT_EQ(segment, halvesWithBox(17, 19, 10, 12, 0));
  // Moved across, the piece touches the right half more: it joins that one.
  segment = halvesWithBox(20, 22, 10, 12, 2);
  t = 3;
  joinSmallSegments(s.graph, s.area, 20.0, 0.0, segment, t);
  EXPECT_EQ(t, 2u);
  EXPECT_EQ(segment, halvesWithBox(20, 22, 10, 12, 1));
}

TEST(JoinSmallSegments, TheSmallestJoinsFirstAndTheJoinedOneIsMeasuredAgain) {
  const Sheet s;
  // Two pieces inside the left half, side by side: a (2 x 3 = 6 points) and b (4 x 3 = 12
  // points), each below 15; a touches b along 3 points and the left half along 7.
  std::vector<std::uint32_t> segment = twoPieces();
  std::size_t t = 4;
  const std::vector<std::uint32_t> map = joinSmallSegments(s.graph, s.area, 15.0, 0.0, segment, t);
  ASSERT_EQ(map.size(), 4u);
  // a, the smallest, joins first: the left half, which holds most of its edges. Then b is
  // still small and joins the left half too.
  EXPECT_EQ(map[2], 0u);
  EXPECT_EQ(map[3], 0u);
  EXPECT_EQ(t, 2u);
  // With a bound of 7, a joins (6 < 7) and b (12) is not small.
  segment = twoPieces();
  t = 4;
  const std::vector<std::uint32_t> map7 = joinSmallSegments(s.graph, s.area, 7.0, 0.0, segment, t);
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
  EXPECT_TRUE(joinSmallSegments(graph, area, 20.0, 0.0, segment, t).empty());
  EXPECT_EQ(segment, before);
  EXPECT_EQ(t, 3u);
  // No segment small: nothing changes.
  EXPECT_TRUE(joinSmallSegments(graph, area, 5.0, 0.0, segment, t).empty());
  EXPECT_EQ(segment, before);
  // Sizes that do not match the graph: nothing changes, no crash.
  EXPECT_TRUE(joinSmallSegments(graph, std::vector<double>(3, 1.0), 1e9, 0.0, segment, t).empty());
  EXPECT_TRUE(joinSmallSegments(s.graph, area, 1e9, 0.0, segment, t).empty());
  EXPECT_EQ(segment, before);
  EXPECT_EQ(t, 3u);
}

TEST(JoinSmallSegments, ALimbsNeckHoldsASmallPartWhereABlobJoins) {
  // The sheet, and a strip two points wide and twelve long standing out of its lower edge at
  // x = 30, 31: a limb, touching the sheet only at its base.
  Sheet s;
  std::vector<std::uint32_t> segment = halvesWithBox(5, 10, 10, 12, 2); // a blob of 18 points
  for (std::size_t y = 1; y <= 12; ++y)
    for (float x : {30.0f, 31.0f}) {
      s.xyz.insert(s.xyz.end(), {x, -static_cast<float>(y), 0.0f});
      segment.push_back(3);
    }
  s.graph = test::kdTreeKnnGraph(s.xyz, 8);
  s.area.assign(segment.size(), 1.0);
  std::size_t t = 4;
  const std::vector<std::uint32_t> map =
      joinSmallSegments(s.graph, s.area, 30.0, kLimbNeck, segment, t);
  ASSERT_EQ(map.size(), 4u);
  EXPECT_EQ(t, 3u);
  EXPECT_EQ(map[2], map[0]); // the blob joins the half around it
  EXPECT_NE(map[3], map[1]); // the limb stays, though smaller
  EXPECT_EQ(std::set<std::uint32_t>(segment.end() - 24, segment.end()).size(), 1u);
  // Without the neck test the limb joins too.
  segment = halvesWithBox(5, 10, 10, 12, 2);
  segment.resize(s.xyz.size() / 3, 3);
  t = 4;
  joinSmallSegments(s.graph, s.area, 30.0, 0.0, segment, t);
  EXPECT_EQ(t, 2u);
}

namespace {

std::vector<pcl::PointIndices> segmentView(const pcl::PointCloud<pcl::PointXYZ>::Ptr& cloud,
                                           std::optional<double> rim_merge) {
  pcl::SupernodeNCutSegmentation<pcl::PointXYZ> seg;
  seg.setInputCloud(cloud);
  seg.setNumberOfThreads(2);
  seg.setRimMerge(rim_merge);
  std::vector<pcl::PointIndices> out;
  seg.extract(out);
  return out;
}

} // namespace

TEST(ViewSmallSegment, LeavesNoSmallPieceInAView) {
  const auto cloud = test::discView(11, 0.02f); // a disc with a bump 2 cm high
  std::size_t valid = 0;
  for (const auto& p : *cloud)
    valid += std::isfinite(p.x);
  const std::vector<pcl::PointIndices> off = segmentView(cloud, std::nullopt);
  const std::vector<pcl::PointIndices> on = segmentView(cloud, 10.0);
  std::cout << "[ INFO     ] bumpy disc view: " << off.size() << " segments, " << on.size()
            << " with the open-view stage\n";
  ASSERT_GT(off.size(), on.size());
  // The points on the disc are evenly spaced in the image and the object's area is taken as
  // twice the view's: a segment of fewer than half of 2% of them (margin for the points'
  // uneven spacing) is small, and the disc has no limb to hold one.
  for (const auto& s : on)
    EXPECT_GE(s.indices.size(), valid / 100);
}

TEST(ViewSmallSegment, AWholeSurfaceIsNoView) {
  const test::LabeledShape hand = test::makeHand(4000, 3);
  std::vector<pcl::PointIndices> on = segmentView(hand.cloud, 10.0),
                                 off = segmentView(hand.cloud, std::nullopt);
  ASSERT_EQ(on.size(), off.size());
  EXPECT_GT(on.size(), 1u);
  for (std::size_t s = 0; s < on.size(); ++s)
    EXPECT_EQ(on[s].indices, off[s].indices);
}

namespace {

const std::string kCarton = std::string(PCL_NCUT_SEG_SHARED_DATA) + "/pcl/milk.pcd";

} // namespace

// PCL's milk.pcd: a gable-top carton seen by a depth camera, cropped from its scene, sensor at
// the origin. In sight (by plane fits within 6 mm): two side faces at right angles (51% and 31%
// of the points) and one slope of the gable top (15%, at 46 degrees to the larger face); the
// pixels along the rim scatter.

TEST(ViewSmallSegment, ARealDepthImageOfACartonIsOneViewWithoutScatteredPieces) {
  if (!std::filesystem::exists(kCarton))
    GTEST_SKIP() << "shared data absent: no " << kCarton;
  pcl::PointCloud<pcl::PointXYZ>::Ptr cloud(new pcl::PointCloud<pcl::PointXYZ>);
  ASSERT_EQ(pcl::io::loadPCDFile(kCarton, *cloud), 0) << "cannot read " << kCarton;
  pcl::SupernodeNCutSegmentation<pcl::PointXYZ> seg;
  seg.setInputCloud(cloud);
  std::vector<pcl::PointIndices> segments;
  seg.extract(segments);
  EXPECT_TRUE(seg.getViewTest().view) << "a depth image is one view from its sensor";
  // The rim's scattered pixels (17 segments with -rim_merge off) join the faces: the
  // stage joins a segment below 2% of the view's area to its neighbour, so none is below half
  // of that (margin for uneven spacing), and no more segments come out than the faces in sight;
  // faces at right angles are not one part, so not fewer than two. (That the two are the
  // carton's faces does not hold yet: one segment holds both sides, the other the gable's slope
  // with a corner of the larger side.)
  EXPECT_GE(segments.size(), 2u);
  EXPECT_LE(segments.size(), 3u);
  for (const auto& s : segments)
    EXPECT_GE(s.indices.size(), cloud->size() / 100);
}
