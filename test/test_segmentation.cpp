// The PCL front end: input checks, parameters, the two stages, outputs.
#include "core/model/model.h" // what getAnalysis() points to
#include <pcl_ncut_seg/supernode_ncut_segmentation.h>
#include <shapes/metrics.h>
#include <shapes/shapes.h>

#include <pcl/common/point_tests.h>
#include <pcl/search/kdtree.h>

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <set>

using Seg = pcl::SupernodeNCutSegmentation<pcl::PointXYZ>;
using Cloud = pcl::PointCloud<pcl::PointXYZ>;
using namespace pcl_ncut_seg::test;

namespace {
Cloud::Ptr dumbbell(std::size_t n = 2000) {
  return makeDumbbell(n, 3).cloud;
}

/// Every index of `segments` is in range, and each listed point appears exactly once.
std::vector<int> checkPartition(const std::vector<pcl::PointIndices>& segments, std::size_t n) {
  std::vector<int> seen(n, 0);
  for (const auto& s : segments) {
    EXPECT_FALSE(s.indices.empty());
    for (int i : s.indices) {
      EXPECT_GE(i, 0);
      EXPECT_LT(static_cast<std::size_t>(i), n);
      ++seen[i];
    }
  }
  return seen;
}
} // namespace

TEST(Segmentation, NoInputGivesNoSegments) {
  Seg seg;
  std::vector<pcl::PointIndices> out(3);
  seg.extract(out);
  EXPECT_TRUE(out.empty());
}

TEST(Segmentation, EmptyAndAllNanCloudsGiveNoSegments) {
  Seg seg;
  std::vector<pcl::PointIndices> out;
  seg.setInputCloud(Cloud::Ptr(new Cloud));
  seg.extract(out);
  EXPECT_TRUE(out.empty());
  Cloud::Ptr nan(new Cloud);
  const float q = std::numeric_limits<float>::quiet_NaN();
  nan->push_back(pcl::PointXYZ(q, q, q));
  nan->push_back(pcl::PointXYZ(1, q, 0));
  seg.setInputCloud(nan);
  seg.extract(out);
  EXPECT_TRUE(out.empty());
  EXPECT_TRUE(seg.getLabeledCloud()->empty());
}

TEST(Segmentation, NonFinitePointsAreInNoSegmentAndChangeNothingElse) {
  Cloud::Ptr clean = dumbbell();
  Cloud::Ptr dirty(new Cloud);
  const float q = std::numeric_limits<float>::quiet_NaN();
  const float inf = std::numeric_limits<float>::infinity();
  std::vector<int> clean_index;
  for (std::size_t i = 0; i < clean->size(); ++i) {
    if (i % 100 == 0)
      dirty->push_back(pcl::PointXYZ(q, 0, 0));
    if (i % 150 == 0)
      dirty->push_back(pcl::PointXYZ(0, inf, 0));
    clean_index.push_back(static_cast<int>(dirty->size()));
    dirty->push_back((*clean)[i]);
  }
  Seg a, b;
  a.setInputCloud(clean);
  b.setInputCloud(dirty);
  std::vector<pcl::PointIndices> sa, sb;
  a.extract(sa);
  b.extract(sb);
  ASSERT_FALSE(sa.empty());
  ASSERT_EQ(sa.size(), sb.size());
  const auto seen = checkPartition(sb, dirty->size());
  for (std::size_t i = 0; i < dirty->size(); ++i)
    EXPECT_EQ(seen[i], pcl::isXYZFinite((*dirty)[i]) ? 1 : 0);
  for (std::size_t s = 0; s < sa.size(); ++s) {
    ASSERT_EQ(sa[s].indices.size(), sb[s].indices.size());
    for (std::size_t j = 0; j < sa[s].indices.size(); ++j)
      EXPECT_EQ(clean_index[sa[s].indices[j]], sb[s].indices[j]);
  }
  const auto labeled = b.getLabeledCloud();
  ASSERT_EQ(labeled->size(), dirty->size());
  EXPECT_EQ((*labeled)[0].label, 0u); // the first point is NaN
}

TEST(Segmentation, IndicesSelectPointsAndOutputRefersToTheCloud) {
  Cloud::Ptr cloud = dumbbell();
  pcl::IndicesPtr even(new pcl::Indices);
  for (std::size_t i = 0; i < cloud->size(); i += 2)
    even->push_back(static_cast<int>(i));
  Seg seg;
  seg.setInputCloud(cloud);
  seg.setIndices(even);
  std::vector<pcl::PointIndices> out;
  seg.extract(out);
  ASSERT_FALSE(out.empty());
  const auto seen = checkPartition(out, cloud->size());
  for (std::size_t i = 0; i < cloud->size(); ++i)
    EXPECT_EQ(seen[i], i % 2 == 0 ? 1 : 0);
}

TEST(Segmentation, BadIndicesGiveNoSegments) {
  Cloud::Ptr cloud = dumbbell(500);
  Seg seg;
  seg.setInputCloud(cloud);
  std::vector<pcl::PointIndices> out;
  pcl::IndicesPtr bad(new pcl::Indices{0, 1, static_cast<int>(cloud->size())});
  seg.setIndices(bad);
  seg.extract(out);
  EXPECT_TRUE(out.empty());
  pcl::IndicesPtr negative(new pcl::Indices{0, -1, 2});
  seg.setIndices(negative);
  seg.extract(out);
  EXPECT_TRUE(out.empty());
  pcl::IndicesPtr empty(new pcl::Indices);
  seg.setIndices(empty);
  seg.extract(out);
  EXPECT_TRUE(out.empty());
  // Repeated indices count once.
  pcl::IndicesPtr twice(new pcl::Indices);
  for (int r = 0; r < 2; ++r)
    for (std::size_t i = 0; i < cloud->size(); ++i)
      twice->push_back(static_cast<int>(i));
  seg.setIndices(twice);
  seg.extract(out);
  const auto seen = checkPartition(out, cloud->size());
  for (int s : seen)
    EXPECT_EQ(s, 1);
}

TEST(Segmentation, FewPointsAndDuplicates) {
  Seg seg;
  std::vector<pcl::PointIndices> out;
  for (std::size_t n : {1u, 2u, 5u, 10u, 11u}) {
    Cloud::Ptr c(new Cloud);
    for (std::size_t i = 0; i < n; ++i)
      c->push_back(pcl::PointXYZ(static_cast<float>(i), 0, 0));
    seg.setInputCloud(c);
    seg.extract(out);
    const auto seen = checkPartition(out, n);
    for (int s : seen)
      EXPECT_EQ(s, 1) << n << " points";
  }
  // Every point three times over: zero-length edges everywhere.
  Cloud::Ptr base = dumbbell(600), triple(new Cloud);
  for (int r = 0; r < 3; ++r)
    *triple += *base;
  seg.setInputCloud(triple);
  seg.extract(out);
  ASSERT_FALSE(out.empty());
  const auto seen = checkPartition(out, triple->size());
  for (int s : seen)
    EXPECT_EQ(s, 1);
}

TEST(Segmentation, SettersRejectBadValuesAndKeepTheOldOnes) {
  Seg seg;
  seg.setNumberOfNeighbours(1);
  EXPECT_EQ(seg.getNumberOfNeighbours(), 10);
  seg.setNumberOfSamples(-1);
  seg.setNumberOfSamples(0);
  EXPECT_EQ(seg.getNumberOfSamples(), std::nullopt); // ceil(sqrt(n)), the default
  seg.setCrossingFraction(1.5f);
  seg.setCrossingFraction(std::numeric_limits<float>::quiet_NaN());
  EXPECT_FLOAT_EQ(seg.getCrossingFraction(), 0.3f);
  seg.setAreaFraction(-0.1f);
  EXPECT_FLOAT_EQ(seg.getAreaFraction(), 0.01f);
  seg.setHeightFraction(2.f);
  EXPECT_FLOAT_EQ(seg.getHeightFraction(), 0.01f);
  seg.setBeta(0);
  seg.setAlpha1(-1);
  seg.setAlpha2(std::numeric_limits<double>::infinity());
  EXPECT_EQ(seg.getBeta(), 2.0);
  EXPECT_EQ(seg.getAlpha1(), 2.0);
  EXPECT_EQ(seg.getAlpha2(), 0.5);
  seg.setThreshold(-1);
  EXPECT_EQ(seg.getThreshold(), 0.1);
  seg.setNumberOfSegments(0);
  seg.setNumberOfSegments(-2);
  EXPECT_EQ(seg.getNumberOfSegments(), 2);
  EXPECT_EQ(seg.getStoppingRule(), pcl_ncut_seg::StoppingRule::ShortCut) << "not the count rule";
  // Valid edge values are taken.
  seg.setNumberOfNeighbours(2);
  seg.setCrossingFraction(1.0f);
  seg.setThreshold(0.0);
  EXPECT_EQ(seg.getNumberOfNeighbours(), 2);
  EXPECT_FLOAT_EQ(seg.getCrossingFraction(), 1.0f);
  EXPECT_EQ(seg.getThreshold(), 0.0);
}

TEST(Segmentation, CutParametersReuseTheExpensiveStage) {
  Seg seg;
  seg.setInputCloud(makeHand(3000, 1).cloud);
  std::vector<pcl::PointIndices> out;
  seg.setNumberOfSegments(6);
  seg.extract(out);
  EXPECT_EQ(out.size(), 6u);
  const auto* analysis = seg.getAnalysis();
  ASSERT_NE(analysis, nullptr);
  seg.setNumberOfSegments(3);
  seg.setAlpha2(0.2);
  seg.setBeta(1.0);
  seg.extract(out);
  EXPECT_EQ(out.size(), 3u);
  EXPECT_EQ(seg.getAnalysis(), analysis); // not recomputed
  seg.setNumberOfNeighbours(12);
  EXPECT_EQ(seg.getAnalysis(), nullptr); // k invalidates it
  seg.extract(out);
  EXPECT_EQ(out.size(), 3u);
}

TEST(Segmentation, IntermediateResultsAreConsistent) {
  Seg seg;
  Cloud::Ptr cloud = makeHand(3000, 1).cloud;
  seg.setInputCloud(cloud);
  seg.setBoundaryBand(std::nullopt); // segment boundaries are supernode boundaries only without it
  std::vector<pcl::PointIndices> out;
  seg.extract(out);
  const auto f = seg.getCentrality();
  ASSERT_EQ(f.size(), cloud->size());
  for (float v : f)
    EXPECT_TRUE(std::isfinite(v) && v > 0);
  const auto maxima = seg.getLocalMaxima();
  const auto saddles = seg.getSaddles();
  const std::size_t m = seg.getNumberOfSupernodes(false), l = seg.getNumberOfSupernodes(true);
  EXPECT_EQ(maxima.size() + saddles.size(), m);
  EXPECT_LE(l, m);
  EXPECT_GE(maxima.size(), 6u); // at least the five fingertips and the wrist end
  const auto raw = seg.getSupernodeLabels(false), refined = seg.getSupernodeLabels(true);
  std::set<int> raw_ids(raw.begin(), raw.end()), refined_ids(refined.begin(), refined.end());
  EXPECT_EQ(raw_ids.size(), m);
  EXPECT_EQ(refined_ids.size(), l);
  // Each supernode lies in one segment.
  const auto seg_of = segmentsToLabels(out, cloud->size());
  std::vector<int> seg_of_supernode(l, -1);
  for (std::size_t i = 0; i < cloud->size(); ++i) {
    int& s = seg_of_supernode[refined[i]];
    if (s < 0)
      s = seg_of[i];
    EXPECT_EQ(s, seg_of[i]);
  }
  const auto& h = seg.getHierarchy();
  ASSERT_FALSE(h.nodes.empty());
  EXPECT_EQ(h.nodes[0].vertices.size(), 2 * l);
  EXPECT_EQ(h.leaves().size(), out.size());
  for (const auto& node : h.nodes) {
    if (node.left >= 0) {
      EXPECT_LE(node.ncut, seg.getThreshold());
    }
  }
}

TEST(Segmentation, ColouredAndLabelledCloudsAreStable) {
  Cloud::Ptr cloud = makeQuadruped(3000, 2).cloud;
  Seg a, b;
  a.setInputCloud(cloud);
  b.setInputCloud(cloud);
  a.setNumberOfThreads(1);
  b.setNumberOfThreads(2);
  std::vector<pcl::PointIndices> sa, sb;
  a.extract(sa);
  b.extract(sb);
  ASSERT_EQ(sa.size(), sb.size());
  for (std::size_t s = 0; s < sa.size(); ++s)
    EXPECT_EQ(sa[s].indices, sb[s].indices);
  const auto ca = a.getColoredCloud(), cb = b.getColoredCloud();
  const auto la = a.getLabeledCloud();
  ASSERT_EQ(ca->size(), cloud->size());
  std::set<std::uint32_t> colours;
  for (std::size_t i = 0; i < cloud->size(); ++i) {
    EXPECT_EQ((*ca)[i].rgba, (*cb)[i].rgba);
    EXPECT_EQ((*la)[i].x, (*cloud)[i].x);
    EXPECT_GE((*la)[i].label, 1u);
    colours.insert((*ca)[i].rgba);
  }
  EXPECT_EQ(colours.size(), sa.size()); // distinct colour per segment
  // The first 64 segment colours are pairwise distinct.
  std::set<std::uint32_t> palette;
  for (std::size_t i = 0; i < 64; ++i) {
    std::uint8_t r, g, bl;
    Seg::segmentColor(i, r, g, bl);
    palette.insert((std::uint32_t(r) << 16) | (std::uint32_t(g) << 8) | bl);
  }
  EXPECT_EQ(palette.size(), 64u);
}

TEST(Segmentation, CustomSearchMethod) {
  Seg seg;
  seg.setInputCloud(dumbbell(1000));
  seg.setSearchMethod(
      pcl::search::KdTree<pcl::PointXYZ>::Ptr(new pcl::search::KdTree<pcl::PointXYZ>));
  std::vector<pcl::PointIndices> out;
  seg.extract(out);
  EXPECT_FALSE(out.empty());
}
