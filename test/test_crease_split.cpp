/*
 * Crease splits: supernodes split along concave creases that cross them
 * (core/supernodes/crease_split.h, SupernodeNCutSegmentation::setCreaseSplit).
 */
#include "core/supernodes/crease_split.h"
#include <pcl_ncut_seg/supernode_ncut_segmentation.h>

#include "support/graphs.h"
#include <shapes/shapes.h>

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <iostream>
#include <limits>
#include <map>
#include <optional>
#include <set>

using namespace pcl_ncut_seg;
using Segmenter = pcl::SupernodeNCutSegmentation<pcl::PointXYZ>;

namespace {

/// The share of points whose supernode's majority part is another part: what no grouping of
/// the supernodes can get right.
double offMajorityShare(const std::vector<int>& supernode, const std::vector<int>& part) {
  std::map<int, std::map<int, int>> count;
  for (std::size_t i = 0; i < part.size(); ++i)
    ++count[supernode[i]][part[i]];
  int off = 0;
  for (const auto& [s, parts] : count) {
    int total = 0, most = 0;
    for (const auto& [p, c] : parts) {
      total += c;
      most = std::max(most, c);
    }
    off += total - most;
  }
  return double(off) / double(part.size());
}

/// Refined supernode labels of a shape with the other defaults, crease splits at c and the
/// given number of threads (0: all cores).
std::vector<int> refinedSupernodes(const test::LabeledShape& shape, std::optional<double> c,
                                   unsigned threads = 0) {
  Segmenter seg;
  seg.setInputCloud(shape.cloud);
  seg.setCreaseSplit(c);
  seg.setNumberOfThreads(threads);
  std::vector<pcl::PointIndices> segments;
  seg.extract(segments);
  return seg.getSupernodeLabels(true);
}

/// A bar of points along x (y = z = 0 but for a kink), with normals that fold inwards at the
/// middle: a concave crease across one supernode.
struct Strip {
  CsrGraph graph;
  std::vector<float> xyz, normals, f, radii;
};

Strip foldedStrip(int n) {
  Strip s;
  // A V-shaped strip in the x-z plane, two points wide in y: z = |x|, normals pointing up
  // (+z) and outwards from the fold, so the fold at x = 0 is concave.
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < 2; ++j) {
      const float x = -1.0f + 2.0f * float(i) / float(n - 1);
      s.xyz.insert(s.xyz.end(), {x, 0.1f * float(j), std::abs(x)});
      const float nx = x < 0 ? 0.7071f : (x > 0 ? -0.7071f : 0.0f);
      const float nz = x == 0 ? 1.0f : 0.7071f;
      s.normals.insert(s.normals.end(), {nx, 0.0f, nz});
      s.f.push_back(2.0f - x); // one supernode grown from x = -1
      s.radii.push_back(0.05f);
    }
  // Grid neighbours: along x and across y.
  const std::uint32_t m = static_cast<std::uint32_t>(2 * n);
  std::vector<std::vector<std::uint32_t>> adj(m);
  auto link = [&](std::uint32_t a, std::uint32_t b) {
    adj[a].push_back(b);
    adj[b].push_back(a);
  };
  for (int i = 0; i < n; ++i) {
    link(2 * i, 2 * i + 1);
    if (i + 1 < n) {
      link(2 * i, 2 * i + 2);
      link(2 * i + 1, 2 * i + 3);
    }
  }
  s.graph = test::graphFromAdjacency(std::move(adj), s.xyz);
  return s;
}

} // namespace

TEST(CreaseSplit, SplitsASupernodeAtItsConcaveFold) {
  const Strip s = foldedStrip(41);
  const Supernodes in = test::oneSupernode(s.f.size());
  CreaseSplitParams params;
  params.min_concavity = 1.0;
  params.area_fraction = 0.1f;
  const Supernodes out = splitAtCreases(s.graph, s.xyz.data(), s.normals, s.f, s.radii, in, params);
  ASSERT_EQ(out.size(), 2u);
  // The two sides of the fold (x < 0 and x > 0) each become one supernode; the side with the
  // higher f (x < 0) terminates at the other, which now counts as created at a saddle.
  for (std::size_t p = 0; p < s.f.size(); ++p) {
    const float x = s.xyz[3 * p];
    if (x < -0.01f) {
      EXPECT_EQ(out.label[p], out.label[0]) << "x = " << x;
    }
    if (x > 0.01f) {
      EXPECT_NE(out.label[p], out.label[0]) << "x = " << x;
    }
  }
  const std::uint32_t top = out.label[0], bottom = 1 - top;
  EXPECT_EQ(out.parent[top], bottom);
  EXPECT_TRUE(out.at_saddle[bottom]);
  EXPECT_EQ(out.children[bottom], std::vector<std::uint32_t>{top});
  // Off (0, the paper) and a threshold above the fold's concavity leave it whole.
  params.min_concavity = 0.0;
  EXPECT_EQ(splitAtCreases(s.graph, s.xyz.data(), s.normals, s.f, s.radii, in, params).size(), 1u);
  params.min_concavity = 1e6;
  EXPECT_EQ(splitAtCreases(s.graph, s.xyz.data(), s.normals, s.f, s.radii, in, params).size(), 1u);
  // Each side must keep the area fraction: at 0.6 no cut qualifies.
  params.min_concavity = 1.0;
  params.area_fraction = 0.6f;
  EXPECT_EQ(splitAtCreases(s.graph, s.xyz.data(), s.normals, s.f, s.radii, in, params).size(), 1u);
}

TEST(CreaseSplit, SeparatesPartsThatShareASupernode) {
  // On the generated four-legged animal the tail and head rise into the body without a saddle
  // (docs/limitations.md) and share supernodes with it; crease splits cut those apart
  // at the concave crease where the parts meet the body.
  double before_sum = 0, after_sum = 0;
  for (std::uint64_t seed : {1, 2, 3}) {
    const test::LabeledShape shape = test::makeQuadruped(4000, seed);
    const std::vector<int> off = refinedSupernodes(shape, std::nullopt);
    const std::vector<int> on = refinedSupernodes(shape, Segmenter().getCreaseSplit());
    const double before = offMajorityShare(off, shape.labels);
    const double after = offMajorityShare(on, shape.labels);
    std::cout << "quadruped seed " << seed << ": " << std::set<int>(off.begin(), off.end()).size()
              << " -> " << std::set<int>(on.begin(), on.end()).size()
              << " supernodes, points off their supernode's majority part " << before << " -> "
              << after << std::endl;
    before_sum += before;
    after_sum += after;
  }
  EXPECT_LT(after_sum, 0.75 * before_sum);
}

TEST(CreaseSplit, SameSupernodesForAnyThreadCount) {
  // The first sweep of each supernode runs on several threads; the result must not depend on
  // how many.
  const std::optional<double> c = Segmenter().getCreaseSplit();
  bool changed = false;
  for (const auto& shape : {test::makeQuadruped(4000, 1), test::makeHand(4000, 2)}) {
    const std::vector<int> one = refinedSupernodes(shape, c, 1);
    EXPECT_EQ(refinedSupernodes(shape, c, 2), one);
    EXPECT_EQ(refinedSupernodes(shape, c, 4), one);
    changed = changed || one != refinedSupernodes(shape, std::nullopt, 1);
  }
  EXPECT_TRUE(changed) << "crease splits changed no supernode of either shape";
}

TEST(CreaseSplit, SetterChecksItsValueAndNulloptIsThePaper) {
  Segmenter seg;
  EXPECT_EQ(seg.getCreaseSplit(), 0.75);
  seg.setCreaseSplit(0.5);
  EXPECT_EQ(seg.getCreaseSplit(), 0.5);
  seg.setCreaseSplit(-1.0);
  EXPECT_EQ(seg.getCreaseSplit(), 0.5);
  seg.setCreaseSplit(std::nan(""));
  EXPECT_EQ(seg.getCreaseSplit(), 0.5);
  seg.setCreaseSplit(std::numeric_limits<double>::infinity());
  EXPECT_EQ(seg.getCreaseSplit(), 0.5);
  seg.setCreaseSplit(0.0);
  EXPECT_EQ(seg.getCreaseSplit(), 0.5);
  seg.setCreaseSplit(std::nullopt);
  EXPECT_EQ(seg.getCreaseSplit(), std::nullopt);
}
