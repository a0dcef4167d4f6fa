#include <support/graphs.h>

#include <gtest/gtest.h>

using namespace pcl_ncut_seg;

TEST(CsrGraph, KnnGraphIsTheSymmetricUnionWithEuclideanLengths) {
  // Points on a line at 0, 1, 3, 7: with k = 1, 0->1, 1->0, 2->1, 3->2.
  const std::vector<float> xyz = {0, 0, 0, 1, 0, 0, 3, 0, 0, 7, 0, 0};
  const std::vector<std::uint32_t> knn = {1, 0, 1, 2};
  const CsrGraph g = buildSymmetricKnnGraph(xyz.data(), 4, knn.data(), 1);
  ASSERT_EQ(g.numVertices(), 4u);
  EXPECT_EQ(g.numDirectedEdges(), 6u); // {0,1}, {1,2}, {2,3} both ways, 0->1 merged
  const std::vector<std::uint32_t> offsets = {0, 1, 3, 5, 6};
  const std::vector<std::uint32_t> targets = {1, 0, 2, 1, 3, 2};
  const std::vector<float> lengths = {1, 1, 2, 2, 4, 4};
  EXPECT_EQ(g.offsets, offsets);
  EXPECT_EQ(g.targets, targets);
  EXPECT_EQ(g.lengths, lengths);
}

TEST(CsrGraph, IgnoresSelfAndMissingNeighbours) {
  const std::vector<float> xyz = {0, 0, 0, 1, 0, 0};
  const std::uint32_t none = 99;
  const std::vector<std::uint32_t> knn = {0, 1, none, none};
  const CsrGraph g = buildSymmetricKnnGraph(xyz.data(), 2, knn.data(), 2);
  EXPECT_EQ(g.numDirectedEdges(), 2u);
}

TEST(CsrGraph, ConnectedComponentsNumberedBySmallestVertex) {
  const CsrGraph g = test::graphFromEdges(6, {{4, 5, 1.f}, {0, 2, 1.f}, {1, 3, 1.f}});
  std::vector<std::uint32_t> comp;
  EXPECT_EQ(connectedComponents(g, comp), 3u);
  const std::vector<std::uint32_t> expected = {0, 1, 0, 1, 2, 2};
  EXPECT_EQ(comp, expected);
}

TEST(CsrGraph, RandomKnnGraphIsSymmetric) {
  const auto xyz = test::randomPoints(200, 7);
  const auto knn = test::bruteForceKnn(xyz, 6);
  const CsrGraph g = buildSymmetricKnnGraph(xyz.data(), 200, knn.data(), 6);
  for (std::uint32_t v = 0; v < 200; ++v) {
    EXPECT_GE(g.degree(v), 6u);
    for (std::uint32_t e = g.offsets[v]; e < g.offsets[v + 1]; ++e) {
      const std::uint32_t w = g.targets[e];
      const auto b = g.targets.begin() + g.offsets[w], end = g.targets.begin() + g.offsets[w + 1];
      EXPECT_TRUE(std::binary_search(b, end, v)) << v << " -> " << w << " has no twin";
    }
  }
}
