/*
 * Bridging components of the kNN graph that only a sampling gap separates
 * (bridgeComponents, SupernodeNCutSegmentation::setBridgeGap).
 */
#include "core/graph/bridging.h"
#include "core/graph/csr_graph.h"
#include "core/model/model.h" // what getAnalysis() points to
#include <pcl_ncut_seg/supernode_ncut_segmentation.h>

#include "support/graphs.h"
#include <shapes/shapes.h>

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <random>
#include <set>
#include <tuple>
#include <vector>

using namespace pcl_ncut_seg;

namespace {

/// Two 10 x 10 grids of spacing 1 in the plane z = 0, the second `gap` further along x than
/// the first ends (x in [0, 9] and [9 + gap, 18 + gap]).
std::vector<float> twoGrids(double gap) {
  std::vector<float> xyz;
  for (int part = 0; part < 2; ++part)
    for (int i = 0; i < 10; ++i)
      for (int j = 0; j < 10; ++j) {
        xyz.push_back(static_cast<float>(i + part * (9 + gap)));
        xyz.push_back(static_cast<float>(j));
        xyz.push_back(0.0f);
      }
  return xyz;
}

/// The symmetric kNN graph by brute force (ties to the smaller index).
CsrGraph knnGraph(const std::vector<float>& xyz, std::size_t k) {
  return buildSymmetricKnnGraph(xyz.data(), xyz.size() / 3, test::bruteForceKnn(xyz, k).data(), k);
}

std::size_t components(const CsrGraph& g) {
  std::vector<std::uint32_t> c;
  return connectedComponents(g, c);
}

} // namespace

TEST(BridgeComponents, JoinsASamplingGapByItsShortestLink) {
  const std::vector<float> xyz = twoGrids(2.5);
  CsrGraph g = knnGraph(xyz, 4); // kNN radius 1 (and sqrt(2) on a few points)
  ASSERT_EQ(components(g), 2u);
  const std::size_t edges = g.numDirectedEdges();
  std::vector<double> ratios;
  EXPECT_EQ(bridgeComponents(g, xyz.data(), 3.0, &ratios), 1u);
  EXPECT_EQ(components(g), 1u);
  EXPECT_EQ(g.numDirectedEdges(), edges + 2); // one bridge, both directions
  ASSERT_EQ(ratios.size(), 1u);
  EXPECT_LE(ratios[0], 2.5 + 1e-6);
  // The bridge is a shortest pair: length 2.5, across the gap along x.
  bool found = false;
  for (std::size_t v = 0; v < g.numVertices(); ++v) {
    EXPECT_TRUE(
        std::is_sorted(g.targets.begin() + g.offsets[v], g.targets.begin() + g.offsets[v + 1]));
    for (std::uint32_t e = g.offsets[v]; e < g.offsets[v + 1]; ++e)
      if ((v < 100) != (g.targets[e] < 100)) {
        EXPECT_NEAR(g.lengths[e], 2.5, 1e-5);
        found = true;
      }
  }
  EXPECT_TRUE(found);
}

TEST(BridgeComponents, KeepsObjectsFartherApartThanTheLimit) {
  // kNN radii are 1 to 2 (the corners' farthest graph neighbour is 2 away).
  const std::vector<float> xyz = twoGrids(8.0);
  CsrGraph g = knnGraph(xyz, 4);
  EXPECT_EQ(bridgeComponents(g, xyz.data(), 3.0), 0u);
  EXPECT_EQ(components(g), 2u);
  EXPECT_EQ(bridgeComponents(g, xyz.data(), 0.0), 0u); // 0: never
  EXPECT_EQ(bridgeComponents(g, xyz.data(), 5.0), 1u);
  EXPECT_EQ(components(g), 1u);
  // A limit far beyond the cloud's size looks at every point (and does not hang).
  CsrGraph h = knnGraph(xyz, 4);
  EXPECT_EQ(bridgeComponents(h, xyz.data(), 1e300), 1u);
  EXPECT_EQ(components(h), 1u);
}

TEST(BridgeComponents, ThreePiecesInAChainGetTwoBridges) {
  std::vector<float> xyz = twoGrids(2.5);
  for (int i = 0; i < 10; ++i) // a third grid 2.5 beyond the second
    for (int j = 0; j < 10; ++j) {
      xyz.push_back(static_cast<float>(i + 2 * (9 + 2.5)));
      xyz.push_back(static_cast<float>(j));
      xyz.push_back(0.0f);
    }
  CsrGraph g = knnGraph(xyz, 4);
  ASSERT_EQ(components(g), 3u);
  EXPECT_EQ(bridgeComponents(g, xyz.data(), 3.0), 2u);
  EXPECT_EQ(components(g), 1u);
}

namespace {
std::size_t analysedComponents(const pcl::SupernodeNCutSegmentation<pcl::PointXYZ>& seg) {
  return components(*seg.getAnalysis()->graph);
}
} // namespace

TEST(BridgeGap, ABarSampledWithAGapIsOneSurface) {
  // A bar with a band of about 2 kNN radii left unsampled (spacing about 0.04 at n = 3000).
  const test::LabeledShape bar = test::makeGappedBar(3000, 1, 0.15);
  pcl::SupernodeNCutSegmentation<pcl::PointXYZ> seg;
  EXPECT_EQ(seg.getBridgeGap(), 3.0);
  seg.setInputCloud(bar.cloud);
  std::vector<pcl::PointIndices> segments;
  seg.setBridgeGap(std::nullopt);
  seg.extract(segments);
  ASSERT_NE(seg.getAnalysis(), nullptr);
  EXPECT_EQ(analysedComponents(seg), 2u);
  seg.setBridgeGap(3.0); // the default
  seg.extract(segments);
  EXPECT_EQ(analysedComponents(seg), 1u);
}

TEST(BridgeGap, SeparateObjectsStaySeparate) {
  const test::LabeledShape two = test::makeTwoObjects(4000, 1);
  pcl::SupernodeNCutSegmentation<pcl::PointXYZ> seg;
  seg.setInputCloud(two.cloud);
  std::vector<pcl::PointIndices> segments;
  seg.extract(segments);
  EXPECT_EQ(analysedComponents(seg), 2u);
  for (const auto& s : segments) {
    std::set<int> parts;
    for (int i : s.indices)
      parts.insert(two.labels[static_cast<std::size_t>(i)]);
    EXPECT_EQ(parts.size(), 1u);
  }
}

TEST(BridgeGap, SetterRejectsBadValues) {
  pcl::SupernodeNCutSegmentation<pcl::PointXYZ> seg;
  seg.setBridgeGap(1.5);
  for (double bad : {0.0, -1e-30, -1.0, std::numeric_limits<double>::quiet_NaN(),
                     std::numeric_limits<double>::infinity()}) {
    seg.setBridgeGap(bad);
    EXPECT_EQ(seg.getBridgeGap(), 1.5);
  }
  seg.setBridgeGap(std::nullopt);
  EXPECT_EQ(seg.getBridgeGap(), std::nullopt);
}

namespace {
/// Bridges by brute force over all pairs, by the rule bridgeComponents() documents: per pair
/// of components the shortest pair of points p < q no longer than the reach (gap times kNN
/// radius, the longest edge) of either point, taken shortest first while it joins two groups.
std::set<std::pair<std::uint32_t, std::uint32_t>>
bruteForceBridges(const CsrGraph& g, const std::vector<float>& xyz, double gap) {
  const std::size_t n = g.numVertices();
  std::vector<std::uint32_t> comp;
  const std::size_t m = connectedComponents(g, comp);
  std::vector<double> reach(n, 0.0);
  for (std::uint32_t v = 0; v < n; ++v)
    for (std::uint32_t e = g.offsets[v]; e < g.offsets[v + 1]; ++e)
      reach[v] = std::max(reach[v], gap * g.lengths[e]);
  std::map<std::pair<std::uint32_t, std::uint32_t>,
           std::tuple<double, std::uint32_t, std::uint32_t>>
      best;
  for (std::uint32_t p = 0; p < n; ++p)
    for (std::uint32_t q = p + 1; q < n; ++q) {
      if (comp[p] == comp[q])
        continue;
      const double dx = xyz[3 * p] - xyz[3 * q], dy = xyz[3 * p + 1] - xyz[3 * q + 1],
                   dz = xyz[3 * p + 2] - xyz[3 * q + 2];
      const double d = std::sqrt(dx * dx + dy * dy + dz * dz);
      if (!(d <= std::min(reach[p], reach[q])))
        continue;
      const auto key = std::minmax(comp[p], comp[q]);
      const auto c = std::make_tuple(d, p, q);
      auto it = best.find(key);
      if (it == best.end() || c < it->second)
        best[key] = c;
    }
  std::vector<std::tuple<double, std::uint32_t, std::uint32_t>> sorted;
  for (const auto& [key, c] : best)
    sorted.push_back(c);
  std::sort(sorted.begin(), sorted.end());
  std::vector<std::uint32_t> parent(m);
  for (std::uint32_t c = 0; c < m; ++c)
    parent[c] = c;
  auto find = [&parent](std::uint32_t c) {
    while (parent[c] != c)
      c = parent[c];
    return c;
  };
  std::set<std::pair<std::uint32_t, std::uint32_t>> out;
  for (const auto& [d, p, q] : sorted) {
    const std::uint32_t a = find(comp[p]), b = find(comp[q]);
    if (a != b) {
      parent[a] = b;
      out.emplace(p, q);
    }
  }
  return out;
}
} // namespace

TEST(BridgeComponents, MatchesAllPairsOnASheetWithSatellitesNearAndFar) {
  // A large sheet (its cells hold only itself: the search skips them) with small clusters
  // beside it at a range of gaps and a few far away, for several seeds.
  for (unsigned seed : {1u, 2u, 3u}) {
    std::vector<float> xyz;
    std::mt19937 rng(seed);
    std::uniform_real_distribution<float> jitter(-0.15f, 0.15f), unit(0.0f, 1.0f);
    for (int i = 0; i < 40; ++i)
      for (int j = 0; j < 40; ++j)
        xyz.insert(xyz.end(), {i + jitter(rng), j + jitter(rng), 0.0f});
    for (int c = 0; c < 12; ++c) { // 3 x 3 clusters along the sheet's edge, 1 to 9 units off
      const float cx = 40.0f + 0.75f * static_cast<float>(c), cy = 3.0f * static_cast<float>(c);
      const float z = c % 3 == 0 ? 20.0f : 0.0f; // every third far above the plane
      for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j)
          xyz.insert(xyz.end(), {cx + i + jitter(rng), cy + j + jitter(rng), z + unit(rng)});
    }
    const CsrGraph before = knnGraph(xyz, 6);
    ASSERT_GT(components(before), 5u) << seed;
    CsrGraph after = before;
    bridgeComponents(after, xyz.data(), 3.0);
    std::set<std::pair<std::uint32_t, std::uint32_t>> added;
    for (std::uint32_t v = 0; v < after.numVertices(); ++v)
      for (std::uint32_t e = after.offsets[v]; e < after.offsets[v + 1]; ++e) {
        const std::uint32_t t = after.targets[e];
        const auto* row = &before.targets[before.offsets[v]];
        const auto* end = &before.targets[0] + before.offsets[v + 1];
        if (v < t && !std::binary_search(row, end, t))
          added.emplace(v, t);
      }
    EXPECT_EQ(added, bruteForceBridges(before, xyz, 3.0)) << seed;
  }
}

namespace {
/// A dense sheet (spacing 1) and a sparse one (spacing 5) `gap` units beside it, the sparse
/// one's points numbered first or last.
std::vector<float> denseAndSparseSheets(float gap, bool sparse_first) {
  std::vector<float> dense, sparse;
  for (int i = 0; i < 60; ++i) // wide enough that no search covers the whole grid
    for (int j = 0; j < 60; ++j)
      dense.insert(dense.end(), {static_cast<float>(i), static_cast<float>(j), 0.0f});
  for (int i = 0; i < 4; ++i)
    for (int j = 0; j < 4; ++j)
      sparse.insert(sparse.end(), {59.0f + gap + 5.0f * i, 5.0f * j, 0.0f});
  std::vector<float> xyz = sparse_first ? sparse : dense;
  const std::vector<float>& rest = sparse_first ? dense : sparse;
  xyz.insert(xyz.end(), rest.begin(), rest.end());
  return xyz;
}
} // namespace

TEST(BridgeComponents, AGapOnlyOneSideReachesAcrossStaysInEitherOrder) {
  // The dense points reach 3 x 1.4 to 3 x 2.2, the sparse ones 3 x 11: a gap of 13 is within
  // the sparse side's reach only, as a far surface seen at a grazing angle beside a near one
  // that hides part of it. (Any gap within both reaches is within the sparse points' k
  // nearest here: the sheets are one component then.)
  for (const bool sparse_first : {false, true}) {
    const std::vector<float> xyz = denseAndSparseSheets(13.0f, sparse_first);
    CsrGraph g = knnGraph(xyz, 6);
    ASSERT_EQ(components(g), 2u);
    EXPECT_TRUE(bruteForceBridges(g, xyz, 3.0).empty());
    EXPECT_EQ(bridgeComponents(g, xyz.data(), 3.0), 0u) << sparse_first;
    EXPECT_EQ(components(g), 2u) << sparse_first;
  }
}
