/*
 * Single views recognised and their rims (core/views/single_view.h): generated views, sampled as a
 * camera at the origin looking along z sees them (one point per ray of a square grid of rays,
 * the surfaces behind others removed), and closed surfaces, which are no view.
 */
#include "core/common/stopwatch.h"
#include "core/graph/csr_graph.h"
#include "core/graph/knn.h"
#include "core/views/single_view.h"

#include <shapes/shapes.h>

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <iostream>
#include <random>

using namespace pcl_ncut_seg;

namespace {

const float kOrigin[3] = {0.0f, 0.0f, 0.0f};

CsrGraph knnGraph(const std::vector<float>& xyz, std::size_t k = 10) {
  const std::size_t n = xyz.size() / 3;
  std::vector<std::uint32_t> knn(n * k);
  kNearestNeighbours(xyz.data(), n, k, 2, knn.data());
  return buildSymmetricKnnGraph(xyz.data(), n, knn.data(), k, 2);
}

/// Appends a grid of cols x rows points with the given spacing at depth z from (x0, y0) on,
/// each moved by up to jitter spacings in x and y. Point (i, j) is the (i * rows + j)-th.
void sheet(double x0, double y0, int cols, int rows, double spacing, double z, double jitter,
           std::mt19937& rng, std::vector<float>& xyz) {
  std::uniform_real_distribution<double> shift(-jitter, jitter);
  for (int i = 0; i < cols; ++i)
    for (int j = 0; j < rows; ++j) {
      const double x = x0 + (i + shift(rng)) * spacing, y = y0 + (j + shift(rng)) * spacing;
      xyz.insert(xyz.end(), {float(x), float(y), float(z)});
    }
}

/// A square grid of cols x cols points, 1 cm apart at 1 m, centred on the z axis (jittered by
/// up to 0.2 spacings).
std::vector<float> grid(int cols, std::uint32_t seed, double spacing = 0.01) {
  std::mt19937 rng(seed);
  std::vector<float> xyz;
  const double x0 = -0.5 * (cols - 1) * spacing;
  sheet(x0, x0, cols, cols, spacing, 1.0, 0.2, rng, xyz);
  return xyz;
}

/// n points of the sphere of the given centre and radius on a Fibonacci lattice.
std::vector<float> sphere(std::size_t n, const double centre[3], double radius) {
  const std::vector<double> unit = pcl_ncut_seg::test::fibonacciSphere(n);
  std::vector<float> xyz(unit.size());
  for (std::size_t i = 0; i < unit.size(); ++i)
    xyz[i] = static_cast<float>(centre[i % 3] + radius * unit[i]);
  return xyz;
}

/// Spacing of the rays of sphereSeen() in the image plane z = 1 (about 0.23 degrees).
const double kRaySpacing = 0.004;

/// What the camera sees of the sphere of the given radius centred 1 m ahead: the first hit of
/// each ray through a square grid of points of the image plane z = 1 (jittered by up to 0.2
/// spacings): the cap in front of the sphere's silhouette.
std::vector<float> sphereSeen(double radius, std::uint32_t seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> shift(-0.2, 0.2);
  const int half = static_cast<int>(std::ceil(1.2 * radius / kRaySpacing));
  std::vector<float> xyz;
  for (int i = -half; i <= half; ++i)
    for (int j = -half; j <= half; ++j) {
      const double u = (i + shift(rng)) * kRaySpacing, v = (j + shift(rng)) * kRaySpacing;
      const double norm = std::sqrt(u * u + v * v + 1.0), b = 1.0 / norm;
      const double disc = b * b - 1.0 + radius * radius;
      if (disc < 0.0)
        continue; // the ray misses the sphere
      const double t = (b - std::sqrt(disc)) / norm;
      xyz.insert(xyz.end(), {float(t * u), float(t * v), float(t)});
    }
  return xyz;
}

/// The fraction of the listed vertices flagged.
double flagged(const std::vector<std::uint8_t>& rim, const std::vector<std::uint32_t>& vertices) {
  std::size_t count = 0;
  for (std::uint32_t v : vertices)
    count += rim[v];
  return vertices.empty() ? 0.0 : double(count) / vertices.size();
}

/// The points of a cols x rows grid (from vertex first on) r steps in from its border (ring r),
/// or with inner more than r steps in.
std::vector<std::uint32_t> ring(int cols, int rows, int r, bool inner = false,
                                std::size_t first = 0) {
  std::vector<std::uint32_t> out;
  for (int i = 0; i < cols; ++i)
    for (int j = 0; j < rows; ++j) {
      const int depth = std::min(std::min(i, j), std::min(cols - 1 - i, rows - 1 - j));
      if (inner ? depth > r : depth == r)
        out.push_back(static_cast<std::uint32_t>(first + i * rows + j));
    }
  return out;
}

/// A square grid (cols x cols) with some of its points removed: per grid point, its vertex or
/// -1 (removed).
struct Holed {
  int cols;
  std::vector<std::int64_t> vertex;

  bool removed(int i, int j) const { return vertex[i * cols + j] < 0; }

  /// The kept points with a removed grid neighbour (4-neighbourhood): those next to a hole.
  std::vector<std::uint32_t> nextToRemoved() const {
    std::vector<std::uint32_t> out;
    for (int i = 1; i + 1 < cols; ++i)
      for (int j = 1; j + 1 < cols; ++j)
        if (!removed(i, j) &&
            (removed(i - 1, j) || removed(i + 1, j) || removed(i, j - 1) || removed(i, j + 1)))
          out.push_back(static_cast<std::uint32_t>(vertex[i * cols + j]));
    return out;
  }

  /// The kept points more than r steps from the border and from any removed point.
  std::vector<std::uint32_t> farFromRemoved(int r) const {
    std::vector<std::uint32_t> out;
    for (int i = r + 1; i + r + 1 < cols; ++i)
      for (int j = r + 1; j + r + 1 < cols; ++j) {
        bool far = true;
        for (int a = i - r; a <= i + r; ++a)
          for (int b = j - r; b <= j + r; ++b)
            far = far && !removed(a, b);
        if (far)
          out.push_back(static_cast<std::uint32_t>(vertex[i * cols + j]));
      }
    return out;
  }
};

/// A grid's points kept where keep(x, y) holds: the grid with holes, and the points kept.
template <typename Keep>
Holed keepWhere(const std::vector<float>& full, int cols, Keep keep, std::vector<float>& xyz) {
  Holed holed{cols, {}};
  for (std::size_t p = 0; p < full.size() / 3; ++p) {
    const bool kept = keep(full[3 * p], full[3 * p + 1]);
    holed.vertex.push_back(kept ? static_cast<std::int64_t>(xyz.size() / 3) : -1);
    if (kept)
      xyz.insert(xyz.end(), full.begin() + 3 * p, full.begin() + 3 * p + 3);
  }
  return holed;
}

} // namespace

TEST(SingleView, AFlatGridIsOneViewWithItsBorderAsRim) {
  const int cols = 100;
  const std::vector<float> xyz = grid(cols, 1);
  const std::vector<std::uint8_t> rim = singleViewRim(knnGraph(xyz), xyz.data(), kOrigin, 2);
  ASSERT_EQ(rim.size(), xyz.size() / 3);
  std::cout << "flagged: border " << flagged(rim, ring(cols, cols, 0)) << ", next ring "
            << flagged(rim, ring(cols, cols, 1)) << ", inside "
            << flagged(rim, ring(cols, cols, 2, true)) << "\n";
  EXPECT_GE(flagged(rim, ring(cols, cols, 0)), 0.95);
  EXPECT_LE(flagged(rim, ring(cols, cols, 2, true)), 0.01);
}

TEST(SingleView, AHemisphereCapIsOneViewWithItsSilhouetteAsRim) {
  // The camera sees the half facing it up to the silhouette, 72.5 degrees around the sphere
  // from the point nearest: the rest of that half lies behind the front.
  const double radius = 0.3;
  const std::vector<float> xyz = sphereSeen(radius, 2);
  const std::vector<std::uint8_t> rim = singleViewRim(knnGraph(xyz), xyz.data(), kOrigin, 2);
  ASSERT_EQ(rim.size(), xyz.size() / 3);
  // Ray spacings in from the silhouette, a circle of radius tan(asin(radius)) in the image.
  const double silhouette = radius / std::sqrt(1.0 - radius * radius);
  std::vector<std::uint32_t> outermost, inside;
  for (std::size_t p = 0; p < rim.size(); ++p) {
    const double image = std::hypot(xyz[3 * p], xyz[3 * p + 1]) / xyz[3 * p + 2];
    const double in = (silhouette - image) / kRaySpacing;
    if (in < 0.5)
      outermost.push_back(static_cast<std::uint32_t>(p));
    else if (in > 2.0)
      inside.push_back(static_cast<std::uint32_t>(p));
  }
  std::cout << "flagged: silhouette " << flagged(rim, outermost) << " of " << outermost.size()
            << ", inside " << flagged(rim, inside) << " of " << inside.size() << "\n";
  EXPECT_GE(flagged(rim, outermost), 0.95);
  EXPECT_LE(flagged(rim, inside), 0.01);
}

TEST(SingleView, AClosedSphereAroundTheOriginIsNoView) {
  const double centre[3] = {0.0, 0.0, 0.0};
  const std::vector<float> xyz = sphere(4000, centre, 1.0);
  EXPECT_TRUE(singleViewRim(knnGraph(xyz), xyz.data(), kOrigin, 2).empty());
}

TEST(SingleView, AClosedSphereInFrontIsNoView) {
  // Both sides sampled: its back is seen through its front.
  const double centre[3] = {0.0, 0.0, 1.0};
  const std::vector<float> xyz = sphere(20000, centre, 0.3);
  EXPECT_TRUE(singleViewRim(knnGraph(xyz), xyz.data(), kOrigin, 2).empty());
}

namespace {

/// A rectangle of points at 0.9 m in front of the 1 m grid: cols x rows points 1 cm apart
/// from (x0, y0) on.
struct Occluder {
  double x0, y0;
  int cols, rows;

  /// Whether it hides the ray through (x, y) at 1 m.
  bool hides(double x, double y) const {
    const double u = 0.9 * x, v = 0.9 * y;
    return u >= x0 && u <= x0 + 0.01 * (cols - 1) && v >= y0 && v <= y0 + 0.01 * (rows - 1);
  }
  /// Whether (x, y) at 1 m is within 2 cm of a corner of its shadow, where the grid wraps three
  /// quarters around a point: a gap of about 90 degrees, either side of the rim's bound.
  bool nearCorner(double x, double y) const {
    const double left = x0 / 0.9, right = (x0 + 0.01 * (cols - 1)) / 0.9;
    const double low = y0 / 0.9, high = (y0 + 0.01 * (rows - 1)) / 0.9;
    return std::min(std::abs(x - left), std::abs(x - right)) < 0.02 &&
           std::min(std::abs(y - low), std::abs(y - high)) < 0.02;
  }
};

/// A depth image: the 1 m grid (100 x 100 points) with the points behind the occluders
/// removed, as the camera would not see them, then each occluder's points.
struct Scene {
  std::vector<float> xyz;
  Holed plane;
  std::vector<std::size_t> first; ///< per occluder, its first vertex
};

Scene occludedGrid(const std::vector<Occluder>& occluders) {
  Scene scene;
  scene.plane = keepWhere(
      grid(100, 3), 100,
      [&](double x, double y) {
        return std::none_of(occluders.begin(), occluders.end(),
                            [&](const Occluder& o) { return o.hides(x, y); });
      },
      scene.xyz);
  std::mt19937 rng(4);
  for (const Occluder& o : occluders) {
    scene.first.push_back(scene.xyz.size() / 3);
    sheet(o.x0, o.y0, o.cols, o.rows, 0.01, 0.9, 0.2, rng, scene.xyz);
  }
  return scene;
}

/// Checks the scene is one view with the occlusion as rim: the grid beside each shadow, each
/// occluder's border; and nothing inside (more than 2 steps in from a border, grid or not).
void expectOcclusionRim(const Scene& scene, const std::vector<Occluder>& occluders) {
  const std::vector<std::uint8_t> rim =
      singleViewRim(knnGraph(scene.xyz), scene.xyz.data(), kOrigin, 2);
  ASSERT_EQ(rim.size(), scene.xyz.size() / 3);
  std::vector<std::uint32_t> beside, borders, inside = scene.plane.farFromRemoved(2);
  for (std::uint32_t v : scene.plane.nextToRemoved())
    if (std::none_of(occluders.begin(), occluders.end(), [&](const Occluder& o) {
          return o.nearCorner(scene.xyz[3 * v], scene.xyz[3 * v + 1]);
        }))
      beside.push_back(v);
  for (std::size_t k = 0; k < occluders.size(); ++k) {
    for (std::uint32_t v : ring(occluders[k].cols, occluders[k].rows, 0, false, scene.first[k]))
      borders.push_back(v);
    for (std::uint32_t v : ring(occluders[k].cols, occluders[k].rows, 2, true, scene.first[k]))
      inside.push_back(v);
  }
  std::cout << "flagged: beside the shadows " << flagged(rim, beside) << " of " << beside.size()
            << ", all next to them " << flagged(rim, scene.plane.nextToRemoved())
            << ", occluders' borders " << flagged(rim, borders) << ", inside "
            << flagged(rim, inside) << " of " << inside.size() << "\n";
  EXPECT_GE(beside.size(), 100u);
  EXPECT_GE(flagged(rim, beside), 0.95);
  EXPECT_GE(flagged(rim, borders), 0.95);
  EXPECT_LE(flagged(rim, inside), 0.01);
}

} // namespace

// The occluders' shadows on the grid have their edges halfway between its rows and columns
// (at 1 m: 0.9 m times a multiple of 1 cm plus 0.5 cm), so the points next to them form straight
// rows; a row on a shadow's edge would be cut raggedly, and the row behind it is then no rim.

TEST(SingleView, ADepthImageWithAnOccluderIsOneViewWithTheOcclusionAsRim) {
  // A square of side 0.54 m, 10 cm in front of the grid (7 edge lengths: two layers by range).
  const std::vector<Occluder> square = {{-0.27, -0.27, 55, 55}};
  expectOcclusionRim(occludedGrid(square), square);
}

TEST(SingleView, ADepthImageBehindAFenceIsOneView) {
  // Five bars 9 cm wide: cells where both layers meet are about 5% of all, beyond the bound of
  // 2% unless only points inside their layers' images count.
  std::vector<Occluder> bars;
  for (int k = 0; k < 5; ++k)
    bars.push_back({-0.396 + 0.18 * k, -0.315, 10, 64});
  expectOcclusionRim(occludedGrid(bars), bars);
}

TEST(SingleView, AGridWithAHoleHasTheHolesBorderAsRim) {
  std::vector<float> xyz;
  const Holed holed = keepWhere(
      grid(100, 5), 100, [](double x, double y) { return std::hypot(x, y) >= 0.15; }, xyz);
  const std::vector<std::uint8_t> rim = singleViewRim(knnGraph(xyz), xyz.data(), kOrigin, 2);
  ASSERT_EQ(rim.size(), xyz.size() / 3);
  const std::vector<std::uint32_t> border = holed.nextToRemoved(), inside = holed.farFromRemoved(2);
  std::cout << "flagged: hole's border " << flagged(rim, border) << " of " << border.size()
            << ", inside " << flagged(rim, inside) << " of " << inside.size() << "\n";
  EXPECT_GE(flagged(rim, border), 0.95);
  EXPECT_LE(flagged(rim, inside), 0.01);
}

TEST(SingleView, BadInputGivesNoView) {
  EXPECT_TRUE(singleViewRim(CsrGraph{}, nullptr, kOrigin).empty());
  const std::vector<float> two = {0.0f, 0.0f, 1.0f, 0.01f, 0.0f, 1.0f};
  EXPECT_TRUE(singleViewRim(knnGraph(two, 1), two.data(), kOrigin).empty());
  // A point at the sensor has no direction.
  std::vector<float> xyz = grid(20, 6);
  xyz.insert(xyz.end(), {0.0f, 0.0f, 0.0f});
  EXPECT_TRUE(singleViewRim(knnGraph(xyz), xyz.data(), kOrigin).empty());
}

TEST(SingleView, TheSameForAnyNumberOfThreads) {
  const Scene scene = occludedGrid({{-0.27, -0.27, 55, 55}});
  const CsrGraph graph = knnGraph(scene.xyz);
  EXPECT_EQ(singleViewRim(graph, scene.xyz.data(), kOrigin, 1),
            singleViewRim(graph, scene.xyz.data(), kOrigin, 2));
}

TEST(SingleView, TimeOnAGridOf300000Points) {
  const int cols = 548; // 300,304 points 1 mm apart
  const std::vector<float> xyz = grid(cols, 7, 0.001);
  const CsrGraph graph = knnGraph(xyz);
  for (unsigned threads : {1u, 2u}) {
    double best = 1e9;
    std::vector<std::uint8_t> rim;
    for (int run = 0; run < 5; ++run) {
      Stopwatch watch;
      rim = singleViewRim(graph, xyz.data(), kOrigin, threads);
      best = std::min(best, watch.lap());
    }
    std::cout << threads << " thread(s): " << 1e3 * best << " ms (best of 5)\n";
    ASSERT_EQ(rim.size(), xyz.size() / 3);
    EXPECT_GE(flagged(rim, ring(cols, cols, 0)), 0.95);
    EXPECT_LE(flagged(rim, ring(cols, cols, 2, true)), 0.01);
  }
}
