// The kNN phase: FLANN queries, Morton order with copies merged, and the parallel graph build.
#include "core/common/morton.h"
#include "core/graph/csr_graph.h"
#include "core/graph/knn.h"
#include <support/graphs.h>

#include <pcl/point_types.h>
#include <pcl/search/kdtree.h>

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numeric>
#include <random>
#include <set>

using namespace pcl_ncut_seg;

namespace {
/// Points on a regular grid: many equal distances, where a tree's tie-breaking shows.
std::vector<float> gridPoints(int side) {
  std::vector<float> xyz;
  for (int i = 0; i < side; ++i)
    for (int j = 0; j < side; ++j)
      for (float v : {0.1f * i, 0.1f * j, 0.0f})
        xyz.push_back(v);
  return xyz;
}

/// The neighbours pcl::search::KdTree finds (self excluded), as sets per point.
std::vector<std::set<std::uint32_t>> pclKnn(const std::vector<float>& xyz, std::size_t k) {
  pcl::PointCloud<pcl::PointXYZ>::Ptr cloud(new pcl::PointCloud<pcl::PointXYZ>);
  for (std::size_t i = 0; i < xyz.size() / 3; ++i)
    cloud->push_back(pcl::PointXYZ(xyz[3 * i], xyz[3 * i + 1], xyz[3 * i + 2]));
  pcl::search::KdTree<pcl::PointXYZ> tree(false);
  tree.setInputCloud(cloud);
  std::vector<std::set<std::uint32_t>> out(cloud->size());
  pcl::Indices nn;
  std::vector<float> sqr;
  for (std::size_t i = 0; i < cloud->size(); ++i) {
    tree.nearestKSearch((*cloud)[i], static_cast<int>(k + 1), nn, sqr);
    for (const auto q : nn)
      if (static_cast<std::size_t>(q) != i && out[i].size() < k)
        out[i].insert(static_cast<std::uint32_t>(q));
  }
  return out;
}
} // namespace

TEST(Knn, SameNeighboursAsPclKdTreeForAnyThreadCount) {
  for (const auto& xyz : {test::randomPoints(3000, 3), gridPoints(40)}) {
    const std::size_t n = xyz.size() / 3, k = 10;
    const auto expected = pclKnn(xyz, k);
    for (int threads : {1, 2, 3}) {
      std::vector<std::uint32_t> knn(n * k, 0xffffffffu);
      kNearestNeighbours(xyz.data(), n, k, threads, knn.data());
      for (std::size_t i = 0; i < n; ++i) {
        const std::set<std::uint32_t> got(knn.begin() + i * k, knn.begin() + (i + 1) * k);
        ASSERT_EQ(got, expected[i]) << "point " << i << ", " << threads << " threads";
      }
    }
  }
}

TEST(Knn, GraphDoesNotDependOnThreads) {
  const auto xyz = test::randomPoints(5000, 11);
  const std::size_t n = 5000, k = 8;
  std::vector<std::uint32_t> knn(n * k);
  kNearestNeighbours(xyz.data(), n, k, 2, knn.data());
  const CsrGraph one = buildSymmetricKnnGraph(xyz.data(), n, knn.data(), k, 1);
  for (int threads : {2, 4}) {
    const CsrGraph many = buildSymmetricKnnGraph(xyz.data(), n, knn.data(), k, threads);
    EXPECT_EQ(one.offsets, many.offsets);
    EXPECT_EQ(one.targets, many.targets);
    EXPECT_EQ(one.lengths, many.lengths);
  }
}

TEST(Knn, DistinctMortonOrderMergesCopies) {
  // 0, 2 and 5 share a position, 3 and 4 another (-0 equals 0); 1 is alone.
  const std::vector<float> xyz = {1, 1, 1, 0, 0, 0, 1, 1, 1, 0.5f, 0, 0, 0.5f, -0.0f, 0, 1, 1, 1};
  const DistinctMortonOrder order = distinctMortonOrder(xyz.data(), 6);
  ASSERT_EQ(order.point.size(), 3u);
  // Morton order of the distinct points 0, 1, 3: (0,0,0) < (0.5,0,0) < (1,1,1).
  const std::vector<std::uint32_t> point = {1, 3, 0}, rank = {1, 2, 0};
  EXPECT_EQ(order.point, point);
  EXPECT_EQ(order.rank, rank);
  const std::vector<std::pair<std::uint32_t, std::uint32_t>> copies = {{2, 2}, {4, 1}, {5, 2}};
  EXPECT_EQ(order.copies, copies);
  // Without copies it is the Morton order.
  const auto random = test::randomPoints(2000, 5);
  const DistinctMortonOrder plain = distinctMortonOrder(random.data(), 2000);
  EXPECT_EQ(plain.point, mortonOrder(random.data(), 2000));
  EXPECT_EQ(plain.rank, plain.point);
  EXPECT_TRUE(plain.copies.empty());
}

TEST(Knn, DistinctMortonOrderDoesNotDependOnTheOrderOfThePoints) {
  // 300 points in few grid cells (a tiny box beside one far point), many sharing a cell, some
  // at one position; reversed and shuffled, they give the same positions in the same order.
  std::vector<float> xyz = test::randomPoints(300, 9);
  for (float& c : xyz)
    c = std::round(c * 8.0f) * 1e-3f;
  xyz.insert(xyz.end(), {100.0f, 100.0f, 100.0f});
  const std::size_t n = xyz.size() / 3;
  auto positions = [](const std::vector<float>& pts) {
    const DistinctMortonOrder order = distinctMortonOrder(pts.data(), pts.size() / 3);
    std::vector<float> out;
    for (std::uint32_t i : order.point)
      out.insert(out.end(), pts.begin() + 3 * i, pts.begin() + 3 * i + 3);
    return out;
  };
  const std::vector<float> reference = positions(xyz);
  ASSERT_LT(reference.size(), xyz.size()); // there are copies
  std::vector<std::size_t> perm(n);
  std::iota(perm.begin(), perm.end(), std::size_t(0));
  std::reverse(perm.begin(), perm.end());
  for (int round = 0; round < 2; ++round) {
    std::vector<float> moved(3 * n);
    for (std::size_t i = 0; i < n; ++i)
      for (int d = 0; d < 3; ++d)
        moved[3 * i + d] = xyz[3 * perm[i] + d];
    EXPECT_EQ(positions(moved), reference) << "round " << round;
    std::mt19937 rng(4);
    std::shuffle(perm.begin(), perm.end(), rng);
  }
}
