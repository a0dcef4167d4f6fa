/*
 * Crease cuts: supernodes split along the minimum cut weighted by concave bend when no level
 * cut of the centrality follows the crease (core/crease_split.h, CreaseSplitParams::
 * cut_concavity; SupernodeNCutSegmentation::setCreaseCut).
 */
#include <pcl_ncut_seg/core/crease_split.h>
#include <pcl_ncut_seg/supernode_ncut_segmentation.h>

#include "support/graphs.h"
#include "support/shapes.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <iostream>
#include <limits>

using namespace pcl_ncut_seg;
using Segmenter = pcl::SupernodeNCutSegmentation<pcl::PointXYZ>;

namespace {

/// A strip folded inwards along a crease that slants across the level sets of f (f falls
/// along x; the crease runs from x = -0.5 at y = 0 to x = 0.5 at y = 1), as a shoulder's
/// boundary slants across the centrality's level sets.
struct SlantedFold {
  CsrGraph graph;
  std::vector<float> xyz, normals, f, radii;
  std::vector<int> side; ///< per point, 0 before the crease (x < s(y)), 1 after it
};

float crease(float y) {
  return -0.5f + y;
}

SlantedFold slantedFold(int nx, int ny) {
  SlantedFold s;
  for (int j = 0; j < ny; ++j)
    for (int i = 0; i < nx; ++i) {
      const float x = -1.0f + 2.0f * float(i) / float(nx - 1);
      const float y = float(j) / float(ny - 1);
      const float d = x - crease(y);
      // z = |x - s(y)|: both sides rise away from the crease, so it folds inwards.
      s.xyz.insert(s.xyz.end(), {x, y, std::abs(d)});
      // Upward unit normal of z = +-(x - s(y)): (-+1, +-s'(y), 1) / norm, s' = 1.
      const float sign = d < 0.0f ? -1.0f : 1.0f;
      const float norm = std::sqrt(3.0f);
      s.normals.insert(s.normals.end(), {-sign / norm, sign / norm, 1.0f / norm});
      s.f.push_back(2.0f - x); // one supernode grown from x = -1
      s.radii.push_back(0.02f);
      s.side.push_back(d < 0.0f ? 0 : 1);
    }
  // 8-neighbour grid.
  const auto m = static_cast<std::uint32_t>(nx * ny);
  std::vector<std::vector<std::uint32_t>> adj(m);
  for (int j = 0; j < ny; ++j)
    for (int i = 0; i < nx; ++i)
      for (int dj = -1; dj <= 1; ++dj)
        for (int di = -1; di <= 1; ++di) {
          const int a = i + di, b = j + dj;
          if ((di != 0 || dj != 0) && a >= 0 && a < nx && b >= 0 && b < ny)
            adj[static_cast<std::size_t>(j * nx + i)].push_back(
                static_cast<std::uint32_t>(b * nx + a));
        }
  s.graph = test::graphFromAdjacency(std::move(adj), s.xyz);
  return s;
}

/// The share of points on the wrong side of the crease: each supernode counted as the side
/// most of its points are on.
double wrongSideShare(const Supernodes& sn, const std::vector<int>& side) {
  std::vector<std::size_t> count(2 * sn.size(), 0);
  for (std::size_t p = 0; p < side.size(); ++p)
    ++count[2 * sn.label[p] + static_cast<std::size_t>(side[p])];
  std::size_t wrong = 0;
  for (std::size_t s = 0; s < sn.size(); ++s)
    wrong += std::min(count[2 * s], count[2 * s + 1]);
  return double(wrong) / double(side.size());
}

} // namespace

TEST(CreaseCut, FollowsACreaseThatSlantsAcrossTheLevelSets) {
  const SlantedFold s = slantedFold(61, 21);
  const Supernodes in = test::oneSupernode(s.f.size());
  CreaseSplitParams params;
  params.area_fraction = 0.05f;
  // Level cuts alone: the most concave level cut crosses the crease in a few rows only. At a
  // threshold it cannot reach, nothing splits; at one it can, the cut is straight across and
  // leaves a large share of the points on the wrong side of the crease.
  params.min_concavity = 6.0;
  const Supernodes level =
      splitAtCreases(s.graph, s.xyz.data(), s.normals, s.f, s.radii, in, params);
  EXPECT_EQ(level.size(), 1u);
  params.min_concavity = 0.5;
  const double level_wrong = wrongSideShare(
      splitAtCreases(s.graph, s.xyz.data(), s.normals, s.f, s.radii, in, params), s.side);
  // Crease cuts on: the minimum cut follows the crease (every edge it crosses is concave).
  params.min_concavity = 6.0;
  params.cut_concavity = 0.9;
  std::size_t splits = 0;
  const Supernodes cut =
      splitAtCreases(s.graph, s.xyz.data(), s.normals, s.f, s.radii, in, params, &splits);
  const double cut_wrong = wrongSideShare(cut, s.side);
  std::cout << "slanted crease: wrong side " << level_wrong << " (best level cut), " << cut_wrong
            << " (crease cut, " << cut.size() << " supernodes)" << std::endl;
  EXPECT_GE(splits, 1u);
  EXPECT_GE(cut.size(), 2u);
  EXPECT_LT(cut_wrong, 0.02);
  EXPECT_GT(level_wrong, 0.1);
  // With crease cuts alone (level cuts off) the same.
  params.min_concavity = 0.0;
  EXPECT_LT(wrongSideShare(
                splitAtCreases(s.graph, s.xyz.data(), s.normals, s.f, s.radii, in, params), s.side),
            0.02);
  // Off (0, the paper's supernodes), and a bend no edge of the crease reaches: no split.
  params.cut_concavity = 0.0;
  EXPECT_EQ(splitAtCreases(s.graph, s.xyz.data(), s.normals, s.f, s.radii, in, params).size(), 1u);
  params.cut_concavity = 0.9;
  params.cut_min_bend = 1e6;
  EXPECT_EQ(splitAtCreases(s.graph, s.xyz.data(), s.normals, s.f, s.radii, in, params).size(), 1u);
}

TEST(CreaseCut, SameSupernodesForAnyThreadCount) {
  // The cuts of the first test of each supernode run on several threads; the result must not
  // depend on how many. A low setting, so that the generated shapes get crease cuts.
  bool changed = false;
  for (const auto& shape : {test::makeQuadruped(4000, 1), test::makeHand(4000, 2)}) {
    std::vector<int> labels[3];
    for (unsigned threads : {1u, 2u, 4u}) {
      Segmenter seg;
      seg.setInputCloud(shape.cloud);
      seg.setCreaseCut(0.3);
      seg.setNumberOfThreads(threads);
      std::vector<pcl::PointIndices> segments;
      seg.extract(segments);
      labels[threads == 1 ? 0 : threads / 2] = seg.getSupernodeLabels(true);
    }
    Segmenter off;
    off.setInputCloud(shape.cloud);
    std::vector<pcl::PointIndices> segments;
    off.extract(segments);
    changed = changed || labels[0] != off.getSupernodeLabels(true);
    EXPECT_EQ(labels[0], labels[1]);
    EXPECT_EQ(labels[0], labels[2]);
  }
  EXPECT_TRUE(changed) << "crease cuts changed no supernode of either shape";
}

TEST(CreaseCut, SetterChecksItsValueAndNulloptIsOff) {
  Segmenter seg;
  EXPECT_EQ(seg.getCreaseCut(), std::nullopt); // off by default
  seg.setCreaseCut(0.5);
  EXPECT_EQ(seg.getCreaseCut(), 0.5);
  seg.setCreaseCut(1.0);
  EXPECT_EQ(seg.getCreaseCut(), 1.0);
  seg.setCreaseCut(-1e-9);
  EXPECT_EQ(seg.getCreaseCut(), 1.0);
  seg.setCreaseCut(1.0000001);
  EXPECT_EQ(seg.getCreaseCut(), 1.0);
  seg.setCreaseCut(std::nan(""));
  EXPECT_EQ(seg.getCreaseCut(), 1.0);
  seg.setCreaseCut(std::numeric_limits<double>::infinity());
  EXPECT_EQ(seg.getCreaseCut(), 1.0);
  seg.setCreaseCut(0.0);
  EXPECT_EQ(seg.getCreaseCut(), 1.0);
  seg.setCreaseCut(std::nullopt);
  EXPECT_EQ(seg.getCreaseCut(), std::nullopt);
}
