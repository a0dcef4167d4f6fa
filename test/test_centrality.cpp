#include "core/centrality/centrality.h"
#include <support/graphs.h>

#include <gtest/gtest.h>

#include <algorithm>
#include <vector>

using namespace pcl_ncut_seg;

namespace {
CsrGraph randomKnnGraph(std::size_t n, std::size_t k, unsigned seed) {
  const auto xyz = test::randomPoints(n, seed);
  const auto knn = test::bruteForceKnn(xyz, k);
  return buildSymmetricKnnGraph(xyz.data(), n, knn.data(), k);
}
} // namespace

TEST(Centrality, BoostDijkstraMatchesAllPairsShortestPaths) {
  const CsrGraph g = randomKnnGraph(150, 5, 3);
  const auto apsp = test::allPairsShortestPaths(g);
  for (std::uint32_t s : {0u, 17u, 149u}) {
    const auto d = geodesicDistances(g, s);
    for (std::size_t v = 0; v < 150; ++v)
      EXPECT_NEAR(d[v], apsp[s * 150 + v], 1e-5 * (1 + apsp[s * 150 + v]));
  }
}

TEST(Centrality, EqualsMeanGeodesicDistanceToTheSamples) {
  for (unsigned seed : {1u, 2u, 3u}) {
    const std::size_t n = 180;
    const CsrGraph g = randomKnnGraph(n, 6, seed);
    const Centrality c = computeCentrality(g, 0, 1);
    ASSERT_EQ(c.num_components, 1u);
    // ceil(sqrt(180)) = 14 distinct samples
    ASSERT_EQ(c.samples.size(), 14u);
    auto sorted = c.samples;
    std::sort(sorted.begin(), sorted.end());
    EXPECT_EQ(std::unique(sorted.begin(), sorted.end()), sorted.end());
    const auto apsp = test::allPairsShortestPaths(g);
    for (std::size_t v = 0; v < n; ++v) {
      double sum = 0;
      for (std::uint32_t s : c.samples)
        sum += apsp[s * n + v];
      EXPECT_NEAR(c.f[v], sum / c.samples.size(), 1e-5 * (1 + sum / c.samples.size()));
    }
  }
}

TEST(Centrality, SamplesAreFarthestPoints) {
  const std::size_t n = 160;
  const CsrGraph g = randomKnnGraph(n, 6, 11);
  const Centrality c = computeCentrality(g, 10, 1);
  const auto apsp = test::allPairsShortestPaths(g);
  // First sample: the farthest vertex from vertex 0.
  double ecc = 0;
  for (std::size_t v = 0; v < n; ++v)
    ecc = std::max(ecc, apsp[v]);
  EXPECT_NEAR(apsp[c.samples[0]], ecc, 1e-6);
  // Each next sample maximises h, the distance to the samples chosen before it (step 4).
  for (std::size_t i = 1; i < c.samples.size(); ++i) {
    auto h = [&](std::size_t v) {
      double m = std::numeric_limits<double>::infinity();
      for (std::size_t j = 0; j < i; ++j)
        m = std::min(m, apsp[c.samples[j] * n + v]);
      return m;
    };
    double best = 0;
    for (std::size_t v = 0; v < n; ++v)
      best = std::max(best, h(v));
    EXPECT_NEAR(h(c.samples[i]), best, 1e-5) << "sample " << i;
  }
}

TEST(Centrality, IdenticalForAnyNumberOfThreads) {
  const CsrGraph g = randomKnnGraph(900, 8, 5);
  const Centrality one = computeCentrality(g, 0, 1);
  const Centrality two = computeCentrality(g, 0, 2);
  const Centrality three = computeCentrality(g, 0, 3);
  EXPECT_EQ(one.f, two.f);
  EXPECT_EQ(one.f, three.f);
  EXPECT_EQ(one.samples, two.samples);
}

TEST(Centrality, IdenticalForAnyNumberOfThreadsOnSeveralComponents) {
  // Three far-apart clouds with their points interleaved: the searches of one component start
  // while the samples of the next are still being chosen.
  const std::size_t per = 400, k = 8;
  std::vector<float> xyz;
  for (unsigned c = 0; c < 3; ++c) {
    const auto part = test::randomPoints(per, 20 + c);
    for (std::size_t i = 0; i < part.size(); ++i)
      xyz.push_back(part[i] + (i % 3 == 0 ? 10.0f * static_cast<float>(c) : 0.0f));
  }
  std::vector<float> mixed(xyz.size());
  for (std::size_t i = 0; i < 3 * per; ++i) { // point i of the result: point (i % 3, i / 3)
    const std::size_t from = (i % 3) * per + i / 3;
    std::copy_n(&xyz[3 * from], 3, &mixed[3 * i]);
  }
  const auto knn = test::bruteForceKnn(mixed, k);
  const CsrGraph g = buildSymmetricKnnGraph(mixed.data(), 3 * per, knn.data(), k);
  const Centrality one = computeCentrality(g, 0, 1);
  ASSERT_EQ(one.num_components, 3u);
  for (unsigned threads : {2u, 3u, 8u}) {
    const Centrality many = computeCentrality(g, 0, threads);
    EXPECT_EQ(one.f, many.f) << threads << " threads";
    EXPECT_EQ(one.samples, many.samples) << threads << " threads";
  }
}

TEST(Centrality, EachComponentIsItsOwnSurface) {
  // Two paths: 0-1-2 (lengths 1) and 3-4 (length 5).
  const CsrGraph g = test::graphFromEdges(5, {{0, 1, 1.f}, {1, 2, 1.f}, {3, 4, 5.f}});
  const Centrality c = computeCentrality(g, 0, 1);
  EXPECT_EQ(c.num_components, 2u);
  // Component {0,1,2}: ceil(sqrt(3)) = 2 samples: 2 (farthest from 0), then 0.
  EXPECT_FLOAT_EQ(c.f[0], 1.0f);
  EXPECT_FLOAT_EQ(c.f[1], 1.0f);
  EXPECT_FLOAT_EQ(c.f[2], 1.0f);
  // Component {3,4}: 2 samples (4, then 3): f = 2.5 everywhere.
  EXPECT_FLOAT_EQ(c.f[3], 2.5f);
  EXPECT_FLOAT_EQ(c.f[4], 2.5f);
  for (float v : c.f)
    EXPECT_TRUE(std::isfinite(v));
}

TEST(Centrality, DuplicatePointsGetEqualCentrality) {
  const CsrGraph g = test::graphFromEdges(4, {{0, 1, 0.f}, {1, 2, 1.f}, {2, 3, 1.f}, {0, 2, 1.f}});
  const Centrality c = computeCentrality(g, 0, 1);
  EXPECT_EQ(c.f[0], c.f[1]);
}
