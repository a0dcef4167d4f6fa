/*
 * The hand-written searches (the bucketed one and the exact multi-source one) against
 * Boost.Graph's Dijkstra (the reference) on real kNN graphs, the two-nearest-sources search
 * against brute force, the Morton order, and the Fast centrality against the Exact one.
 */
#include "core/centrality/coarse_centrality.h"
#include "core/common/morton.h"
#include "core/graph/shortest_paths.h"
#include <pcl_ncut_seg/supernode_ncut_segmentation.h>

#include "support/graphs.h"
#include "support/knn_graph.h"
#include <shapes/shapes.h>
#include <surfaces/mesh_sampling.h>

#include <pcl/io/pcd_io.h>

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <iostream>
#include <limits>
#include <numeric>
#include <string>
#include <thread>
#include <vector>

using namespace pcl_ncut_seg;
using Cloud = pcl::PointCloud<pcl::PointXYZ>;

namespace {

constexpr float kInf = std::numeric_limits<float>::infinity();

/// The symmetric k = 10 graph of a cloud, vertices in the cloud's order.
CsrGraph knnGraph(const std::vector<float>& xyz) {
  return test::kdTreeKnnGraph(xyz, 10);
}

/// Real surfaces: the bundled hand (8000 points, in file order), and 40000 samples of the
/// horse mesh from the shared data when it is present. A file present but unreadable fails the
/// test.
std::vector<std::vector<float>> realClouds() {
  std::vector<std::vector<float>> clouds;
  const std::string hand_path = std::string(PCL_NCUT_SEG_DATA_DIR) + "/hand.pcd";
  Cloud hand;
  if (pcl::io::loadPCDFile(hand_path, hand) == 0)
    clouds.push_back(test::xyzOf(hand));
  else
    ADD_FAILURE() << "cannot read the bundled " << hand_path;
  const std::filesystem::path horse =
      std::filesystem::path(PCL_NCUT_SEG_SHARED_DATA) / "models" / "horse.off";
  TriangleMesh mesh;
  std::string error;
  if (!std::filesystem::exists(horse))
    std::cout << "[ skipped  ] shared data absent: no " << horse << std::endl;
  else if (readOff(horse.string(), mesh, &error))
    clouds.push_back(sampleSurface(mesh, 40000, 3));
  else
    ADD_FAILURE() << horse << ": " << error;
  return clouds;
}

} // namespace

TEST(BucketDijkstra, DistancesEqualBoostsBitForBitOnRealGraphs) {
  const auto clouds = realClouds();
  ASSERT_FALSE(clouds.empty()) << "data/hand.pcd not found";
  for (const auto& xyz : clouds) {
    const std::size_t n = xyz.size() / 3;
    // In the file's order, and in Morton order as the PCL front end numbers vertices.
    const std::vector<std::uint32_t> morton = mortonOrder(xyz.data(), n);
    std::vector<float> reordered(xyz.size());
    for (std::size_t i = 0; i < n; ++i)
      std::copy_n(&xyz[3 * morton[i]], 3, &reordered[3 * i]);
    for (const std::vector<float>* points :
         {&xyz, static_cast<const std::vector<float>*>(&reordered)}) {
      const CsrGraph g = knnGraph(*points);
      BucketDijkstra search(g);
      std::vector<float> dist(n, kInf);
      for (std::uint32_t source :
           {0u, static_cast<std::uint32_t>(n / 3), static_cast<std::uint32_t>(n - 1)}) {
        std::fill(dist.begin(), dist.end(), kInf);
        std::vector<std::uint32_t> touched;
        search.run(source, dist.data(), nullptr, &touched);
        const std::vector<float> reference = geodesicDistances(g, source);
        std::size_t differ = 0;
        for (std::size_t v = 0; v < n; ++v)
          differ += dist[v] != reference[v];
        EXPECT_EQ(differ, 0u) << n << " points, source " << source;
        std::sort(touched.begin(), touched.end());
        EXPECT_EQ(std::unique(touched.begin(), touched.end()), touched.end());
        EXPECT_EQ(touched.size(), n) << "every vertex of a connected graph is reached once";
      }
    }
  }
}

TEST(MultiSourceDijkstra, DistancesEqualBoostsBitForBitOnRealGraphs) {
  // The exact search of the other stages (ridgeDistance() and the bands) against Boost's
  // Dijkstra: from several sources, each vertex's distance to the nearest one.
  const auto clouds = realClouds();
  ASSERT_FALSE(clouds.empty()) << "data/hand.pcd not found";
  for (const auto& xyz : clouds) {
    const std::size_t n = xyz.size() / 3;
    const CsrGraph g = knnGraph(xyz);
    std::vector<std::uint32_t> sources;
    for (std::uint32_t v = 7; v < n; v += static_cast<std::uint32_t>(n / 5))
      sources.push_back(v);
    std::vector<float> dist(n, kInf), reference(n, kInf);
    for (std::uint32_t s : sources) {
      dist[s] = 0.0f;
      const std::vector<float> from = geodesicDistances(g, s);
      for (std::size_t v = 0; v < n; ++v)
        reference[v] = std::min(reference[v], from[v]);
    }
    multiSourceDijkstra(g, sources, dist.data(), AnyEdge(), ExpandAll());
    std::size_t differ = 0;
    for (std::size_t v = 0; v < n; ++v)
      differ += dist[v] != reference[v];
    EXPECT_EQ(differ, 0u) << n << " points, " << sources.size() << " sources";
  }
}

TEST(BucketDijkstra, HandlesComponentsZeroLengthsAndAnOutlierEdge) {
  // 0-1-2 with a zero-length edge, 3-4 far away, and 5-6 joined by a very long edge.
  const CsrGraph g =
      test::graphFromEdges(7, {{0, 1, 0.f}, {1, 2, 1.f}, {3, 4, 2.f}, {5, 6, 1e7f}, {2, 5, 0.5f}});
  BucketDijkstra search(g);
  for (std::uint32_t s = 0; s < 7; ++s) {
    std::vector<float> dist(7, kInf);
    search.run(s, dist.data());
    EXPECT_EQ(dist, geodesicDistances(g, s)) << "source " << s;
  }
}

TEST(NearestTwoSources, MatchesBruteForce) {
  const std::size_t n = 1500;
  const auto xyz = test::randomPoints(n, 9);
  const CsrGraph g = knnGraph(xyz);
  std::vector<std::uint32_t> sources;
  for (std::uint32_t v = 0; v < n; v += 53)
    sources.push_back(v);
  const NearestSources near = nearestTwoSources(g, sources);
  std::vector<std::vector<float>> from(sources.size());
  for (std::size_t i = 0; i < sources.size(); ++i)
    from[i] = geodesicDistances(g, sources[i]);
  for (std::size_t v = 0; v < n; ++v) {
    std::vector<float> d;
    for (const auto& f : from)
      d.push_back(f[v]);
    std::vector<float> sorted = d;
    std::sort(sorted.begin(), sorted.end());
    EXPECT_EQ(near.at[v].first_dist, sorted[0]) << v;
    EXPECT_EQ(near.at[v].second_dist, sorted[1]) << v;
    ASSERT_LT(near.at[v].first, sources.size());
    ASSERT_LT(near.at[v].second, sources.size());
    EXPECT_NE(near.at[v].first, near.at[v].second);
    EXPECT_EQ(d[near.at[v].first], near.at[v].first_dist);
    EXPECT_EQ(d[near.at[v].second], near.at[v].second_dist);
  }
}

TEST(Morton, OrderIsAPermutationThatKeepsNeighboursClose) {
  const std::size_t n = 20000;
  const auto xyz = test::randomPoints(n, 4);
  const std::vector<std::uint32_t> order = mortonOrder(xyz.data(), n);
  std::vector<std::uint32_t> sorted = order;
  std::sort(sorted.begin(), sorted.end());
  for (std::uint32_t i = 0; i < n; ++i)
    ASSERT_EQ(sorted[i], i);
  // Consecutive points along the curve are much closer than consecutive input points.
  auto meanStep = [&](auto at) {
    double sum = 0;
    for (std::size_t i = 1; i < n; ++i) {
      const float* a = &xyz[3 * at(i - 1)];
      const float* b = &xyz[3 * at(i)];
      sum += std::sqrt((a[0] - b[0]) * (a[0] - b[0]) + (a[1] - b[1]) * (a[1] - b[1]) +
                       (a[2] - b[2]) * (a[2] - b[2]));
    }
    return sum / (n - 1);
  };
  const double along = meanStep([&](std::size_t i) { return order[i]; });
  const double input = meanStep([](std::size_t i) { return i; });
  EXPECT_LT(along, 0.1 * input);
}

TEST(CoarseCentrality, IsExactWhenTheGraphIsSmall) {
  const CsrGraph g = knnGraph(test::randomPoints(900, 5));
  const Centrality exact = computeCentrality(g, 0, 1);
  const Centrality coarse = computeCoarseCentrality(g, 900, 0, 1);
  EXPECT_EQ(exact.f, coarse.f);
  EXPECT_EQ(exact.samples, coarse.samples);
  // Up to 1.25 times the representatives a coarse graph does not pay: exact too.
  const CsrGraph h = knnGraph(test::randomPoints(1125, 5));
  EXPECT_FALSE(coarseGraphPays(1125, 900));
  EXPECT_EQ(computeCoarseCentrality(h, 900, 0, 1).f, computeCentrality(h, 0, 1).f);
  EXPECT_TRUE(coarseGraphPays(1126, 900));
}

TEST(CoarseCentrality, IsCloseToExactAndIndependentOfThreads) {
  const auto clouds = realClouds();
  ASSERT_FALSE(clouds.empty());
  for (const auto& xyz : clouds) {
    const std::size_t n = xyz.size() / 3;
    const CsrGraph g = knnGraph(xyz);
    const Centrality exact = computeCentrality(g, 0, 2);
    const std::size_t reps = n / 8;
    const Centrality one = computeCoarseCentrality(g, reps, 0, 1);
    const Centrality two = computeCoarseCentrality(g, reps, 0, 2);
    EXPECT_EQ(one.f, two.f);
    EXPECT_EQ(one.samples, two.samples);
    ASSERT_EQ(one.f.size(), n);
    // Relative error of f, and the rank correlation of f (Spearman) with the exact f.
    double error = 0;
    for (std::size_t v = 0; v < n; ++v)
      error += std::abs(one.f[v] - exact.f[v]) / exact.f[v];
    error /= n;
    auto ranks = [n](const std::vector<float>& f) {
      std::vector<std::uint32_t> order(n);
      std::iota(order.begin(), order.end(), 0u);
      std::sort(order.begin(), order.end(), [&](auto a, auto b) { return f[a] < f[b]; });
      std::vector<double> r(n);
      for (std::size_t i = 0; i < n; ++i)
        r[order[i]] = static_cast<double>(i);
      return r;
    };
    const auto ra = ranks(one.f), rb = ranks(exact.f);
    double d2 = 0;
    for (std::size_t v = 0; v < n; ++v)
      d2 += (ra[v] - rb[v]) * (ra[v] - rb[v]);
    const double spearman = 1 - 6 * d2 / (double(n) * (double(n) * n - 1));
    std::cout << "[ measured ] " << n << " points, " << reps
              << " representatives: mean relative error of f " << error << ", Spearman " << spearman
              << std::endl;
    EXPECT_LT(error, 0.03);
    // The ranks of f decide the supernodes. A coarse graph of a thousand points (the hand)
    // blurs them a little, so the rank correlation is checked from 5000 representatives on
    // (the default has 20000).
    if (reps >= 5000) {
      EXPECT_GT(spearman, 0.99);
    }
  }
}

TEST(CentralityMode, SetterChecksAndBothModesSegment) {
  pcl::SupernodeNCutSegmentation<pcl::PointXYZ> seg;
  EXPECT_EQ(seg.getCentralityMode(), CentralityMode::Fast);
  seg.setCentralityMode(static_cast<CentralityMode>(7));
  EXPECT_EQ(seg.getCentralityMode(), CentralityMode::Fast);
  seg.setCentralityMode(CentralityMode::Exact);
  EXPECT_EQ(seg.getCentralityMode(), CentralityMode::Exact);

  // 30000 points: the Fast mode runs on a coarse graph (kFastCentralityRepresentatives); both
  // give the hand's 6 parts, the same labels on one thread and on two.
  ASSERT_TRUE(coarseGraphPays(30000, kFastCentralityRepresentatives));
  const test::LabeledShape hand = test::makeHand(30000, 2);
  seg.setInputCloud(hand.cloud);
  seg.setNumberOfSegments(6);
  std::vector<pcl::PointIndices> exact, fast, fast_two;
  seg.extract(exact);
  seg.setCentralityMode(CentralityMode::Fast);
  seg.setNumberOfThreads(1);
  seg.extract(fast);
  seg.setNumberOfThreads(2);
  seg.setInputCloud(hand.cloud); // invalidates: recomputed on two threads
  seg.extract(fast_two);
  EXPECT_EQ(exact.size(), 6u);
  EXPECT_EQ(fast.size(), 6u);
  ASSERT_EQ(fast.size(), fast_two.size());
  for (std::size_t s = 0; s < fast.size(); ++s)
    EXPECT_EQ(fast[s].indices, fast_two[s].indices);
}

TEST(CentralityProgress, ReportsFromTheCallingThreadUpToOne) {
  const CsrGraph g = knnGraph(test::randomPoints(2000, 6));
  const std::thread::id caller = std::this_thread::get_id();
  std::vector<double> seen;
  bool same_thread = true;
  const Centrality c = computeCentrality(g, 0, 2, nullptr, [&](double fraction) {
    same_thread = same_thread && std::this_thread::get_id() == caller;
    seen.push_back(fraction);
  });
  ASSERT_FALSE(seen.empty());
  EXPECT_TRUE(same_thread);
  EXPECT_TRUE(std::is_sorted(seen.begin(), seen.end()));
  EXPECT_GT(seen.front(), 0.0);
  EXPECT_EQ(seen.back(), 1.0);
  EXPECT_EQ(c.f, computeCentrality(g, 0, 1).f);
}
