/*
 * The options that extend the paper's cut (each one setting away from the paper): adjacent
 * supernode pairs in G_s and the largest-gap stopping rule.
 */
#include <pcl_ncut_seg/core/normalized_cut.h>
#include <pcl_ncut_seg/core/supernode_graph.h>

#include "support/graphs.h"

#include <gtest/gtest.h>

#include <cmath>

using namespace pcl_ncut_seg;
using test::edgeWeight;
using test::memberGraph;

namespace {

// A chain of three supernodes s0 - s1 - s2 that meet at saddles, and s0 also touching s2 in
// the kNN graph (a ring, as on a cup) without a saddle between them.
Supernodes ringSupernodes() {
  Supernodes sn;
  sn.label = {0, 1, 2};
  sn.origin = {0, 1, 2};
  sn.at_saddle = {false, true, true};
  sn.parent = {1, 2, kNone};
  sn.children = {{}, {0}, {1}};
  return sn;
}
FeatureStats ringStats() {
  FeatureStats st;
  st.height = {1, 1, 1};
  st.area = {1, 1, 1};
  st.width = {1, 1, 1};
  return st;
}
Connectivity ringConn() {
  return {{{0, 0}, 4.0}, {{1, 1}, 4.0}, {{2, 2}, 4.0}, {{0, 1}, 2.0}, {{1, 2}, 2.0}, {{0, 2}, 1.0}};
}

/// Member vertex of supernode s among l supernodes.
std::uint32_t m(std::size_t l, std::uint32_t s) {
  return static_cast<std::uint32_t>(l + s);
}

} // namespace

TEST(AdjacencyAll, AddsThePairsThatMeetAtNoSaddle) {
  SimilarityParams p;
  p.normalize_width = false;
  p.adjacency = Adjacency::Trees; // the paper's saddle edges, and the trees joined
  const WeightedGraph saddles_only =
      buildSupernodeGraph(ringSupernodes(), ringStats(), ringConn(), p);
  EXPECT_EQ(edgeWeight(saddles_only, m(3, 0), m(3, 2)), -1) << "the paper: a tree of saddle edges";
  p.adjacency = Adjacency::All;
  p.adjacent_share = 0.0;
  const WeightedGraph all = buildSupernodeGraph(ringSupernodes(), ringStats(), ringConn(), p);
  EXPECT_EQ(all.edges.size(), saddles_only.edges.size() + 1);
  // eq. (9) with d1 = 0 (equal heights), d2 = 1 - 1/2, alpha = 0.5 (equal widths).
  EXPECT_NEAR(edgeWeight(all, m(3, 0), m(3, 2)), std::exp(-0.5 / 0.5), 1e-12);
  EXPECT_NEAR(edgeWeight(all, m(3, 0), m(3, 1)), edgeWeight(saddles_only, m(3, 0), m(3, 1)), 1e-15);
  // s0 and s2 touch with conn 1; each has total contact 3: joined up to a share of 1/3.
  p.adjacent_share = 0.3;
  EXPECT_GT(edgeWeight(buildSupernodeGraph(ringSupernodes(), ringStats(), ringConn(), p), m(3, 0),
                       m(3, 2)),
            0);
  p.adjacent_share = 0.5;
  EXPECT_EQ(edgeWeight(buildSupernodeGraph(ringSupernodes(), ringStats(), ringConn(), p), m(3, 0),
                       m(3, 2)),
            -1);
}

TEST(LargestGap, StopsWhereTheNCutJumps) {
  // Three tight pairs {0,1}, {2,3}, {4,5} (weight 1) in a chain joined by weak edges (1e-3):
  // two cheap splits, then every further split costs orders of magnitude more.
  const WeightedGraph g =
      memberGraph(6, {{0, 1, 1.0}, {2, 3, 1.0}, {4, 5, 1.0}, {1, 2, 1e-3}, {3, 4, 1e-3}});
  StoppingParams p;
  p.rule = StoppingRule::Threshold;
  p.threshold = 2.0; // the paper's rule splits everything that can be split
  EXPECT_EQ(buildHierarchy(g, 6, p).leaves().size(), 6u);
  p.rule = StoppingRule::LargestGap;
  p.gap_floor = 1e-3;
  const Hierarchy h = buildHierarchy(g, 6, p);
  ASSERT_EQ(h.leaves().size(), 3u);
  for (int leaf : h.leaves())
    EXPECT_EQ(h.nodes[leaf].vertices.size(), 4u) << "a pair with its representatives";
  // The bound on the number of parts holds.
  p.max_segments = 2;
  EXPECT_EQ(buildHierarchy(g, 6, p).leaves().size(), 2u);
  // Every kept split is within the threshold.
  p.max_segments = 20;
  p.threshold = 1e-4;
  EXPECT_EQ(buildHierarchy(g, 6, p).leaves().size(), 1u);
}

TEST(LargestGap, KeepsAtLeastOneSplitWithinTheThreshold) {
  // A uniform chain: every split costs about the same, so the gap rule has no jump to find;
  // it still makes the first split (and never more than max_segments parts).
  const WeightedGraph g = memberGraph(4, {{0, 1, 1.0}, {1, 2, 1.0}, {2, 3, 1.0}});
  StoppingParams p;
  p.threshold = 2.0;
  p.rule = StoppingRule::LargestGap;
  const std::size_t leaves = buildHierarchy(g, 4, p).leaves().size();
  EXPECT_GE(leaves, 2u);
  EXPECT_LE(leaves, 4u);
}
