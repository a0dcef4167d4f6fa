/*
 * The evaluator's sampling conditions (eval/eval_sampling.h) and its spread report
 * (eval/eval_spread.h): noise in units of the mean spacing, the density gradient's ratio as
 * measured on the samples, each face labelled by its nearest sample, the permutation and its
 * mapping back, and the spread of a tiny report made by hand.
 */
#include "eval_sampling.h"
#include "eval_spread.h"
#include "psb_metrics.h"
#include <surfaces/mesh_sampling.h>

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <numeric>
#include <random>
#include <vector>

namespace {

using namespace pcl_ncut_seg;
using namespace pcl_ncut_seg::eval;

/** A flat rectangle in z = 0, w by h, as two triangles (one original face each). */
TriangleMesh rectangle(float w, float h) {
  TriangleMesh m;
  m.vertices = {0, 0, 0, w, 0, 0, w, h, 0, 0, h, 0};
  m.faces = {0, 1, 2, 0, 2, 3};
  m.original_face = {0, 1};
  m.num_original_faces = 2;
  return m;
}

/** The unit cube as 12 triangles, two per side: original faces 0-5. */
TriangleMesh cube() {
  TriangleMesh m;
  m.vertices = {0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0, 0, 0, 1, 1, 0, 1, 1, 1, 1, 0, 1, 1};
  const std::uint32_t quads[6][4] = {{0, 3, 2, 1}, {4, 5, 6, 7}, {0, 1, 5, 4},
                                     {3, 7, 6, 2}, {0, 4, 7, 3}, {1, 2, 6, 5}};
  for (std::uint32_t f = 0; f < 6; ++f) {
    const auto* q = quads[f];
    m.faces.insert(m.faces.end(), {q[0], q[1], q[2], q[0], q[2], q[3]});
    m.original_face.insert(m.original_face.end(), {f, f});
  }
  m.num_original_faces = 6;
  return m;
}

double stddev(const std::vector<double>& v) {
  const double mean = std::accumulate(v.begin(), v.end(), 0.0) / v.size();
  double s = 0;
  for (double x : v)
    s += (x - mean) * (x - mean);
  return std::sqrt(s / v.size());
}

// ------------------------------------------------------------------------------------ noise

TEST(EvalSampling, MeanSpacingIsSqrtOfAreaPerPoint) {
  EXPECT_DOUBLE_EQ(meanSpacing(1.0, 100), 0.1);
  EXPECT_DOUBLE_EQ(meanSpacing(8.0, 2), 2.0);
  EXPECT_EQ(meanSpacing(1.0, 0), 0.0);
}

TEST(EvalSampling, NoiseHasTheGivenSigmaOnEveryCoordinate) {
  std::vector<float> xyz(3 * 100000, 0.0f);
  addNoise(xyz, 0.25, 7);
  for (int d = 0; d < 3; ++d) {
    std::vector<double> c;
    for (std::size_t i = d; i < xyz.size(); i += 3)
      c.push_back(xyz[i]);
    EXPECT_NEAR(stddev(c), 0.25, 0.25 * 0.015) << "axis " << d;
    EXPECT_NEAR(std::accumulate(c.begin(), c.end(), 0.0) / c.size(), 0.0, 0.005);
  }
}

TEST(EvalSampling, CloudNoiseIsInMeanSpacings) {
  // A flat 4 x 1 rectangle: the samples' z is the noise alone; spacing sqrt(4 / 10000) = 0.02.
  SamplingOptions o;
  o.samples = 10000;
  o.noise = 1.5;
  const TriangleMesh mesh = rectangle(4, 1);
  const SampledCloud c = makeCloud(mesh, faceCentroids(mesh), o, 3, 0);
  EXPECT_DOUBLE_EQ(c.spacing, 0.02);
  std::vector<double> z;
  for (std::size_t i = 2; i < c.xyz.size(); i += 3)
    z.push_back(c.xyz[i]);
  ASSERT_EQ(z.size(), 10000u);
  EXPECT_NEAR(stddev(z), 1.5 * 0.02, 1.5 * 0.02 * 0.04);
}

// ---------------------------------------------------------------------------------- density

TEST(EvalSampling, LongestAxisOfTheBoundingBox) {
  EXPECT_EQ(longestAxis({0, 0, 0, 1, 5, 2}), 1);
  EXPECT_EQ(longestAxis({0, 0, 0, 1, 2, -3}), 2);
  EXPECT_EQ(longestAxis({-4, 0, 0, 1, 2, 3}), 0);
}

TEST(EvalSampling, RatioOneIsTheUniformSampling) {
  const TriangleMesh mesh = cube();
  EXPECT_EQ(sampleWithGradient(mesh, 500, 1.0, 11), sampleSurface(mesh, 500, 11));
}

/** Samples per unit length in the slab [a, b) of a coordinate. */
double slabDensity(const std::vector<float>& xyz, int axis, double a, double b) {
  std::size_t count = 0;
  for (std::size_t i = axis; i < xyz.size(); i += 3)
    count += xyz[i] >= a && xyz[i] < b;
  return count / (b - a);
}

TEST(EvalSampling, DensityGradientHasTheRatioAlongTheLongestAxis) {
  // A 1 x 10 strip: the longest axis is y. Density R - (R - 1) t: the 5% slab at the low end
  // holds R - (R - 1) 0.025 per unit length, the one at the high end R - (R - 1) 0.975.
  const double r = 4;
  const TriangleMesh mesh = rectangle(1, 10);
  const std::vector<float> xyz = sampleWithGradient(mesh, 400000, r, 5);
  ASSERT_EQ(xyz.size(), 3u * 400000);
  const double expected = gradientDensity(r, 0.025) / gradientDensity(r, 0.975);
  EXPECT_NEAR(slabDensity(xyz, 1, 0, 0.5) / slabDensity(xyz, 1, 9.5, 10), expected,
              0.04 * expected);
  // Linear in between: the middle slab is at (R + 1) / 2 relative to the high end.
  EXPECT_NEAR(slabDensity(xyz, 1, 4.75, 5.25) / slabDensity(xyz, 1, 9.5, 10),
              gradientDensity(r, 0.5) / gradientDensity(r, 0.975), 0.04 * 2.5);
  // Nothing changes across the short axis.
  EXPECT_NEAR(slabDensity(xyz, 0, 0, 0.5) / slabDensity(xyz, 0, 0.5, 1), 1.0, 0.02);
}

// ------------------------------------------------------------------------- nearest labelling

TEST(EvalSampling, NearestPointsMatchBruteForce) {
  std::mt19937 rng(3);
  std::uniform_real_distribution<float> u(-1, 1), wide(-2, 2);
  std::vector<float> points(3 * 3000), queries(3 * 700);
  for (float& v : points)
    v = u(rng);
  for (std::size_t i = 0; i < 9; ++i) // a duplicate: the tie goes to the lower index
    points[3 * 2999 + i % 3] = points[3 * 17 + i % 3];
  for (float& v : queries)
    v = wide(rng); // some outside the points' box
  const std::vector<std::uint32_t> got = nearestPoints(points, queries);
  ASSERT_EQ(got.size(), 700u);
  for (std::size_t q = 0; q < 700; ++q) {
    std::uint32_t best = 0;
    double best_d = 1e300;
    for (std::uint32_t p = 0; p < 3000; ++p) {
      double d = 0;
      for (int k = 0; k < 3; ++k)
        d += std::pow(double(points[3 * p + k]) - queries[3 * q + k], 2);
      if (d < best_d) {
        best_d = d;
        best = p;
      }
    }
    EXPECT_EQ(got[q], best) << "query " << q;
  }
  EXPECT_EQ(nearestPoints(points, {points[51], points[52], points[53]})[0], 17u);
  EXPECT_THROW(nearestPoints({}, queries), std::invalid_argument);
}

TEST(EvalSampling, FaceLabelsComeFromTheNearestPoint) {
  EXPECT_EQ(faceLabels({5, 6, 7}, {2, 2, 0, 1}), (std::vector<int>{7, 7, 5, 6}));
  EXPECT_EQ(faceLabels({5, 6, 7}, {}), (std::vector<int>{5, 6, 7}));
}

TEST(EvalSampling, EachCubeSideTakesASampleOnItself) {
  // The centre of each side is nearest to a sample on that side (the others are >= 0.5 away).
  SamplingOptions o;
  o.samples = 2000;
  const TriangleMesh mesh = cube();
  const std::vector<float> centroids = faceCentroids(mesh);
  const SampledCloud c = makeCloud(mesh, centroids, o, 1, 0);
  ASSERT_EQ(c.nearest.size(), 6u);
  const int axis[6] = {2, 2, 1, 1, 0, 0};
  for (int f = 0; f < 6; ++f)
    EXPECT_EQ(c.xyz[3 * c.nearest[f] + axis[f]], centroids[3 * f + axis[f]]) << "side " << f;
}

TEST(EvalSampling, FaceNormalsPointOutwardWhicheverWayTheMeshIsWound) {
  // Each side's normal points away from the cube's centre, for the mesh as written and for
  // the same mesh with every triangle wound the other way (what LCCP and CPC are given).
  TriangleMesh mesh = cube();
  for (int wound = 0; wound < 2; ++wound) {
    const std::vector<float> centroids = faceCentroids(mesh);
    const std::vector<float> normals = outwardFaceNormals(mesh);
    ASSERT_EQ(normals.size(), centroids.size());
    for (std::size_t f = 0; f < 6; ++f) {
      double dot = 0, length = 0;
      for (int d = 0; d < 3; ++d) {
        dot += normals[3 * f + d] * (centroids[3 * f + d] - 0.5);
        length += normals[3 * f + d] * normals[3 * f + d];
      }
      EXPECT_NEAR(dot, 0.5, 1e-6) << "side " << f << ", winding " << wound;
      EXPECT_NEAR(length, 1.0, 1e-6);
    }
    for (std::size_t t = 0; t < mesh.numTriangles(); ++t)
      std::swap(mesh.faces[3 * t + 1], mesh.faces[3 * t + 2]);
  }
}

TEST(EvalSampling, EachSampleTakesItsNearestFacesNormal) {
  const TriangleMesh mesh = cube();
  const std::vector<float> centroids = faceCentroids(mesh);
  const std::vector<float> faces = outwardFaceNormals(mesh);
  // Points just off the centres of the sides: each takes its own side's normal.
  std::vector<float> points;
  for (std::size_t f = 0; f < 6; ++f)
    for (int d = 0; d < 3; ++d)
      points.push_back(centroids[3 * f + d] + 0.01f * faces[3 * f + d]);
  EXPECT_EQ(nearestFaceNormals(points, centroids, faces), faces);
}

// ------------------------------------------------------------------------------ permutation

TEST(EvalSampling, RandomOrderIsASeededPermutation) {
  const std::vector<std::uint32_t> a = randomOrder(1000, 9), b = randomOrder(1000, 9);
  EXPECT_EQ(a, b);
  EXPECT_NE(a, randomOrder(1000, 10));
  std::vector<std::uint32_t> sorted = a, identity(1000);
  std::sort(sorted.begin(), sorted.end());
  std::iota(identity.begin(), identity.end(), 0u);
  EXPECT_EQ(sorted, identity);
  EXPECT_NE(a, identity);
}

TEST(EvalSampling, LabelsOfReorderedPointsMapBack) {
  // Label each point by its x; labels of the reordered points, mapped back, are the original's.
  const std::vector<float> xyz = {0, 0, 0, 1, 0, 0, 2, 0, 0, 3, 0, 0, 4, 0, 0};
  const std::vector<std::uint32_t> order = {3, 0, 4, 1, 2};
  const std::vector<float> moved = reordered(xyz, order);
  std::vector<int> labels;
  for (std::size_t i = 0; i < moved.size(); i += 3)
    labels.push_back(static_cast<int>(moved[i]) * 10);
  EXPECT_EQ(mappedBack(labels, order), (std::vector<int>{0, 10, 20, 30, 40}));
  EXPECT_EQ(mappedBack(labels, {}), labels);
}

TEST(EvalSampling, PermutedDrawsAreTheSamePointsInAnotherOrder) {
  SamplingOptions o;
  o.samples = 3000;
  o.draws = 3;
  o.noise = 0.5;
  o.permute = true;
  const TriangleMesh mesh = cube();
  const std::vector<float> centroids = faceCentroids(mesh);
  const SampledCloud first = makeCloud(mesh, centroids, o, 4, 0);
  const SampledCloud second = makeCloud(mesh, centroids, o, 4, 1);
  const SampledCloud third = makeCloud(mesh, centroids, o, 4, 2);
  EXPECT_TRUE(first.order.empty());
  ASSERT_EQ(second.order.size(), 3000u);
  EXPECT_NE(second.order, third.order);
  EXPECT_EQ(reordered(first.xyz, second.order), second.xyz);
  EXPECT_EQ(second.nearest, first.nearest);
}

TEST(EvalSampling, JitteredDrawsAreTheSamePointsMovedByTheGivenSigma) {
  SamplingOptions o;
  o.samples = 3000;
  o.draws = 3;
  o.jitter = 0.01;
  const TriangleMesh mesh = cube(); // area 6: spacing sqrt(6 / 3000)
  const std::vector<float> centroids = faceCentroids(mesh);
  const SampledCloud first = makeCloud(mesh, centroids, o, 4, 0);
  const SampledCloud second = makeCloud(mesh, centroids, o, 4, 1);
  const SampledCloud third = makeCloud(mesh, centroids, o, 4, 2);
  EXPECT_TRUE(second.order.empty());
  EXPECT_EQ(second.nearest, first.nearest);
  EXPECT_NE(second.xyz, third.xyz);
  std::vector<double> moved;
  for (std::size_t i = 0; i < first.xyz.size(); ++i)
    moved.push_back(second.xyz[i] - first.xyz[i]);
  EXPECT_NEAR(stddev(moved), 0.01 * first.spacing, 0.01 * first.spacing * 0.05);
  SamplingOptions plain = o;
  plain.jitter = 0;
  plain.draws = 1;
  EXPECT_EQ(first.xyz, makeCloud(mesh, centroids, plain, 4, 0).xyz); // draw 1 as sampled
}

TEST(EvalSampling, DrawsAreSeededByModelAndDraw) {
  SamplingOptions o;
  o.samples = 500;
  const TriangleMesh mesh = cube();
  const std::vector<float> centroids = faceCentroids(mesh);
  EXPECT_EQ(makeCloud(mesh, centroids, o, 2, 1).xyz, makeCloud(mesh, centroids, o, 2, 1).xyz);
  EXPECT_NE(makeCloud(mesh, centroids, o, 2, 1).xyz, makeCloud(mesh, centroids, o, 2, 0).xyz);
  EXPECT_NE(makeCloud(mesh, centroids, o, 3, 1).xyz, makeCloud(mesh, centroids, o, 2, 1).xyz);
  o.samples = 0; // no condition: the centroids themselves
  const SampledCloud plain = makeCloud(mesh, centroids, o, 2, 0);
  EXPECT_EQ(plain.xyz, centroids);
  EXPECT_TRUE(plain.nearest.empty());
}

TEST(EvalSampling, HumanLabelsCarriedThroughSamplesComeBack) {
  const std::filesystem::path psb = std::filesystem::path(PCL_NCUT_SEG_SHARED_DATA) / "psb-dev";
  if (!std::filesystem::exists(psb / "off" / "1.off"))
    GTEST_SKIP() << "no " << psb.string() << " (the shared benchmark data is absent)";
  TriangleMesh mesh;
  ASSERT_TRUE(readOff((psb / "off" / "1.off").string(), mesh));
  std::vector<int> human;
  ASSERT_TRUE(readSeg((psb / "seg" / "1" / "1_0.seg").string(), human));
  // Each sample carries the label of the face it was drawn on; each face takes its nearest's.
  std::vector<std::uint32_t> face_of;
  const std::vector<float> xyz = sampleSurface(mesh, 20000, drawSeed(1, 0, 0), &face_of);
  std::vector<int> sample_labels;
  for (const std::uint32_t f : face_of)
    sample_labels.push_back(human[f]);
  const std::vector<int> back = faceLabels(sample_labels, nearestPoints(xyz, faceCentroids(mesh)));
  EXPECT_LT(compareSegmentations(back, human, {}).rand_index_error, 0.01);
}

// ----------------------------------------------------------------------------------- spread

Row fakeRow(const std::string& method, int id, int draw, double ri, double hamming,
            double segments) {
  Row r;
  r.method = method;
  r.mode = "auto";
  r.id = id;
  r.category = psbCategory(id);
  r.draw = draw;
  r.segments = segments;
  r.scores.rand_index_error = ri;
  r.scores.hamming = hamming;
  return r;
}

TEST(EvalSpread, RangesAndCountChangesOfATinyReport) {
  Report report;
  report.modes = {"auto"};
  report.ids = {1, 21};
  report.draws = 3;
  for (const Row& r : {fakeRow("ours", 1, 0, 0.10, 0.2, 5), fakeRow("ours", 1, 1, 0.30, 0.1, 5),
                       fakeRow("ours", 1, 2, 0.15, 0.4, 5), fakeRow("ours", 21, 0, 0.5, 0.5, 2),
                       fakeRow("ours", 21, 1, 0.5, 0.5, 4), fakeRow("ours", 21, 2, 0.4, 0.5, 3)})
    report.rows.push_back(r);
  report.rows.push_back(fakeRow("human", 1, 0, 0.1, 0.1, 3)); // once per model: no spread
  report.between_draws[{"ours", "auto", 21}] = 0.25;
  const std::vector<Spread> s = spreads(report);
  ASSERT_EQ(s.size(), 2u);
  EXPECT_EQ(s[0].id, 1);
  EXPECT_EQ(s[0].draws, 3);
  EXPECT_NEAR(s[0].range[0], 0.20, 1e-12);
  EXPECT_NEAR(s[0].range[1], 0.30, 1e-12);
  EXPECT_FALSE(s[0].countChanges());
  EXPECT_EQ(s[0].between, 0.0);
  EXPECT_NEAR(s[1].range[0], 0.10, 1e-12);
  EXPECT_EQ(s[1].range[1], 0.0);
  EXPECT_TRUE(s[1].countChanges());
  EXPECT_EQ(s[1].segments_min, 2);
  EXPECT_EQ(s[1].segments_max, 4);
  EXPECT_EQ(s[1].between, 0.25);
  // Overall: mean range of 1 - RI 0.150, Hamming 0.150; the count changes on 1 of 2 models;
  // the segment count spans 1.00 on average; 1 - RI between draws 0.125.
  const std::string md = spreadMarkdown(report);
  EXPECT_NE(
      md.find("| ours | 0.150 | 0.150 | 0.000 | 0.000 | 0.000 | 0.000 | 50% | 1.00 | 0.125 |"),
      std::string::npos)
      << md;
  EXPECT_NE(md.find("| Human | 0.200 | 0% |"), std::string::npos) << md;
  EXPECT_NE(md.find("| Cup | 0.100 | 100% |"), std::string::npos) << md;
  const std::string csv = spreadCsv(report);
  EXPECT_NE(csv.find("\"ours\",auto,21,Cup,3,2,4,0.100000,0.000000"), std::string::npos) << csv;
}

} // namespace
