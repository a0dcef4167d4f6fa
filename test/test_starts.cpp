/*
 * Several starts of eq. (1)'s farthest-point sampling and the medoid of their segmentations
 * (core/centrality/starts.h, SupernodeNCutSegmentation::setStarts).
 */
#include "core/centrality/centrality.h"
#include "core/centrality/starts.h"
#include "core/pipeline/pipeline.h"
#include <pcl_ncut_seg/supernode_ncut_segmentation.h>

#include "support/knn_graph.h"
#include <shapes/shapes.h>

#include <gtest/gtest.h>

#include <algorithm>
#include <vector>

using namespace pcl_ncut_seg;

namespace {

using Labels = std::vector<std::uint32_t>;

/// The kNN graph of a generated hand of n points.
CsrGraph handGraph(std::size_t n, std::uint64_t seed, std::size_t k) {
  const test::LabeledShape hand = test::makeHand(n, seed);
  std::vector<float> xyz;
  for (const auto& p : *hand.cloud)
    xyz.insert(xyz.end(), {p.x, p.y, p.z});
  return test::kdTreeKnnGraph(xyz, k);
}

/// Per input point, its segment in segments.
Labels labelsOf(const std::vector<pcl::PointIndices>& segments, std::size_t n) {
  Labels label(n, kNone);
  for (std::size_t s = 0; s < segments.size(); ++s)
    for (int i : segments[s].indices)
      label[i] = static_cast<std::uint32_t>(s);
  return label;
}

/// Per input point, its segment when only the given start of the kept analysis is cut.
Labels cutOneStart(const pcl::SupernodeNCutSegmentation<pcl::PointXYZ>& seg, std::size_t start,
                   std::size_t n) {
  Analyses one;
  one.starts.push_back(seg.getAnalyses()->starts.at(start));
  PhaseTimes times;
  const CutResult r = cut(one, seg.getParameters(), times);
  Labels label(n, kNone);
  for (std::size_t v = 0; v < r.point_segment.size(); ++v)
    label[seg.getAnalysedIndices()[v]] = r.point_segment[v];
  return label;
}

} // namespace

TEST(Starts, PairDisagreementsCountThePairsSplitDifferently) {
  // Pairs (0,2) and (1,2) are apart in a and together in b; (2,3) the other way round.
  EXPECT_EQ(pairDisagreements({0, 0, 1, 1}, {0, 0, 0, 1}), 3u);
  EXPECT_EQ(pairDisagreements({0, 0, 1, 1}, {7, 7, 3, 3}), 0u); // the same partition
  EXPECT_EQ(pairDisagreements({0, 0, 0, 0}, {0, 1, 2, 3}), 6u); // every pair
  EXPECT_EQ(pairDisagreements({}, {}), 0u);
  // Many labels (the sorting path) and few (the table of label pairs) count alike.
  std::vector<std::uint32_t> few_a(5000), few_b(5000), many_a(5000), many_b(5000);
  for (std::uint32_t i = 0; i < 5000; ++i) {
    few_a[i] = (i * 7919u) % 13u;
    few_b[i] = (i * 104729u) % 17u;
    many_a[i] = few_a[i] * 100000u; // the same partitions under labels too large for a table
    many_b[i] = few_b[i] * 100000u + 7u;
  }
  std::uint64_t brute = 0;
  for (std::size_t i = 0; i < 5000; ++i)
    for (std::size_t j = i + 1; j < 5000; ++j)
      brute += (few_a[i] == few_a[j]) != (few_b[i] == few_b[j]);
  EXPECT_EQ(pairDisagreements(few_a, few_b), brute);
  EXPECT_EQ(pairDisagreements(many_a, many_b), brute);
}

TEST(Starts, TheMedoidIsThePartitionClosestToTheOthers) {
  const Labels a = {0, 0, 0, 1, 1, 1, 2, 2, 2};
  Labels b = a, c = a;
  b[2] = 1; // one point moved each way: a is one move from b and c, b two moves from c
  c[6] = 1;
  EXPECT_EQ(medoidPartition({&b, &a, &c}), 1u);
  EXPECT_EQ(medoidPartition({&b, &c, &a}), 2u);
  // Ties go to the smallest index.
  EXPECT_EQ(medoidPartition({&b, &c}), 0u);
  EXPECT_EQ(medoidPartition({&c, &b}), 0u);
  EXPECT_EQ(medoidPartition({&a}), 0u);
  // Weights count a partition as several equal ones: c twice and b once make c the medoid.
  EXPECT_EQ(medoidPartition({&b, &c}, {1, 2}), 1u);
  EXPECT_EQ(medoidPartition({&b, &a, &c}, {3, 1, 1}), 0u);
}

TEST(Starts, EachStartBeginsAtTheNextSampleOfTheFirstChain) {
  const CsrGraph graph = handGraph(2000, 5, 10);
  const std::vector<Centrality> f = computeCentralities(graph, 0, 2, nullptr, {}, 4);
  ASSERT_EQ(f.size(), 4u);
  EXPECT_EQ(f[0].f, computeCentrality(graph, 0, 2).f);
  for (std::size_t start = 1; start < 4; ++start) {
    ASSERT_EQ(f[start].samples.size(), f[0].samples.size());
    EXPECT_EQ(f[start].samples[0], f[0].samples[start]);
    // f depends on the set of samples only; the chains from some starts come back to the
    // same set (here starts 1 and 3), others do not (start 2).
    std::vector<std::uint32_t> a = f[0].samples, b = f[start].samples;
    std::sort(a.begin(), a.end());
    std::sort(b.begin(), b.end());
    EXPECT_EQ(a == b, f[start].f == f[0].f);
    EXPECT_EQ(a == b, start != 2);
  }
}

TEST(Starts, EachStartsCentralityIsTheMeanDistanceToItsOwnSamples) {
  // Only the samples in which a start differs from start 0 are searched again: check the
  // result against eq. (1) over each start's samples with Boost's Dijkstra.
  const CsrGraph graph = handGraph(1500, 9, 8);
  const std::vector<Centrality> f = computeCentralities(graph, 0, 2, nullptr, {}, 5);
  for (const Centrality& c : f) {
    ASSERT_EQ(c.num_components, 1u);
    std::vector<double> mean(graph.numVertices(), 0.0);
    for (std::uint32_t s : c.samples) {
      const std::vector<float> d = geodesicDistances(graph, s);
      for (std::size_t v = 0; v < d.size(); ++v)
        mean[v] += d[v] / static_cast<double>(c.samples.size());
    }
    for (std::size_t v = 0; v < mean.size(); ++v)
      ASSERT_NEAR(c.f[v], mean[v], 1e-5 * mean[v]) << "vertex " << v;
  }
}

TEST(Starts, TheResultIsTheMedoidOfTheStartsSegmentations) {
  const test::LabeledShape hand = test::makeHand(4000, 3);
  const std::size_t n = hand.cloud->size();
  pcl::SupernodeNCutSegmentation<pcl::PointXYZ> seg;
  seg.setInputCloud(hand.cloud);
  seg.setNumberOfThreads(2);
  seg.setStarts(5);
  std::vector<pcl::PointIndices> segments;
  seg.extract(segments);
  ASSERT_GT(segments.size(), 1u);
  const Analyses& analyses = *seg.getAnalyses();
  const Analysis& analysis = analyses.starts[0];
  EXPECT_EQ(seg.getAnalysis(), &analysis);
  // An analysis per start with samples of its own, weighted by the starts that have them.
  const std::size_t distinct = analyses.starts.size();
  ASSERT_GT(distinct, 1u);
  ASSERT_EQ(analyses.weights.size(), distinct);
  std::uint32_t total = 0;
  for (std::uint32_t w : analyses.weights)
    total += w;
  EXPECT_EQ(total, 5u);
  // The starts differ in their samples only: they share one kNN graph, not copies of it.
  ASSERT_NE(analysis.graph, nullptr);
  for (std::size_t s = 1; s < distinct; ++s)
    EXPECT_EQ(analyses.starts[s].graph.get(), analysis.graph.get());
  std::vector<Labels> each;
  for (std::size_t s = 0; s < distinct; ++s)
    each.push_back(cutOneStart(seg, s, n));
  std::vector<const Labels*> partitions;
  for (const Labels& l : each)
    partitions.push_back(&l);
  const std::size_t medoid = medoidPartition(partitions, analyses.weights);
  EXPECT_EQ(labelsOf(segments, n), each[medoid]);
  // The intermediate results are the medoid start's.
  const std::vector<float> f = seg.getCentrality();
  const Analysis& shown = analyses.starts[medoid];
  for (std::size_t v = 0; v < shown.centrality.f.size(); ++v)
    ASSERT_EQ(f[seg.getAnalysedIndices()[v]], shown.centrality.f[v]);

  // One start is start 0 alone: the same segments as start 0 of several.
  seg.setStarts(1);
  seg.extract(segments);
  EXPECT_EQ(seg.getAnalyses()->starts.size(), 1u);
  EXPECT_EQ(labelsOf(segments, n), each[0]);
}

TEST(Starts, TheSameForAnyNumberOfThreads) {
  const test::LabeledShape hand = test::makeHand(4000, 8);
  std::vector<Labels> results;
  for (int threads : {1, 2}) {
    pcl::SupernodeNCutSegmentation<pcl::PointXYZ> seg;
    seg.setInputCloud(hand.cloud);
    seg.setNumberOfThreads(threads);
    seg.setStarts(4);
    std::vector<pcl::PointIndices> segments;
    seg.extract(segments);
    results.push_back(labelsOf(segments, hand.cloud->size()));
  }
  EXPECT_EQ(results[0], results[1]);
}

TEST(Starts, AnOpenViewHasOneStart) {
  pcl::SupernodeNCutSegmentation<pcl::PointXYZ> seg;
  seg.setInputCloud(test::discView(4, 0.02f));
  seg.setStarts(5);
  std::vector<pcl::PointIndices> segments;
  seg.extract(segments);
  ASSERT_FALSE(segments.empty());
  EXPECT_FALSE(seg.getAnalysis()->rim.empty());
  EXPECT_EQ(seg.getAnalyses()->starts.size(), 1u);
  EXPECT_EQ(seg.getAnalyses()->weights, std::vector<std::uint32_t>{1u});
}

TEST(Starts, SetterKeepsTheOldValueOnABadOne) {
  pcl::SupernodeNCutSegmentation<pcl::PointXYZ> seg;
  EXPECT_EQ(seg.getStarts(), 5);
  seg.setStarts(0);
  EXPECT_EQ(seg.getStarts(), 5);
  seg.setStarts(17);
  EXPECT_EQ(seg.getStarts(), 5);
  seg.setStarts(1);
  EXPECT_EQ(seg.getStarts(), 1);
  EXPECT_EQ(Parameters::paper().centrality.starts, 1);
}

TEST(Starts, CentralRanksGoByTheDistanceFromEachComponentsCentroid) {
  // Component 0: x = -1, 0, 3 (centroid 2/3); component 1: x = 10, 12 (centroid 11), tied.
  const std::vector<float> xyz = {-1, 0, 0, 10, 0, 0, 0, 0, 0, 3, 0, 0, 12, 0, 0};
  const std::vector<std::uint32_t> component = {0, 1, 0, 0, 1};
  // Distances: 5/3, 1, 2/3, 7/3, 1; ties by index.
  EXPECT_EQ(centralRanks(xyz.data(), 5, component), (std::vector<std::uint32_t>{3, 1, 0, 4, 2}));
  // Without components: from the origin.
  EXPECT_EQ(centralRanks(xyz.data(), 5), (std::vector<std::uint32_t>{1, 3, 0, 2, 4}));
}
