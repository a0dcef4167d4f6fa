/*
 * Sensor noise, detected and projected away (core/graph/denoise.h,
 * SupernodeNCutSegmentation::setDenoise).
 */
#include "core/centrality/starts.h"
#include "core/graph/csr_graph.h"
#include "core/graph/denoise.h"
#include "core/graph/knn.h"
#include "core/pipeline/analysis_stages.h"
#include "core/pipeline/pipeline.h"
#include <pcl_ncut_seg/supernode_ncut_segmentation.h>

#include "support/knn_graph.h"
#include <shapes/shapes.h>

#include <gtest/gtest.h>

#include <cmath>
#include <iostream>
#include <random>

using namespace pcl_ncut_seg;

namespace {

constexpr double kPi = 3.14159265358979323846;

/// n points of the unit sphere on a Fibonacci lattice (spacing about sqrt(4 pi / n)), moved by
/// Gaussian noise of sigma per coordinate.
std::vector<float> sphere(std::size_t n, double sigma, std::uint64_t seed = 1) {
  std::mt19937_64 rng(seed);
  std::normal_distribution<double> noise(0.0, sigma);
  std::vector<float> xyz;
  for (const double c : test::fibonacciSphere(n))
    xyz.push_back(static_cast<float>(c + (sigma > 0 ? noise(rng) : 0.0)));
  return xyz;
}

double rmsOffSphere(const std::vector<float>& xyz) {
  double sum = 0.0;
  for (std::size_t i = 0; i < xyz.size(); i += 3) {
    const double r = std::sqrt(double(xyz[i]) * xyz[i] + double(xyz[i + 1]) * xyz[i + 1] +
                               double(xyz[i + 2]) * xyz[i + 2]);
    sum += (r - 1.0) * (r - 1.0);
  }
  return std::sqrt(sum / (xyz.size() / 3));
}

const std::size_t kN = 4000;
const double kSpacing = std::sqrt(4.0 * kPi / kN);

} // namespace

TEST(Denoise, ACleanSphereIsCurvedNotNoisy) {
  const std::vector<float> xyz = sphere(kN, 0.0);
  const double growth = residualGrowth(test::kdTreeKnnGraph(xyz, 10), xyz.data(), 2);
  // Curvature: the scatter grows with the squared radius of the neighbourhood.
  EXPECT_GT(growth, 3.0);
  EXPECT_FALSE(isNoisy(growth, 2.0));
}

TEST(Denoise, NoiseIsDetectedAndProjectedTowardsTheSurface) {
  for (double sigma : {0.25, 0.5, 1.0}) {
    SCOPED_TRACE(sigma);
    const std::vector<float> xyz = sphere(kN, sigma * kSpacing);
    const CsrGraph graph = test::kdTreeKnnGraph(xyz, 10);
    const double growth = residualGrowth(graph, xyz.data(), 2);
    EXPECT_LT(growth, 2.0);
    EXPECT_TRUE(isNoisy(growth, 2.0));
    const std::vector<float> projected = projectOntoLocalPlanes(graph, xyz.data(), 2);
    ASSERT_EQ(projected.size(), xyz.size());
    std::cout << "sigma " << sigma << " spacings: off the sphere " << rmsOffSphere(xyz)
              << " before, " << rmsOffSphere(projected) << " after\n";
    EXPECT_LT(rmsOffSphere(projected), 0.7 * rmsOffSphere(xyz));
  }
}

TEST(Denoise, AnExactlyFlatGridHasNoScatterAndStays) {
  std::vector<float> xyz;
  for (int i = 0; i < 50; ++i)
    for (int j = 0; j < 50; ++j)
      xyz.insert(xyz.end(), {0.1f * i, 0.1f * j, 0.5f});
  const CsrGraph graph = test::kdTreeKnnGraph(xyz, 10);
  const double growth = residualGrowth(graph, xyz.data(), 2);
  EXPECT_EQ(growth, 0.0);
  EXPECT_FALSE(isNoisy(growth, 2.0));
  const std::vector<float> projected = projectOntoLocalPlanes(graph, xyz.data(), 2);
  for (std::size_t i = 0; i < xyz.size(); ++i)
    EXPECT_NEAR(projected[i], xyz[i], 1e-5f);
}

TEST(Denoise, TheResidualTestsFitsProjectAsTheProjectionsOwn) {
  // A noisy sphere and an exactly flat grid (whose 2-rings have no scatter), with a few
  // collinear points whose rings have no plane.
  std::vector<float> grid;
  for (int i = 0; i < 30; ++i)
    for (int j = 0; j < 30; ++j)
      grid.insert(grid.end(), {0.1f * i, 0.1f * j, 0.5f});
  for (int i = 0; i < 12; ++i)
    grid.insert(grid.end(), {10.0f + 0.1f * i, 0.0f, 0.0f});
  for (const auto& xyz : {sphere(kN, 0.5 * kSpacing), grid}) {
    const CsrGraph graph = test::kdTreeKnnGraph(xyz, 10);
    for (unsigned threads : {1u, 2u}) {
      RingFits fits;
      EXPECT_EQ(residualGrowth(graph, xyz.data(), threads, &fits),
                residualGrowth(graph, xyz.data(), threads));
      EXPECT_EQ(projectOntoLocalPlanes(graph, xyz.data(), threads, &fits),
                projectOntoLocalPlanes(graph, xyz.data(), threads));
    }
  }
}

TEST(Denoise, TheSameForAnyNumberOfThreads) {
  const std::vector<float> xyz = sphere(kN, 0.5 * kSpacing);
  const CsrGraph graph = test::kdTreeKnnGraph(xyz, 10);
  EXPECT_EQ(residualGrowth(graph, xyz.data(), 1), residualGrowth(graph, xyz.data(), 2));
  EXPECT_EQ(projectOntoLocalPlanes(graph, xyz.data(), 1),
            projectOntoLocalPlanes(graph, xyz.data(), 2));
  std::vector<float> values(kN);
  for (std::size_t i = 0; i < kN; ++i)
    values[i] = xyz[3 * i] + 0.001f * static_cast<float>(i % 7);
  EXPECT_EQ(neighbourhoodMean(graph, values, 1), neighbourhoodMean(graph, values, 2));
}

TEST(Denoise, TheNeighbourhoodMeanIsOverTheVertexAndItsNeighbours) {
  // A path 0 - 1 - 2 - 3 with one isolated vertex 4.
  CsrGraph graph;
  graph.offsets = {0, 1, 3, 5, 6, 6};
  graph.targets = {1, 0, 2, 1, 3, 2};
  graph.lengths.assign(graph.targets.size(), 1.0f);
  const std::vector<float> mean = neighbourhoodMean(graph, {4.0f, 1.0f, 7.0f, 3.0f, 9.0f}, 2);
  ASSERT_EQ(mean.size(), 5u);
  EXPECT_FLOAT_EQ(mean[0], 2.5f);         // (4 + 1) / 2
  EXPECT_FLOAT_EQ(mean[1], 4.0f);         // (1 + 4 + 7) / 3
  EXPECT_FLOAT_EQ(mean[2], 11.0f / 3.0f); // (7 + 1 + 3) / 3
  EXPECT_FLOAT_EQ(mean[3], 5.0f);         // (3 + 7) / 2
  EXPECT_FLOAT_EQ(mean[4], 9.0f);         // alone: itself
}

namespace {
/// The analysis' centrality (start 0) and the graph stage's f before any mean, for the same
/// points, parameters and kNN graph.
struct CentralityPair {
  std::vector<float> analysed, raw, mean_of_raw;
  bool projected = false;
};

CentralityPair centralityBeforeAndAfter(const std::vector<float>& xyz, const Parameters& params,
                                        std::vector<std::uint8_t> rim = {}) {
  const std::size_t n = xyz.size() / 3, k = static_cast<std::size_t>(params.graph.k);
  std::vector<std::uint32_t> knn(n * k);
  kNearestNeighbours(xyz.data(), n, k, 1, knn.data());
  CentralityPair out;
  PhaseTimes times;
  PointSet points;
  points.xyz = xyz;
  points.knn = knn;
  points.k = k;
  points.rim = std::move(rim);
  out.analysed = analyze(points, params, times).starts.at(0).centrality.f;
  std::vector<float> moved = xyz;
  NoiseTest noise;
  const CsrGraph graph = graphStage(moved, knn.data(), k, params.graph, true, 1, &noise);
  out.projected = noise.projected;
  std::vector<std::uint32_t> component;
  connectedComponents(graph, component);
  const std::vector<std::uint32_t> rank = centralRanks(moved.data(), n, component); // as analyze()
  out.raw = centralityStage(graph, params, rank.data(), times, {}).front().f;
  out.mean_of_raw = neighbourhoodMean(graph, out.raw, 1);
  return out;
}
} // namespace

TEST(Denoise, OnANoisyWholeSurfaceTheCentralityIsTakenThroughTheMeanOnce) {
  Parameters params;
  params.centrality.starts = 1;
  params.graph.max_points.reset();
  const std::vector<float> noisy = sphere(kN, 0.5 * kSpacing);
  const CentralityPair a = centralityBeforeAndAfter(noisy, params);
  ASSERT_TRUE(a.projected);
  EXPECT_EQ(a.analysed, a.mean_of_raw);
  EXPECT_NE(a.analysed, a.raw);

  // The same noisy cloud as an open view (it has a rim) keeps eq. (1)'s f: a depth sensor's
  // noise runs along its rays, and the projection takes it out.
  std::vector<std::uint8_t> rim(kN, 0);
  rim[0] = 1;
  EXPECT_EQ(centralityBeforeAndAfter(noisy, params, rim).analysed, a.raw);

  // A clean, evenly spread cloud keeps eq. (1)'s f as it is.
  const CentralityPair b = centralityBeforeAndAfter(sphere(kN, 0.0), params);
  ASSERT_FALSE(b.projected);
  EXPECT_EQ(b.analysed, b.raw);
}

TEST(Denoise, SamplingIrregularityTellsPointsDrawnAtRandomFromEvenOnes) {
  // Points drawn at random: about 0.45, whatever the density and its gradient.
  for (double ratio : {1.0, 10.0}) {
    SCOPED_TRACE(ratio);
    test::SamplingOptions options;
    options.density_ratio = ratio;
    const std::vector<float> random = test::xyzOf(*test::makeHand(4000, 7, options).cloud);
    const double v = samplingIrregularity(test::kdTreeKnnGraph(random, 10));
    EXPECT_GT(v, 0.38);
    EXPECT_LT(v, 0.52);
  }
  // Spread evenly (a Fibonacci lattice), with or without noise along the normal and across.
  EXPECT_LT(samplingIrregularity(test::kdTreeKnnGraph(sphere(kN, 0.0), 10)), 0.15);
  EXPECT_LT(samplingIrregularity(test::kdTreeKnnGraph(sphere(kN, 0.05 * kSpacing), 10)), 0.2);
  // Too few vertices with an edge to measure.
  EXPECT_EQ(samplingIrregularity(CsrGraph{}), 0.0);
}

TEST(Denoise, OnAWholeSurfaceDrawnAtRandomTheCentralityIsTakenThroughTheMeanOnce) {
  Parameters params;
  params.centrality.starts = 1;
  params.graph.max_points.reset();
  ASSERT_EQ(params.graph.irregular_sampling, 0.3); // the default
  const std::vector<float> random = test::xyzOf(*test::makeHand(4000, 7).cloud);
  const CentralityPair a = centralityBeforeAndAfter(random, params);
  ASSERT_FALSE(a.projected); // clean: not projected, but averaged
  EXPECT_EQ(a.analysed, a.mean_of_raw);
  EXPECT_NE(a.analysed, a.raw);
  // With the rule off, eq. (1)'s f as it is.
  params.graph.irregular_sampling.reset();
  EXPECT_EQ(centralityBeforeAndAfter(random, params).analysed, a.raw);
  // With a bound above the cloud's irregularity, too.
  params.graph.irregular_sampling = 0.6;
  EXPECT_EQ(centralityBeforeAndAfter(random, params).analysed, a.raw);
}

TEST(Denoise, CleanSurfacesGiveTheSameSegmentsWithAndWithout) {
  using Segmenter = pcl::SupernodeNCutSegmentation<pcl::PointXYZ>;
  const test::LabeledShape hand = test::makeHand(4000, 7);
  std::vector<pcl::PointIndices> with, without;
  Segmenter seg;
  EXPECT_EQ(seg.getDenoise(), 2.0); // the default
  seg.setInputCloud(hand.cloud);
  seg.extract(with);
  seg.setDenoise(std::nullopt);
  EXPECT_EQ(seg.getDenoise(), std::nullopt);
  seg.extract(without);
  ASSERT_EQ(with.size(), without.size());
  for (std::size_t s = 0; s < with.size(); ++s)
    EXPECT_EQ(with[s].indices, without[s].indices);
}

TEST(Denoise, TheSegmenterReportsItsNoiseTest) {
  using Segmenter = pcl::SupernodeNCutSegmentation<pcl::PointXYZ>;
  const test::LabeledShape hand = test::makeHand(4000, 7);
  Segmenter seg;
  EXPECT_EQ(seg.getNoiseTest().residual_growth, 0.0); // nothing analysed yet
  std::vector<pcl::PointIndices> segments;
  seg.setInputCloud(hand.cloud);
  seg.extract(segments);
  EXPECT_GT(seg.getNoiseTest().residual_growth, 2.0);
  EXPECT_FALSE(seg.getNoiseTest().projected);

  // The same hand with noise of half a point spacing per coordinate.
  pcl::PointCloud<pcl::PointXYZ>::Ptr noisy(new pcl::PointCloud<pcl::PointXYZ>(*hand.cloud));
  std::mt19937_64 rng(3);
  std::normal_distribution<float> noise(0.0f,
                                        0.5f * static_cast<float>(test::meanPointSpacing(*noisy)));
  for (auto& p : noisy->points) {
    p.x += noise(rng);
    p.y += noise(rng);
    p.z += noise(rng);
  }
  seg.setInputCloud(noisy);
  seg.extract(segments);
  EXPECT_LT(seg.getNoiseTest().residual_growth, 2.0);
  EXPECT_TRUE(seg.getNoiseTest().projected);
  EXPECT_FALSE(segments.empty());

  seg.setDenoise(std::nullopt); // off: not measured
  seg.extract(segments);
  EXPECT_EQ(seg.getNoiseTest().residual_growth, 0.0);
  EXPECT_FALSE(seg.getNoiseTest().projected);

  // On by default (0.3): the hand's points are drawn at random.
  EXPECT_GT(seg.getNoiseTest().sampling_irregularity, 0.3);
  EXPECT_TRUE(seg.getNoiseTest().irregular);
  seg.setIrregularSampling(0.6); // measured, but below this bound
  seg.extract(segments);
  EXPECT_GT(seg.getNoiseTest().sampling_irregularity, 0.3);
  EXPECT_FALSE(seg.getNoiseTest().irregular);
  seg.setIrregularSampling(std::nullopt); // off: not measured
  seg.extract(segments);
  EXPECT_EQ(seg.getNoiseTest().sampling_irregularity, 0.0);
  EXPECT_FALSE(seg.getNoiseTest().irregular);
}

TEST(Denoise, SetterRejectsBadValues) {
  pcl::SupernodeNCutSegmentation<pcl::PointXYZ> seg;
  seg.setDenoise(1.5);
  for (double bad : {1.0, 0.5, 0.0, -2.0, std::nan("")}) { // 0 is no off
    seg.setDenoise(bad);
    EXPECT_EQ(seg.getDenoise(), 1.5);
  }
  EXPECT_EQ(seg.getIrregularSampling(), 0.3); // the default
  seg.setIrregularSampling(0.25);
  for (double bad : {0.0, -0.1, std::nan("")}) {
    seg.setIrregularSampling(bad);
    EXPECT_EQ(seg.getIrregularSampling(), 0.25);
  }
  seg.setDenoise(std::nullopt);
  seg.setIrregularSampling(std::nullopt);
  EXPECT_EQ(seg.getDenoise(), std::nullopt);
  EXPECT_EQ(seg.getIrregularSampling(), std::nullopt);
}
