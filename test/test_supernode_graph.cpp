#include "core/cut/supernode_graph.h"
#include <support/graphs.h>

#include <gtest/gtest.h>

#include <cmath>

using namespace pcl_ncut_seg;
using test::edgeWeight;
using test::threeSupernodes;

TEST(Connectivity, Eq8ByHand) {
  // Path 0 - 1 - 2, unit lengths, f = 0, 0, 1; supernodes {0, 1} and {2}.
  const CsrGraph g = test::graphFromEdges(3, {{0, 1, 1.f}, {1, 2, 1.f}});
  const Connectivity c = supernodeConnectivity(g, {0, 0, 1}, {0, 0, 1});
  ASSERT_EQ(c.size(), 2u);                         // (0,0) and (0,1); supernode 1 has no inner edge
  EXPECT_NEAR(c.at({0, 0}), 2.0, 1e-12);           // 0->1 and 1->0
  EXPECT_NEAR(c.at({0, 1}), std::sqrt(2.0), 1e-7); // 1->2 with ||.||_2 of eq. (3)
}

namespace {
// Features and connectivity of threeSupernodes() (Fig. 6).
FeatureStats threeStats() {
  FeatureStats st;
  st.height = {1, 2, 4};
  st.area = {2, 2, 8};
  st.width = {2, 1, 2};
  return st;
}
Connectivity threeConn() {
  return {{{0, 0}, 4.0}, {{1, 1}, 2.0}, {{2, 2}, 8.0}, {{0, 2}, 1.0}, {{1, 2}, 3.0}};
}
} // namespace

TEST(SupernodeGraph, Weights7And9ByHand) {
  SimilarityParams p; // beta 2, alpha1 2, alpha2 0.5
  p.normalize_width = false;
  p.adjacency = Adjacency::Saddles; // the paper's graph
  const WeightedGraph g = buildSupernodeGraph(threeSupernodes(), threeStats(), threeConn(), p);
  EXPECT_EQ(g.num_vertices, 6u);
  EXPECT_EQ(g.edges.size(), 5u); // three r-m, two m-m
  // eq. (7): exp(-(1 / (beta f_w)) (1 - conn_ii / max conn_jj)), max conn_jj = 8
  EXPECT_NEAR(edgeWeight(g, 0, 3), std::exp(-0.125), 1e-12);
  EXPECT_NEAR(edgeWeight(g, 1, 4), std::exp(-0.375), 1e-12);
  EXPECT_NEAR(edgeWeight(g, 2, 5), 1.0, 1e-12);
  // eq. (9) for m0 - m2: d1 = 3/3, d2 = 1 - 1/3, alpha_02 = 0.5 * 2/2
  EXPECT_NEAR(edgeWeight(g, 3, 5), std::exp(-1.0 / 2.0 - (2.0 / 3.0) / 0.5), 1e-12);
  // m1 - m2: d1 = 2/3, d2 = 0, alpha_12 = 0.5 * 1/2
  EXPECT_NEAR(edgeWeight(g, 4, 5), std::exp(-(2.0 / 3.0) / 2.0), 1e-12);
  EXPECT_LT(edgeWeight(g, 3, 4), 0); // no edge between supernodes that share no saddle
}

TEST(SupernodeGraph, WidthNormalisationMakesWeightsUnitFree) {
  SimilarityParams p;
  p.adjacency = Adjacency::Saddles;   // the paper's graph
  FeatureStats scaled = threeStats(); // the same shape in units 10x larger
  for (std::size_t i = 0; i < 3; ++i) {
    scaled.height[i] *= 10;
    scaled.area[i] *= 100;
    scaled.width[i] *= 10;
  }
  Connectivity conn = threeConn();
  for (auto& kv : conn)
    kv.second *= 10;
  const WeightedGraph a = buildSupernodeGraph(threeSupernodes(), threeStats(), threeConn(), p);
  const WeightedGraph b = buildSupernodeGraph(threeSupernodes(), scaled, conn, p);
  ASSERT_EQ(a.edges.size(), b.edges.size());
  for (std::size_t i = 0; i < a.edges.size(); ++i)
    EXPECT_NEAR(a.edges[i].w, b.edges[i].w, 1e-12);
}

TEST(SupernodeGraph, AdjacentTreesWithoutSaddleAreJoinedAtTheirStrongestContact) {
  Supernodes sn;
  sn.label = {0, 1, 2};
  sn.origin = {0, 1, 2};
  sn.at_saddle = {false, false, false};
  sn.parent = {kNone, kNone, kNone};
  sn.children = {{}, {}, {}};
  FeatureStats st;
  st.height = {1, 1, 1};
  st.area = {1, 1, 1};
  st.width = {1, 1, 1};
  const Connectivity conn = {{{0, 1}, 1.0}, {{0, 2}, 5.0}, {{1, 2}, 2.0}};
  SimilarityParams p;
  p.adjacency = Adjacency::Saddles;                                 // the paper's graph
  EXPECT_EQ(buildSupernodeGraph(sn, st, conn, p).edges.size(), 3u); // r-m only
  p.adjacency = Adjacency::Trees;
  const WeightedGraph g = buildSupernodeGraph(sn, st, conn, p);
  // A maximum spanning forest: {0, 2} then {1, 2}; {0, 1} would close a cycle.
  EXPECT_EQ(g.edges.size(), 5u);
  EXPECT_GT(edgeWeight(g, 3, 5), 0);
  EXPECT_GT(edgeWeight(g, 4, 5), 0);
  EXPECT_LT(edgeWeight(g, 3, 4), 0);
}

TEST(SupernodeGraph, EachComponentIsWeighedOnItsOwn) {
  // threeSupernodes() as supernodes 0-2, and beside them (no kNN edge between) a second object
  // of the same shape, higher, larger and better connected: supernodes 3-5. The maxima of
  // eqs. (7) and (9) and the width's unit are per component, so 0-2 keep the weights they have
  // alone, and 3-5 get the weights they would have alone.
  Supernodes two = threeSupernodes();
  two.label = {0, 1, 2, 3, 4, 5};
  two.origin = {0, 1, 2, 3, 4, 5};
  two.at_saddle = {false, false, true, false, false, true};
  two.parent = {2, 2, kNone, 5, 5, kNone};
  two.children = {{}, {}, {0, 1}, {}, {}, {3, 4}};
  FeatureStats st = threeStats(), big = threeStats();
  Connectivity conn = threeConn(), big_conn;
  for (std::size_t i = 0; i < 3; ++i) {
    big.height[i] *= 7;
    big.area[i] *= 49;
    big.width[i] *= 7;
  }
  for (const auto& [key, value] : threeConn())
    big_conn[key] = 5.0 * value;
  for (std::size_t i = 0; i < 3; ++i) {
    st.height.push_back(big.height[i]);
    st.area.push_back(big.area[i]);
    st.width.push_back(big.width[i]);
  }
  for (const auto& [key, value] : big_conn)
    conn[{key.first + 3, key.second + 3}] = value;
  for (const Adjacency adjacency : {Adjacency::Saddles, Adjacency::All}) {
    SimilarityParams p; // the width normalized by sqrt(total area): per component too
    p.adjacency = adjacency;
    const WeightedGraph both = buildSupernodeGraph(two, st, conn, p);
    const WeightedGraph first =
        buildSupernodeGraph(threeSupernodes(), threeStats(), threeConn(), p);
    const WeightedGraph second = buildSupernodeGraph(threeSupernodes(), big, big_conn, p);
    // r_i = i, m_i = l + i: l = 6 in both, 3 alone.
    for (std::uint32_t a = 0; a < 3; ++a)
      for (std::uint32_t b = a; b < 3; ++b) {
        const auto inBoth = [](std::uint32_t v, std::uint32_t shift) {
          return v < 3 ? v + shift : v + 3 + shift;
        };
        for (const auto& [alone, shift] : {std::make_pair(&first, 0u), {&second, 3u}}) {
          for (const auto& [x, y] : {std::make_pair(a, b + 3), {a + 3, b + 3}}) {
            const double w = edgeWeight(*alone, x, y);
            EXPECT_NEAR(edgeWeight(both, inBoth(x, shift), inBoth(y, shift)), w,
                        1e-12 * std::max(1.0, std::abs(w)))
                << a << " " << b << " shift " << shift;
          }
        }
      }
  }
}
