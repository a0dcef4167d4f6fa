/*
 * The options that extend the paper's cut (each one setting away from the paper): adjacent
 * supernode pairs in G_s.
 */
#include "core/cut/supernode_graph.h"

#include "support/graphs.h"

#include <gtest/gtest.h>

#include <cmath>

using namespace pcl_ncut_seg;
using test::edgeWeight;

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
/// c02: the contact of s0 and s2, which meet at no saddle.
Connectivity ringConn(double c02 = 1.0) {
  return {{{0, 0}, 4.0}, {{1, 1}, 4.0}, {{2, 2}, 4.0}, {{0, 1}, 2.0}, {{1, 2}, 2.0}, {{0, 2}, c02}};
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
  // s0 and s2 touch with conn 2 of each one's total contact 4: a share of 1/2, joined.
  ASSERT_GE(0.5, kAdjacentShare);
  const WeightedGraph all = buildSupernodeGraph(ringSupernodes(), ringStats(), ringConn(2.0), p);
  EXPECT_EQ(all.edges.size(), saddles_only.edges.size() + 1);
  // eq. (9) with d1 = 0 (equal heights), d2 = 1 - 2/2 (the component's largest contact).
  EXPECT_NEAR(edgeWeight(all, m(3, 0), m(3, 2)), 1.0, 1e-12);
  EXPECT_NEAR(edgeWeight(all, m(3, 0), m(3, 1)), edgeWeight(saddles_only, m(3, 0), m(3, 1)), 1e-15);
  // With conn 1 of a total contact 3 (a share of 1/3) they only graze: not joined.
  ASSERT_LT(1.0 / 3.0, kAdjacentShare);
  EXPECT_EQ(edgeWeight(buildSupernodeGraph(ringSupernodes(), ringStats(), ringConn(1.0), p),
                       m(3, 0), m(3, 2)),
            -1);
}
