/*
 * Depth-camera views of a mesh (kit/surfaces/depth_view.h): the ray casting against brute force,
 * the organized layout and its NaNs, the camera convention, the range noise's growth with depth,
 * the sensor pose; and the scoring of a view on the faces it sees (eval/view_scoring.h).
 */
#include "view_scoring.h"
#include <surfaces/depth_view.h>
#include <surfaces/depth_view_pcl.h>

#include <gtest/gtest.h>

#include <cmath>
#include <random>

namespace {

using pcl_ncut_seg::CameraPose;
using pcl_ncut_seg::CameraSettings;
using pcl_ncut_seg::DepthView;
using pcl_ncut_seg::RayCaster;
using pcl_ncut_seg::TriangleMesh;
using Vec = std::array<double, 3>;

void addTriangle(TriangleMesh& m, const Vec& a, const Vec& b, const Vec& c) {
  const auto first = static_cast<std::uint32_t>(m.numVertices());
  for (const Vec* v : {&a, &b, &c})
    for (double x : *v)
      m.vertices.push_back(static_cast<float>(x));
  for (std::uint32_t k = 0; k < 3; ++k)
    m.faces.push_back(first + k);
  m.original_face.push_back(static_cast<std::uint32_t>(m.numTriangles() - 1));
  m.num_original_faces = m.numTriangles();
}

/** The square [x0, x1] x [y0, y1] at height z, two triangles sharing a diagonal. */
void addSquare(TriangleMesh& m, double x0, double x1, double y0, double y1, double z) {
  addTriangle(m, {x0, y0, z}, {x1, y0, z}, {x1, y1, z});
  addTriangle(m, {x0, y0, z}, {x1, y1, z}, {x0, y1, z});
}

/** An axis-aligned box of 12 triangles (shared edges and corners everywhere). */
TriangleMesh box(double sx, double sy, double sz) {
  TriangleMesh m;
  const double x[2] = {-sx / 2, sx / 2}, y[2] = {-sy / 2, sy / 2}, z[2] = {-sz / 2, sz / 2};
  for (int s = 0; s < 2; ++s) {
    addTriangle(m, {x[0], y[0], z[s]}, {x[1], y[0], z[s]}, {x[1], y[1], z[s]});
    addTriangle(m, {x[0], y[0], z[s]}, {x[1], y[1], z[s]}, {x[0], y[1], z[s]});
    addTriangle(m, {x[0], y[s], z[0]}, {x[1], y[s], z[0]}, {x[1], y[s], z[1]});
    addTriangle(m, {x[0], y[s], z[0]}, {x[1], y[s], z[1]}, {x[0], y[s], z[1]});
    addTriangle(m, {x[s], y[0], z[0]}, {x[s], y[1], z[0]}, {x[s], y[1], z[1]});
    addTriangle(m, {x[s], y[0], z[0]}, {x[s], y[1], z[1]}, {x[s], y[0], z[1]});
  }
  return m;
}

/** Random triangles in the unit cube: overlaps, intersections, slivers. */
TriangleMesh soup(std::size_t n, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(-0.5, 0.5);
  TriangleMesh m;
  for (std::size_t i = 0; i < n; ++i) {
    const Vec a{{u(rng), u(rng), u(rng)}};
    addTriangle(m, a, {a[0] + 0.3 * u(rng), a[1] + 0.3 * u(rng), a[2] + 0.3 * u(rng)},
                {a[0] + 0.3 * u(rng), a[1] + 0.3 * u(rng), a[2] + 0.3 * u(rng)});
  }
  return m;
}

/** The pixel's ray direction in the world, as the header documents it. */
Vec pixelRay(const CameraSettings& cam, const CameraPose& pose, int u, int v) {
  const double f = 0.5 * cam.width / std::tan(0.5 * cam.horizontal_fov_degrees * M_PI / 180);
  const Vec c{{(u + 0.5 - cam.width / 2.0) / f, (v + 0.5 - cam.height / 2.0) / f, 1}};
  const auto& R = pose.rotation;
  return {R[0] * c[0] + R[1] * c[1] + R[2] * c[2], R[3] * c[0] + R[4] * c[1] + R[5] * c[2],
          R[6] * c[0] + R[7] * c[1] + R[8] * c[2]};
}

/** Camera coordinates of a world point: R^T (p - origin). */
Vec toCamera(const CameraPose& pose, const float* p) {
  const auto& R = pose.rotation;
  const Vec d{{p[0] - pose.origin[0], p[1] - pose.origin[1], p[2] - pose.origin[2]}};
  return {R[0] * d[0] + R[3] * d[1] + R[6] * d[2], R[1] * d[0] + R[4] * d[1] + R[7] * d[2],
          R[2] * d[0] + R[5] * d[1] + R[8] * d[2]};
}

CameraPose poseLookingFrom(const Vec& origin, std::uint64_t seed) {
  CameraPose pose;
  pose.rotation = pcl_ncut_seg::randomRotation(seed);
  pose.origin = origin;
  return pose;
}

// ---------------------------------------------------------------------------- ray casting

TEST(RayCaster, FindsTheSameHitAsBruteForce) {
  for (const TriangleMesh& mesh : {box(1, 0.6, 0.3), soup(300, 1), soup(40, 2)}) {
    const RayCaster caster(mesh);
    std::mt19937 rng(7);
    std::uniform_real_distribution<double> u(-1, 1);
    std::size_t hits = 0;
    for (int r = 0; r < 20000; ++r) {
      const Vec o{{2 * u(rng), 2 * u(rng), 2 * u(rng)}};
      Vec target{{0.6 * u(rng), 0.6 * u(rng), 0.6 * u(rng)}};
      if (r % 4 == 0) { // through a vertex: where rounding decides between triangles
        const std::size_t v = static_cast<std::size_t>(r / 4) % mesh.numVertices();
        target = {mesh.vertices[3 * v], mesh.vertices[3 * v + 1], mesh.vertices[3 * v + 2]};
      }
      Vec d{{target[0] - o[0], target[1] - o[1], target[2] - o[2]}};
      if (r % 7 == 0)
        d[r % 3] = 0; // axis-parallel components
      const auto fast = caster.cast(o, d);
      const auto slow = RayCaster::castBruteForce(mesh, o, d);
      ASSERT_EQ(fast.triangle, slow.triangle) << "ray " << r;
      if (slow.triangle >= 0) {
        ++hits;
        ASSERT_EQ(fast.t, slow.t) << "ray " << r;
      }
    }
    EXPECT_GT(hits, 2000u);
  }
}

TEST(RayCaster, RendersEveryPixelAsBruteForceDoes) {
  const TriangleMesh mesh = soup(200, 3); // fills most of the frame from 1 m
  CameraSettings cam;
  cam.width = 64;
  cam.height = 48;
  cam.noise_at_1m = 0;
  const CameraPose pose = poseLookingFrom({0, 0, -1}, 0); // rotated: any direction will do
  CameraPose facing;
  facing.origin = {0, 0, -1}; // the identity looks along +z, at the soup
  std::size_t hits = 0;
  for (const CameraPose& p : {pose, facing}) {
    const DepthView view = pcl_ncut_seg::renderMesh(mesh, cam, p, 1);
    for (int v = 0; v < cam.height; ++v)
      for (int u = 0; u < cam.width; ++u) {
        const std::size_t i = static_cast<std::size_t>(v) * cam.width + u;
        const Vec d = pixelRay(cam, p, u, v);
        const auto hit = RayCaster::castBruteForce(mesh, p.origin, d);
        ASSERT_EQ(view.face[i],
                  hit.triangle < 0 ? -1 : std::int64_t{mesh.original_face[hit.triangle]});
        if (hit.triangle < 0)
          continue;
        ++hits;
        for (int k = 0; k < 3; ++k)
          EXPECT_FLOAT_EQ(view.xyz[3 * i + k], static_cast<float>(p.origin[k] + hit.t * d[k]));
      }
  }
  EXPECT_GT(hits, 500u);
}

// ------------------------------------------------------------------------ layout and camera

TEST(DepthView, IsOrganizedWithNaNWhereNothingWasHit) {
  // A square right of and below the optical axis (x right, y down), 0.5 m away.
  TriangleMesh mesh;
  addSquare(mesh, 0.05, 0.15, 0.02, 0.10, 0.5);
  CameraSettings cam;
  cam.noise_at_1m = 0;
  const DepthView view = pcl_ncut_seg::renderMesh(mesh, cam, CameraPose(), 1);
  ASSERT_EQ(view.width, 640);
  ASSERT_EQ(view.height, 480);
  ASSERT_EQ(view.face.size(), 640u * 480u);
  const double f = cam.focalLength();
  EXPECT_NEAR(f, 320 / std::tan(28.5 * M_PI / 180), 1e-9);
  std::size_t valid = 0;
  for (int v = 0; v < view.height; ++v)
    for (int u = 0; u < view.width; ++u) {
      const std::size_t i = static_cast<std::size_t>(v) * view.width + u;
      const double x = (u + 0.5 - 320) / f * 0.5, y = (v + 0.5 - 240) / f * 0.5;
      const bool inside = x > 0.05 && x < 0.15 && y > 0.02 && y < 0.10;
      const bool near_edge = std::abs(x - 0.05) < 1e-3 || std::abs(x - 0.15) < 1e-3 ||
                             std::abs(y - 0.02) < 1e-3 || std::abs(y - 0.10) < 1e-3;
      if (!near_edge) {
        ASSERT_EQ(view.face[i] >= 0, inside) << u << "," << v;
      }
      ASSERT_EQ(std::isnan(view.xyz[3 * i]), view.face[i] < 0);
      if (view.face[i] >= 0) {
        ++valid;
        EXPECT_NEAR(view.xyz[3 * i + 2], 0.5, 1e-6);
        EXPECT_NEAR(view.xyz[3 * i], x, 1e-6);
      }
    }
  EXPECT_EQ(valid, view.validPixels());
  const auto cloud = pcl_ncut_seg::toPclCloud(view);
  EXPECT_EQ(cloud->width, 640u);
  EXPECT_EQ(cloud->height, 480u);
  EXPECT_TRUE(cloud->isOrganized());
  EXPECT_FALSE(cloud->is_dense);
  EXPECT_TRUE(std::isnan(cloud->at(0, 0).x)); // column 0, row 0: top left, nothing there
  const std::size_t centre = 60 * 640 + 400;  // u = 400, v = 60 + 240 in the square
  EXPECT_TRUE(std::isfinite(cloud->at(400, 300).x));
  EXPECT_TRUE(std::isnan((*cloud)[centre].x)); // row 60 is above the axis: nothing
}

/** The sample standard deviation of (camera z - plane depth) over a view of a plane. */
double depthSpread(double depth, std::size_t* samples) {
  TriangleMesh mesh;
  addSquare(mesh, -5, 5, -5, 5, depth);
  CameraSettings cam; // default noise: 1.5 mm at 1 m
  const DepthView view = pcl_ncut_seg::renderMesh(mesh, cam, CameraPose(), 11);
  double sum = 0, sum2 = 0;
  *samples = 0;
  for (std::size_t i = 0; i < view.face.size(); ++i)
    if (view.face[i] >= 0) {
      const double e = view.xyz[3 * i + 2] - depth;
      sum += e;
      sum2 += e * e;
      ++*samples;
    }
  const double n = static_cast<double>(*samples);
  EXPECT_NEAR(sum / n, 0, 5 * 1.5e-3 * depth * depth / std::sqrt(n)); // unbiased
  return std::sqrt((sum2 - sum * sum / n) / (n - 1));
}

TEST(DepthView, RangeNoiseGrowsWithTheSquareOfTheDepth) {
  std::size_t n_near = 0, n_far = 0;
  const double near = depthSpread(0.8, &n_near), far = depthSpread(1.6, &n_far);
  ASSERT_EQ(n_near, 640u * 480u); // the plane fills the frame
  // sigma = 1.5 mm * z^2; with 307200 samples the estimate is within 1% (5 standard errors).
  EXPECT_NEAR(near, 1.5e-3 * 0.64, 0.01 * 1.5e-3 * 0.64);
  EXPECT_NEAR(far, 1.5e-3 * 2.56, 0.01 * 1.5e-3 * 2.56);
  EXPECT_NEAR(far / near, 4.0, 0.08);
}

TEST(DepthView, NoiseMovesPointsAlongTheirRays) {
  TriangleMesh mesh;
  addSquare(mesh, -1, 1, -1, 1, 1.0);
  CameraSettings cam;
  cam.width = 80;
  cam.height = 60;
  cam.noise_at_1m = 0.01;
  const CameraPose pose = poseLookingFrom({0.1, 0.2, -0.3}, 5);
  TriangleMesh moved = mesh; // the plane in front of this camera: 1 m along its axis
  for (std::size_t i = 0; i < mesh.vertices.size(); i += 3) {
    const Vec c{{mesh.vertices[i], mesh.vertices[i + 1], mesh.vertices[i + 2]}};
    for (int k = 0; k < 3; ++k)
      moved.vertices[i + k] =
          static_cast<float>(pose.origin[k] + pose.rotation[3 * k] * c[0] +
                             pose.rotation[3 * k + 1] * c[1] + pose.rotation[3 * k + 2] * c[2]);
  }
  const DepthView view = pcl_ncut_seg::renderMesh(moved, cam, pose, 3);
  const double f = cam.focalLength();
  ASSERT_EQ(view.validPixels(), 80u * 60u);
  double spread = 0;
  for (int v = 0; v < cam.height; ++v)
    for (int u = 0; u < cam.width; ++u) {
      const Vec c = toCamera(pose, &view.xyz[3 * (static_cast<std::size_t>(v) * cam.width + u)]);
      EXPECT_NEAR(c[0] / c[2] * f + 40, u + 0.5, 1e-3); // still on pixel (u, v)'s ray
      EXPECT_NEAR(c[1] / c[2] * f + 30, v + 0.5, 1e-3);
      spread = std::max(spread, std::abs(c[2] - 1.0));
    }
  EXPECT_GT(spread, 0.01); // the noise is there (about 4 sigma over 4800 pixels)
}

// ----------------------------------------------------------------------------- sensor pose

TEST(DepthView, TheSensorPoseLooksAtTheObjectFromTheGivenDistance) {
  const TriangleMesh mesh = box(2, 1, 0.5); // diagonal sqrt(5.25), scaled to 0.3 m
  CameraSettings cam;
  cam.width = 160;
  cam.height = 120;
  Vec previous{{0, 0, 0}};
  for (std::uint64_t seed = 1; seed <= 5; ++seed) {
    const DepthView view = pcl_ncut_seg::renderView(mesh, cam, pcl_ncut_seg::viewSeed(9, seed));
    ASSERT_EQ(view.width, 160);
    EXPECT_NEAR(view.scale, 0.3 / std::sqrt(5.25), 1e-9);
    const auto& o = view.pose.origin;
    EXPECT_NEAR(std::sqrt(o[0] * o[0] + o[1] * o[1] + o[2] * o[2]), 1.0, 1e-9);
    const float centre[3] = {0, 0, 0};
    const Vec c = toCamera(view.pose, centre); // the object's centre is straight ahead, 1 m
    EXPECT_NEAR(c[0], 0, 1e-9);
    EXPECT_NEAR(c[1], 0, 1e-9);
    EXPECT_NEAR(c[2], 1, 1e-9);
    EXPECT_NE(o, previous); // each seed its own direction
    previous = o;
    // The rotation is a proper one, and PCL's pose is the same.
    const auto& R = view.pose.rotation;
    const double det = R[0] * (R[4] * R[8] - R[5] * R[7]) - R[1] * (R[3] * R[8] - R[5] * R[6]) +
                       R[2] * (R[3] * R[7] - R[4] * R[6]);
    EXPECT_NEAR(det, 1, 1e-9);
    const auto cloud = pcl_ncut_seg::toPclCloud(view);
    const Eigen::Matrix3f M = cloud->sensor_orientation_.toRotationMatrix();
    for (int r = 0; r < 3; ++r) {
      EXPECT_NEAR(cloud->sensor_origin_[r], o[r], 1e-6);
      for (int k = 0; k < 3; ++k)
        EXPECT_NEAR(M(r, k), R[3 * r + k], 1e-6);
    }
    // Every point seen lies within the scaled box, in front of the camera.
    ASSERT_GT(view.validPixels(), 100u);
    for (std::size_t i = 0; i < view.face.size(); ++i)
      if (view.face[i] >= 0) {
        EXPECT_LT(std::abs(view.xyz[3 * i]), 0.3 / std::sqrt(5.25) + 0.01);
        EXPECT_GT(toCamera(view.pose, &view.xyz[3 * i])[2], 0.8);
      }
  }
  EXPECT_NE(pcl_ncut_seg::viewSeed(1, 2), pcl_ncut_seg::viewSeed(2, 1));
}

// ------------------------------------------------------------------------- seen-face scoring

TEST(ViewScoring, EachSeenFaceTakesItsPixelsMajorityLabel) {
  // Pixels: face 4 twice with label 7, once with 2; face 1 with 3 and 5 once each (a tie: the
  // smaller label); face 9 only in no segment; face 6 once unlabelled, once 8; one miss.
  const std::vector<std::int64_t> face = {4, 1, -1, 4, 9, 1, 4, 6, 6};
  const std::vector<int> label = {7, 5, 0, 7, -1, 3, 2, -1, 8};
  const std::vector<std::size_t> seen = pcl_ncut_seg::seenFaces(face);
  EXPECT_EQ(seen, (std::vector<std::size_t>{1, 4, 6, 9}));
  EXPECT_EQ(pcl_ncut_seg::faceLabelsFromPixels(face, label, seen), (std::vector<int>{3, 7, 8, -1}));
  const std::vector<int> human = {0, 10, 0, 0, 11, 0, 12, 0, 0, 13};
  EXPECT_EQ(pcl_ncut_seg::restrictToFaces(human, seen), (std::vector<int>{10, 11, 12, 13}));
}

} // namespace

namespace {

TEST(DepthView, ReadsAResolution) {
  int w = 0, h = 0;
  EXPECT_TRUE(pcl_ncut_seg::parseResolution("640x480", w, h));
  EXPECT_EQ(w, 640);
  EXPECT_EQ(h, 480);
  EXPECT_TRUE(pcl_ncut_seg::parseResolution("4096x8", w, h));
  for (const char* bad : {"", "x", "640", "640x", "x480", "640x480x2", "-640x480", "640 x 480",
                          "7x480", "640x4097", "1e3x480", "0000000640x480"})
    EXPECT_FALSE(pcl_ncut_seg::parseResolution(bad, w, h)) << bad;
}

} // namespace
