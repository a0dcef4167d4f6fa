/*
 * A view's sensor position read off its points (core/views/view_origin.h): boundary points from the
 * points alone, and the sensor found on the axis of the rim when the cloud's origin says
 * nothing (sensor_origin_ left at 0 in the object's frame).
 */
#include "core/graph/csr_graph.h"
#include "core/graph/knn.h"
#include "core/views/view_origin.h"
#include <pcl_ncut_seg/supernode_ncut_segmentation.h>

#include <shapes/shapes.h>

#include <gtest/gtest.h>

#include <cmath>
#include <random>

using namespace pcl_ncut_seg;

namespace {

CsrGraph knnGraph(const std::vector<float>& xyz, std::size_t k = 10) {
  const std::size_t n = xyz.size() / 3;
  std::vector<std::uint32_t> knn(n * k);
  kNearestNeighbours(xyz.data(), n, k, 2, knn.data());
  return buildSymmetricKnnGraph(xyz.data(), n, knn.data(), k, 2);
}

/// What a camera at (0, 0, -1) sees of the sphere of the given radius centred at the origin:
/// the first hit of each ray through a square grid of the image plane (jittered by up to 0.2
/// spacings of 0.004): the cap in front of the silhouette, in the object's frame.
std::vector<float> capSeenFromBelow(double radius, std::uint32_t seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> shift(-0.2, 0.2);
  const double spacing = 0.004;
  const int half = static_cast<int>(std::ceil(1.2 * radius / spacing));
  std::vector<float> xyz;
  for (int i = -half; i <= half; ++i)
    for (int j = -half; j <= half; ++j) {
      const double u = (i + shift(rng)) * spacing, v = (j + shift(rng)) * spacing;
      const double norm = std::sqrt(u * u + v * v + 1.0), b = 1.0 / norm;
      const double disc = b * b - 1.0 + radius * radius;
      if (disc < 0.0)
        continue;
      const double t = (b - std::sqrt(disc)) / norm;
      xyz.insert(xyz.end(), {float(t * u), float(t * v), float(t - 1.0)});
    }
  return xyz;
}

std::vector<float> sphere(std::size_t n, double radius) {
  const std::vector<double> unit = pcl_ncut_seg::test::fibonacciSphere(n);
  std::vector<float> xyz(unit.size());
  for (std::size_t i = 0; i < unit.size(); ++i)
    xyz[i] = static_cast<float>(radius * unit[i]);
  return xyz;
}

} // namespace

TEST(BoundaryPoints, AFlatGridsBorderAndNotItsInside) {
  const int cols = 60;
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> shift(-0.2, 0.2);
  std::vector<float> xyz;
  for (int i = 0; i < cols; ++i)
    for (int j = 0; j < cols; ++j)
      xyz.insert(xyz.end(), {float(i + shift(rng)), float(j + shift(rng)), 0.0f});
  const std::vector<std::uint8_t> boundary = boundaryPoints(knnGraph(xyz), xyz.data());
  std::size_t border = 0, border_flagged = 0, inside_flagged = 0;
  for (int i = 0; i < cols; ++i)
    for (int j = 0; j < cols; ++j) {
      const bool on_border = i == 0 || j == 0 || i == cols - 1 || j == cols - 1;
      const bool deep = i > 1 && j > 1 && i < cols - 2 && j < cols - 2;
      border += on_border;
      border_flagged += on_border && boundary[i * cols + j];
      inside_flagged += deep && boundary[i * cols + j];
    }
  EXPECT_GE(border_flagged, 0.95 * border);
  EXPECT_EQ(inside_flagged, 0u);
}

TEST(EstimateViewOrigin, FindsTheCameraSideOfACap) {
  const std::vector<float> xyz = capSeenFromBelow(0.3, 1);
  const CsrGraph graph = knnGraph(xyz);
  std::vector<std::uint8_t> rim;
  const auto origin = estimateViewOrigin(graph, xyz.data(), 2, &rim);
  ASSERT_TRUE(origin.has_value());
  ASSERT_EQ(rim.size(), xyz.size() / 3);
  // On the camera's side, along its line of sight (the z axis) within 10 degrees.
  const double norm = std::sqrt((*origin)[0] * (*origin)[0] + (*origin)[1] * (*origin)[1] +
                                (*origin)[2] * (*origin)[2]);
  EXPECT_LT((*origin)[2], 0.0f);
  EXPECT_GT(-(*origin)[2] / norm, std::cos(10.0 * M_PI / 180.0));
  std::size_t on_rim = 0;
  for (std::uint8_t r : rim)
    on_rim += r;
  EXPECT_GT(on_rim, 0u);
  EXPECT_LT(on_rim, rim.size() / 5);
  // The same on one thread.
  std::vector<std::uint8_t> rim_one;
  EXPECT_EQ(estimateViewOrigin(graph, xyz.data(), 1, &rim_one), origin);
  EXPECT_EQ(rim_one, rim);
}

TEST(EstimateViewOrigin, AClosedSurfaceIsNoView) {
  const std::vector<float> xyz = sphere(6000, 0.3);
  EXPECT_FALSE(estimateViewOrigin(knnGraph(xyz), xyz.data(), 2).has_value());
}

TEST(EstimateViewOrigin, TooFewPointsAreNoView) {
  const std::vector<float> xyz = {0, 0, 0, 1, 0, 0, 0, 1, 0};
  EXPECT_FALSE(estimateViewOrigin(knnGraph(xyz, 2), xyz.data(), 1).has_value());
}

TEST(ViewTest, ACropWithItsOriginAtTheCentreIsAViewFromAnEstimatedSensor) {
  // The crop in a frame centred on its points, the origin left at 0 there.
  const std::vector<float> xyz = capSeenFromBelow(0.3, 2);
  double mean_z = 0.0;
  for (std::size_t i = 2; i < xyz.size(); i += 3)
    mean_z += xyz[i] / (xyz.size() / 3.0);
  pcl::PointCloud<pcl::PointXYZ>::Ptr cloud(new pcl::PointCloud<pcl::PointXYZ>);
  for (std::size_t i = 0; i < xyz.size(); i += 3)
    cloud->push_back(pcl::PointXYZ(xyz[i], xyz[i + 1], static_cast<float>(xyz[i + 2] - mean_z)));
  pcl::SupernodeNCutSegmentation<pcl::PointXYZ> seg;
  seg.setInputCloud(cloud);
  std::vector<pcl::PointIndices> segments;
  seg.extract(segments);
  EXPECT_FALSE(segments.empty());
  const ViewTest view = seg.getViewTest();
  EXPECT_TRUE(view.view);
  EXPECT_TRUE(view.origin_estimated);
  EXPECT_GT(view.rim_points, 0u);
  // With the camera's position given, it is used as it is.
  cloud->sensor_origin_ = Eigen::Vector4f(0.0f, 0.0f, static_cast<float>(-1.0 - mean_z), 0.0f);
  seg.setInputCloud(cloud);
  seg.extract(segments);
  EXPECT_TRUE(seg.getViewTest().view);
  EXPECT_FALSE(seg.getViewTest().origin_estimated);
  // A closed surface is none; nor is anything with single_view off.
  const std::vector<float> closed = sphere(3000, 0.3);
  pcl::PointCloud<pcl::PointXYZ>::Ptr ball(new pcl::PointCloud<pcl::PointXYZ>);
  for (std::size_t i = 0; i < closed.size(); i += 3)
    ball->push_back(pcl::PointXYZ(closed[i], closed[i + 1], closed[i + 2]));
  seg.setInputCloud(ball);
  seg.extract(segments);
  EXPECT_FALSE(seg.getViewTest().view);
  Parameters off;
  off.graph.single_view = false;
  ASSERT_TRUE(seg.setParameters(off));
  seg.setInputCloud(cloud);
  seg.extract(segments);
  EXPECT_FALSE(seg.getViewTest().view);
}
