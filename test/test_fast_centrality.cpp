// The Fast (coarse) centrality: the same result for any number of threads, and components that
// match the kNN graph's.
#include "core/centrality/coarse_centrality.h"
#include "core/graph/csr_graph.h"
#include "core/graph/knn.h"
#include <support/graphs.h>

#include <gtest/gtest.h>

using namespace pcl_ncut_seg;

namespace {
CsrGraph graphOf(const std::vector<float>& xyz, std::size_t k) {
  const std::size_t n = xyz.size() / 3;
  std::vector<std::uint32_t> knn(n * k, 0xffffffffu);
  kNearestNeighbours(xyz.data(), n, k, 1, knn.data());
  return buildSymmetricKnnGraph(xyz.data(), n, knn.data(), k);
}
} // namespace

TEST(FastCentrality, SameForAnyThreadCountWithSeveralComponents) {
  // Three separate clumps and a lone far point (a component with one representative).
  std::vector<float> xyz = test::randomPoints(12000, 21);
  for (std::size_t i = 0; i < 12000; ++i)
    xyz[3 * i] += 3.0f * static_cast<float>(i % 3);
  for (float v : {50.0f, 50.0f, 50.0f})
    xyz.push_back(v);
  const CsrGraph g = graphOf(xyz, 8);
  std::vector<std::uint32_t> component;
  const std::size_t components = connectedComponents(g, component);
  ASSERT_GE(components, 4u);
  const Centrality one = computeCoarseCentrality(g, 1500, 0, 1);
  EXPECT_EQ(one.num_components, components);
  EXPECT_EQ(one.component, component);
  for (unsigned threads : {2u, 3u, 4u}) {
    const Centrality many = computeCoarseCentrality(g, 1500, 0, threads);
    EXPECT_EQ(one.f, many.f) << threads << " threads";
    EXPECT_EQ(one.samples, many.samples) << threads << " threads";
    EXPECT_EQ(one.component, many.component) << threads << " threads";
  }
}
