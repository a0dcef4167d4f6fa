#include "core/supernodes/refinement.h"
#include "core/supernodes/supernodes.h"
#include <support/graphs.h>

#include <gtest/gtest.h>

using namespace pcl_ncut_seg;

namespace {
CsrGraph chain(std::size_t n) {
  std::vector<std::tuple<int, int, float>> edges;
  for (std::size_t i = 0; i + 1 < n; ++i)
    edges.emplace_back(static_cast<int>(i), static_cast<int>(i + 1), 1.f);
  return test::graphFromEdges(n, edges);
}
} // namespace

TEST(Supernodes, SaddleCreatesSupernodeAndRedirectsMergedOnes) {
  // Two peaks on a chain, at 6 (f = 4) and 2 (f = 3); they meet at 4, a saddle.
  const std::vector<float> f = {1, 2, 3, 2, 1.5f, 2, 4, 2, 1};
  const Supernodes sn = extractSupernodes(chain(9), f, 0.3f);
  ASSERT_EQ(sn.size(), 3u);
  EXPECT_EQ(sn.origin[0], 6u);
  EXPECT_EQ(sn.origin[1], 2u);
  EXPECT_EQ(sn.origin[2], 4u);
  EXPECT_FALSE(sn.at_saddle[0]);
  EXPECT_TRUE(sn.at_saddle[2]);
  // Points 0 and 8 (f = 1) come after the saddle: they join the new supernode, not their
  // peaks' supernodes, which now redirect to it.
  const std::vector<std::uint32_t> label = {2, 1, 1, 1, 2, 0, 0, 0, 2};
  EXPECT_EQ(sn.label, label);
  EXPECT_EQ(sn.parent[0], 2u);
  EXPECT_EQ(sn.parent[1], 2u);
  EXPECT_EQ(sn.parent[2], kNone);
  const std::vector<std::uint32_t> children = {0, 1};
  EXPECT_EQ(sn.children[2], children);
  EXPECT_EQ(sn.localMaxima(), (std::vector<std::uint32_t>{6, 2}));
  EXPECT_EQ(sn.saddles(), (std::vector<std::uint32_t>{4}));
}

namespace {
// Point 0 (f = 1) has ten neighbours: a chain 1..5 (f 10..6, one supernode), vertex 6 alone
// (f = 5, its own maximum) and four lower vertices 7..10.
CsrGraph crossingGraph() {
  std::vector<std::tuple<int, int, float>> e;
  for (int v = 1; v <= 10; ++v)
    e.emplace_back(0, v, 1.f);
  for (int v = 1; v < 5; ++v)
    e.emplace_back(v, v + 1, 1.f);
  return test::graphFromEdges(11, e);
}
const std::vector<float> kCrossingF = {1, 10, 9, 8, 7, 6, 5, 0.5f, 0.4f, 0.3f, 0.2f};
} // namespace

TEST(Supernodes, FeatureCrossingEdgeIsIgnoredBelowTheFraction) {
  // One of ten neighbours in vertex 6's supernode: 1 < 0.3 * 10, so that edge is crossing.
  const Supernodes sn = extractSupernodes(crossingGraph(), kCrossingF, 0.3f);
  EXPECT_EQ(sn.label[0], sn.label[1]);
  EXPECT_TRUE(sn.saddles().empty());
}

TEST(Supernodes, WithoutTheFractionRuleTheSamePointIsASaddle) {
  const Supernodes sn = extractSupernodes(crossingGraph(), kCrossingF, 0.0f);
  EXPECT_EQ(sn.saddles(), (std::vector<std::uint32_t>{0}));
  EXPECT_TRUE(sn.at_saddle[sn.label[0]]);
}

TEST(Supernodes, WhenEveryCandidateIsDroppedThePointFollowsTheSteepestAscent) {
  // Point 0 (f = 0) has neighbours 1, 2 (peak A, f 5 and 4) and 3, 4 (peak B, f 9 and 8,
  // farther away) and six lower ones: 2 < 0.3 * 10 for both peaks.
  std::vector<std::tuple<int, int, float>> e = {{0, 1, 1.f}, {0, 2, 1.f}, {0, 3, 4.f},
                                                {0, 4, 4.f}, {1, 2, 1.f}, {3, 4, 1.f}};
  for (int v = 5; v <= 10; ++v)
    e.emplace_back(0, v, 1.f);
  const std::vector<float> f = {0, 5, 4, 9, 8, -1, -1, -1, -1, -1, -1};
  const Supernodes sn = extractSupernodes(test::graphFromEdges(11, e), f, 0.3f);
  // z = (5 - 0) / 1 = 5 towards peak A beats (9 - 0) / 4 = 2.25 towards B.
  EXPECT_EQ(sn.label[0], sn.label[1]);
  EXPECT_NE(sn.label[0], sn.label[3]);
}

TEST(FeatureStats, HeightAreaWidthAndRadiusByHand) {
  // Path 0 - 1 - 2, unit lengths, f = 0, 0, 1: edge lengths of eq. (3) are 1 and sqrt(2).
  const CsrGraph g = test::graphFromEdges(3, {{0, 1, 1.f}, {1, 2, 1.f}});
  const std::vector<float> f = {0, 0, 1};
  const auto r = pointRadii(g, f);
  EXPECT_FLOAT_EQ(r[0], 1.0f);
  EXPECT_FLOAT_EQ(r[1], (1.0f + std::sqrt(2.0f)) / 2);
  EXPECT_FLOAT_EQ(r[2], std::sqrt(2.0f));
  Supernodes sn;
  sn.label = {0, 0, 0};
  sn.origin = {2};
  sn.at_saddle = {false};
  sn.parent = {kNone};
  sn.children = {{}};
  const FeatureStats st = featureStats(sn, f, r);
  const double pi = 3.14159265358979;
  const double area = pi * (r[0] * r[0] + r[1] * r[1] + r[2] * r[2]);
  EXPECT_FLOAT_EQ(st.height[0], 1.0f);
  EXPECT_NEAR(st.area[0], area, 1e-5);
  EXPECT_NEAR(st.width[0], area / 1.0, 1e-5);
}

TEST(Refinement, SmallSaddleSupernodeIsMergedUpIntoItsChildren) {
  // Two long branches meeting at a saddle, with a tiny tail below it.
  //   0..19 : f from 20 down to 1 (peak at 0)      } joined at 40 (f = 0.5)
  //   20..39: f from 19.5 down to 0.5+ (peak at 20) }
  //   40 - 41: the saddle and one point below it
  std::vector<std::tuple<int, int, float>> e;
  std::vector<float> f(42);
  for (int i = 0; i < 20; ++i) {
    f[i] = 20.f - i;
    f[20 + i] = 19.5f - i;
    if (i + 1 < 20) {
      e.emplace_back(i, i + 1, 1.f);
      e.emplace_back(20 + i, 21 + i, 1.f);
    }
  }
  f[40] = 0.4f;
  f[41] = 0.3f;
  e.emplace_back(19, 40, 1.f);
  e.emplace_back(39, 40, 1.f);
  e.emplace_back(40, 41, 1.f);
  const CsrGraph g = test::graphFromEdges(42, e);
  const Supernodes raw = extractSupernodes(g, f, 0.3f);
  ASSERT_EQ(raw.size(), 3u);
  ASSERT_TRUE(raw.at_saddle[2]);
  const auto r = pointRadii(g, f);
  RefinementParams params;
  params.area_fraction = 0.1f; // the saddle's 2 points are small, the branches are not
  params.height_fraction = 0.01f;
  const Supernodes out = refineSupernodes(g, f, r, raw, params);
  ASSERT_EQ(out.size(), 2u);
  EXPECT_NE(out.label[0], out.label[20]);
  // The saddle's points went to a branch that touches them.
  EXPECT_TRUE(out.label[40] == out.label[19] || out.label[40] == out.label[39]);
  EXPECT_EQ(out.label[41], out.label[40]);
}

TEST(Refinement, SkinnySupernodeIsMergedDownIntoItsSaddle) {
  // A long branch (0..19) and a short bump (20, 21) meet at saddle 22, which continues down.
  std::vector<std::tuple<int, int, float>> e;
  std::vector<float> f(30);
  for (int i = 0; i < 20; ++i) {
    f[i] = 30.f - i;
    if (i + 1 < 20)
      e.emplace_back(i, i + 1, 1.f);
  }
  f[20] = 10.05f;
  f[21] = 10.02f;
  e.emplace_back(20, 21, 1.f);
  f[22] = 10.f;
  e.emplace_back(19, 22, 1.f);
  e.emplace_back(21, 22, 1.f);
  for (int i = 23; i < 30; ++i) {
    f[i] = 10.f - (i - 22);
    e.emplace_back(i - 1, i, 1.f);
  }
  const CsrGraph g = test::graphFromEdges(30, e);
  const Supernodes raw = extractSupernodes(g, f, 0.3f);
  ASSERT_EQ(raw.size(), 3u);
  const auto r = pointRadii(g, f);
  RefinementParams params;
  params.area_fraction = 0.0f;
  params.height_fraction = 0.05f; // the bump's height 0.03 is below 5% of 11
  const Supernodes out = refineSupernodes(g, f, r, raw, params);
  ASSERT_EQ(out.size(), 2u);
  EXPECT_EQ(out.label[20], out.label[22]); // merged down into the saddle's supernode
  EXPECT_NE(out.label[0], out.label[22]);
}

TEST(Supernodes, CompactLabelsNumberLabelsByTheirFirstPoint) {
  // Labels 3, 0 and 5 of 7 are carried, first by points 0, 1 and 3.
  const std::vector<std::uint32_t> label = {3, 0, 3, 5, 0};
  std::vector<std::uint32_t> id, compact;
  const std::vector<std::uint32_t> first = compactLabels(label, 7, id, compact);
  EXPECT_EQ(first, (std::vector<std::uint32_t>{0, 1, 3}));
  EXPECT_EQ(compact, (std::vector<std::uint32_t>{0, 1, 0, 2, 1}));
  EXPECT_EQ(id, (std::vector<std::uint32_t>{1, kNone, kNone, 0, kNone, 2, kNone}));
}

TEST(Supernodes, RenumberingKeepsTheSaddleRelationsOfTheSupernodesLeft) {
  // Supernode 1 is empty; 3 terminates at 0, 2 at 1 (which is dropped), 0 at nothing.
  Supernodes sn;
  sn.label = {2, 3, 0, 3};
  sn.origin = {10, 11, 12, 13};
  sn.at_saddle = {true, true, false, false};
  sn.parent = {kNone, kNone, 1, 0};
  const Supernodes out = renumberSupernodes(sn);
  ASSERT_EQ(out.size(), 3u); // 2 -> 0, 3 -> 1, 0 -> 2
  EXPECT_EQ(out.label, (std::vector<std::uint32_t>{0, 1, 2, 1}));
  EXPECT_EQ(out.origin, (std::vector<std::uint32_t>{12, 13, 10}));
  EXPECT_EQ(out.at_saddle, (std::vector<bool>{false, false, true}));
  EXPECT_EQ(out.parent, (std::vector<std::uint32_t>{kNone, 2, kNone}));
  EXPECT_EQ(out.children[2], (std::vector<std::uint32_t>{1}));
  EXPECT_TRUE(out.children[0].empty());
}
