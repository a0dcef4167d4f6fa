/*
 * Concave creases between supernodes (core/cut/concavity.h,
 * SupernodeNCutSegmentation::setConcavityWeight).
 */
#include "core/cut/concavity.h"
#include "core/graph/csr_graph.h"
#include "core/model/model.h" // what getAnalysis() points to
#include <pcl_ncut_seg/supernode_ncut_segmentation.h>

#include "support/knn_graph.h"
#include <shapes/shapes.h>

#include <gtest/gtest.h>

#include <cmath>
#include <iostream>
#include <limits>
#include <map>
#include <optional>
#include <random>

using namespace pcl_ncut_seg;

namespace {

struct Cloud {
  std::vector<float> xyz;
  CsrGraph graph;
};

/// The points of a shape and their symmetric 10-NN graph.
Cloud knnOf(const pcl::PointCloud<pcl::PointXYZ>::Ptr& cloud) {
  Cloud c;
  c.xyz = test::xyzOf(*cloud);
  c.graph = test::kdTreeKnnGraph(c.xyz, 10);
  return c;
}

} // namespace

TEST(Concavity, NormalsOfAClosedSurfacePointOutwards) {
  const test::LabeledShape shape = test::makeDumbbell(3000, 1);
  const Cloud c = knnOf(shape.cloud);
  const std::vector<float> normals = orientedNormals(c.graph, c.xyz.data());
  // On the balls (centres at x = -1.2 and 1.2, radius 0.5), away from the bar, the outward
  // normal is the direction from the centre.
  std::size_t checked = 0, outwards = 0;
  for (std::size_t p = 0; p < shape.cloud->size(); ++p) {
    const double x = c.xyz[3 * p], y = c.xyz[3 * p + 1], z = c.xyz[3 * p + 2];
    const double cx = x < 0 ? -1.2 : 1.2;
    if (std::abs(x) < 1.2)
      continue; // the outer halves of the balls only
    ++checked;
    const double along =
        normals[3 * p] * (x - cx) + normals[3 * p + 1] * y + normals[3 * p + 2] * z;
    outwards += along > 0.4; // |x - c| = 0.5: cos < 0.8 would be a bad fit
  }
  ASSERT_GT(checked, 500u);
  EXPECT_EQ(outwards, checked);
}

TEST(Concavity, NormalsPointOutwardsWhenTheFarthestPointIsAThinFinsTip) {
  // A ball of radius 1 with a thin fin, two triangular sheets 0.004 apart (a sixteenth of the
  // point spacing) reaching to x = 2.2: a fish's fin. At the fin's tip, the point farthest from
  // the centroid, the fitted plane holds both sheets, so its normal is nearly tangent to the
  // direction from the centroid and cannot tell outwards from inwards. The ball's normals must
  // point outwards in every draw of the fin's points.
  const std::vector<double> ball = test::fibonacciSphere(3000);
  for (std::uint64_t seed = 1; seed <= 8; ++seed) {
    std::vector<float> xyz(ball.begin(), ball.end());
    const std::size_t on_ball = xyz.size() / 3;
    std::mt19937_64 rng(seed);
    std::uniform_real_distribution<double> unit(0.0, 1.0);
    for (int i = 0; i < 600; ++i) {
      const double x = 0.95 + 1.25 * unit(rng);
      const double y = (2.0 * unit(rng) - 1.0) * 0.3 * (2.2 - x) / 1.25;
      const double z = i % 2 ? 0.002 : -0.002;
      for (double v : {x, y, z})
        xyz.push_back(static_cast<float>(v));
    }
    const CsrGraph graph = test::kdTreeKnnGraph(xyz, 10);
    const std::vector<float> normals = orientedNormals(graph, xyz.data());
    std::size_t checked = 0, outwards = 0;
    for (std::size_t p = 0; p < on_ball; ++p) {
      if (xyz[3 * p] > 0.5)
        continue; // away from the fin's root
      ++checked;
      const double along = normals[3 * p] * xyz[3 * p] + normals[3 * p + 1] * xyz[3 * p + 1] +
                           normals[3 * p + 2] * xyz[3 * p + 2];
      outwards += along > 0.8;
    }
    ASSERT_GT(checked, 2000u);
    EXPECT_EQ(outwards, checked) << "seed " << seed;
  }
}

TEST(Concavity, NormalsOfOneViewFaceTheSensor) {
  // A bowl seen from above its opening: the inside of the lower half of the unit sphere, as a
  // camera at (0, 0, 3) sees it. The solid's outside there faces the sphere's centre, and the
  // camera. Whole-surface rules get it wrong: the rim point farthest from the points'
  // centroid has a normal pointing back towards it.
  const std::vector<double> sphere = test::fibonacciSphere(4000);
  std::vector<float> xyz;
  for (std::size_t i = 0; i + 2 < sphere.size(); i += 3)
    if (sphere[i + 2] < 0.0)
      for (int d = 0; d < 3; ++d)
        xyz.push_back(static_cast<float>(sphere[i + d]));
  const CsrGraph graph = test::kdTreeKnnGraph(xyz, 10);
  const float camera[3] = {0.0f, 0.0f, 3.0f};
  const std::vector<float> normals = orientedNormals(graph, xyz.data(), 1, camera);
  std::size_t facing = 0;
  const std::size_t n = xyz.size() / 3;
  for (std::size_t p = 0; p < n; ++p) // towards the centre: -p
    facing += -(normals[3 * p] * xyz[3 * p] + normals[3 * p + 1] * xyz[3 * p + 1] +
                normals[3 * p + 2] * xyz[3 * p + 2]) > 0.8;
  ASSERT_GT(n, 1900u);
  EXPECT_EQ(facing, n);
  // Without the sensor the bowl is taken for a whole surface and turned the other way.
  const std::vector<float> whole = orientedNormals(graph, xyz.data(), 1);
  EXPECT_GT(whole[0] * xyz[0] + whole[1] * xyz[1] + whole[2] * xyz[2], 0.0f);
}

TEST(Concavity, NormalsDoNotDependOnTheNumberOfThreads) {
  const test::LabeledShape shape = test::makeQuadruped(6000, 1);
  const Cloud c = knnOf(shape.cloud);
  const std::vector<float> one = orientedNormals(c.graph, c.xyz.data(), 1);
  const std::vector<float> two = orientedNormals(c.graph, c.xyz.data(), 2);
  ASSERT_EQ(one.size(), 3 * shape.cloud->size());
  EXPECT_EQ(one, two); // bit for bit
  std::size_t fitted = 0;
  for (std::size_t p = 0; p < shape.cloud->size(); ++p)
    fitted += one[3 * p] != 0.0f || one[3 * p + 1] != 0.0f || one[3 * p + 2] != 0.0f;
  EXPECT_EQ(fitted, shape.cloud->size()); // a surface: every point has a plane
}

TEST(Concavity, ABarMeetsItsBallsAtAConcaveCrease) {
  const test::LabeledShape shape = test::makeDumbbell(4000, 1);
  const Cloud c = knnOf(shape.cloud);
  const std::vector<float> normals = orientedNormals(c.graph, c.xyz.data());
  // Parts as supernodes: ball 0, bar 1, ball 2; and the balls split at their equator plane
  // x = +-1.2 into halves 3 and 4 (a convex contact on a smooth surface, for reference).
  std::vector<std::uint32_t> label(shape.labels.size());
  for (std::size_t p = 0; p < label.size(); ++p) {
    label[p] = static_cast<std::uint32_t>(shape.labels[p]);
    if (shape.labels[p] != 1 && std::abs(c.xyz[3 * p]) > 1.2)
      label[p] = shape.labels[p] == 0 ? 3u : 4u;
  }
  const Connectivity concave = contactConcavity(c.graph, c.xyz.data(), normals, label);
  ASSERT_TRUE(concave.count({0, 1}) && concave.count({1, 2}));
  ASSERT_TRUE(concave.count({0, 3}) && concave.count({2, 4}));
  std::cout << "contact concavity: ball-bar " << concave.at({0, 1}) << ", " << concave.at({1, 2})
            << "; half-half " << concave.at({0, 3}) << ", " << concave.at({2, 4}) << "\n";
  // The bar's contact with a ball bends inwards several times more than a typical edge bends;
  // the halves of a ball meet where the surface bends outwards only.
  EXPECT_GT(concave.at({0, 1}), 1.5);
  EXPECT_GT(concave.at({1, 2}), 1.5);
  EXPECT_LT(concave.at({0, 3}), 0.25);
  EXPECT_LT(concave.at({2, 4}), 0.25);
}

TEST(ConcavityWeight, ConcaveContactsGetWeakerEdges) {
  const test::LabeledShape shape = test::makeQuadruped(4000, 1);
  pcl::SupernodeNCutSegmentation<pcl::PointXYZ> seg;
  EXPECT_EQ(seg.getConcavityWeight(), 3.0);
  seg.setInputCloud(shape.cloud);
  std::vector<pcl::PointIndices> segments;
  auto memberWeights = [&](std::optional<double> w) {
    seg.setConcavityWeight(w);
    seg.extract(segments);
    std::map<std::pair<std::uint32_t, std::uint32_t>, double> out;
    const std::size_t l = seg.getNumberOfSupernodes(true);
    for (const auto& e : seg.getSupernodeGraph().edges)
      if (e.source >= l && e.target >= l)
        out[{e.source, e.target}] = e.weight;
    return out;
  };
  const auto off = memberWeights(std::nullopt);
  EXPECT_TRUE(seg.getAnalysis()->concavity.empty());
  const auto on = memberWeights(3.0);
  EXPECT_FALSE(seg.getAnalysis()->concavity.empty());
  ASSERT_EQ(on.size(), off.size());
  std::size_t weaker = 0;
  for (const auto& [key, w] : on) {
    ASSERT_TRUE(off.count(key));
    EXPECT_LE(w, off.at(key) * (1 + 1e-12));
    weaker += w < 0.9 * off.at(key);
  }
  EXPECT_GT(weaker, 0u); // legs, neck and tail meet the body at concave creases
}

TEST(ConcavityWeight, SetterRejectsBadValues) {
  pcl::SupernodeNCutSegmentation<pcl::PointXYZ> seg;
  seg.setConcavityWeight(1.5);
  for (double bad : {0.0, -1e-30, -1.0, std::numeric_limits<double>::quiet_NaN(),
                     std::numeric_limits<double>::infinity()}) {
    seg.setConcavityWeight(bad);
    EXPECT_EQ(seg.getConcavityWeight(), 1.5);
  }
  seg.setConcavityWeight(std::nullopt);
  EXPECT_EQ(seg.getConcavityWeight(), std::nullopt);
}
