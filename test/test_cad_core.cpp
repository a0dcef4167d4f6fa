/*
 * CAD mode (Sec. 7) over plain arrays: the normal smoothing, ridge points, ridge distance,
 * the graph transformation and the dihedral angles between faces.
 */
#include "core/cad/cad.h"
#include "core/graph/csr_graph.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <utility>
#include <vector>

namespace {

using pcl_ncut_seg::CsrGraph;

/** \brief A path 0 - 1 - ... - (n-1) with unit lengths. */
CsrGraph path(std::size_t n) {
  std::vector<float> xyz(3 * n, 0.0f);
  std::vector<std::uint32_t> knn(n, ~0u);
  for (std::size_t i = 0; i < n; ++i) {
    xyz[3 * i] = float(i);
    if (i + 1 < n)
      knn[i] = std::uint32_t(i + 1);
  }
  return pcl_ncut_seg::buildSymmetricKnnGraph(xyz.data(), n, knn.data(), 1);
}

TEST(CadCore, SmoothingKeepsAPlaneAndFlipsNeighboursToAgree) {
  const CsrGraph g = path(5);
  // The same unoriented normal with alternating signs: smoothing must not cancel it.
  const std::vector<float> n = {0, 0, 1, 0, 0, -1, 0, 0, 1, 0, 0, -1, 0, 0, 1};
  const std::vector<float> s = pcl_ncut_seg::smoothNormals(g, n.data(), 4);
  for (std::size_t p = 0; p < 5; ++p)
    EXPECT_NEAR(std::abs(s[3 * p + 2]), 1.0f, 1e-6f) << "vertex " << p;
}

TEST(CadCore, SmoothingLeavesMissingNormalsOutAndFillsThemFromNeighbours) {
  const CsrGraph g = path(3);
  const float nan = std::nanf("");
  const std::vector<float> n = {1, 0, 0, nan, nan, nan, 0, 0, 0};
  const std::vector<float> s = pcl_ncut_seg::smoothNormals(g, n.data(), 1);
  EXPECT_NEAR(s[0], 1.0f, 1e-6f);
  EXPECT_NEAR(s[3], 1.0f, 1e-6f); // from vertex 0
  EXPECT_EQ(s[6], 0.0f);          // no usable normal around vertex 2 yet
}

TEST(CadCore, RidgePointsAreWhereNormalsTurn) {
  const CsrGraph g = path(6);
  // Normals turn by 90 degrees between vertices 2 and 3.
  const std::vector<float> n = {0, 0, 1, 0, 0, 1, 0, 0, 1, 0, 1, 0, 0, 1, 0, 0, 1, 0};
  const std::vector<bool> ridge = pcl_ncut_seg::ridgePoints(g, n, 10.0f);
  EXPECT_EQ(ridge, std::vector<bool>({false, false, true, true, false, false}));
}

TEST(CadCore, RidgeDistanceIsGeodesic) {
  const CsrGraph g = path(6);
  const std::vector<float> phi =
      pcl_ncut_seg::ridgeDistance(g, {false, false, true, false, false, false});
  EXPECT_EQ(phi, std::vector<float>({2, 1, 0, 1, 2, 3}));
  const std::vector<float> none = pcl_ncut_seg::ridgeDistance(g, std::vector<bool>(6, false));
  for (float v : none)
    EXPECT_TRUE(std::isinf(v));
}

TEST(CadCore, TransformShrinksLevelEdgesAndStretchesRisingOnes) {
  // A square 0 (0,0), 1 (1,0), 2 (1,1), 3 (0,1), knn rows: 0->1, 1->2, 2->3, 3->0.
  const std::vector<float> xyz = {0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0};
  const std::vector<std::uint32_t> knn = {1, 2, 3, 0};
  const CsrGraph g = pcl_ncut_seg::buildSymmetricKnnGraph(xyz.data(), 4, knn.data(), 1);
  // phi: 0 and 1 on a level set, 2 and 3 one unit higher; edge 1-2 rises by 0.5 only.
  const std::vector<float> phi = {0.0f, 0.5f, 1.0f, 1.0f};
  const CsrGraph t = pcl_ncut_seg::transformGraph(g, phi, 0.1f, 2.0f);
  auto length = [&](std::uint32_t p, std::uint32_t q) {
    for (std::uint32_t e = t.offsets[p]; e < t.offsets[p + 1]; ++e)
      if (t.targets[e] == q)
        return t.lengths[e];
    return -1.0f;
  };
  EXPECT_NEAR(length(2, 3), 0.1f, 1e-6f);               // level: shrunk
  EXPECT_NEAR(length(0, 3), 2.0f, 1e-6f);               // straight up: stretched
  EXPECT_NEAR(length(0, 1), 0.1f + 1.9f * 0.5f, 1e-6f); // half
  EXPECT_NEAR(length(1, 2), length(2, 1), 0.0f);        // symmetric
}

TEST(CadCore, FaceContactAnglesMeasureTheDihedralAngle) {
  // Two supernodes: a grid on z = 0 (x <= 0) and a grid that either continues it (flat) or
  // turns up into the plane x = 0 (a 90 degree ridge).
  for (const bool fold : {false, true}) {
    std::vector<float> xyz;
    std::vector<std::uint32_t> label;
    for (int i = -6; i <= 6; ++i)
      for (int j = 0; j < 8; ++j) {
        const float u = 0.1f * i, v = 0.1f * j;
        if (i <= 0 || !fold)
          xyz.insert(xyz.end(), {u, v, 0.0f});
        else
          xyz.insert(xyz.end(), {0.0f, v, u});
        label.push_back(i <= 0 ? 0 : 1);
      }
    const std::size_t n = label.size(), k = 8;
    std::vector<std::uint32_t> knn;
    for (std::size_t p = 0; p < n; ++p) {
      std::vector<std::pair<float, std::uint32_t>> d;
      for (std::size_t q = 0; q < n; ++q)
        if (q != p) {
          float s = 0;
          for (int c = 0; c < 3; ++c)
            s += (xyz[3 * p + c] - xyz[3 * q + c]) * (xyz[3 * p + c] - xyz[3 * q + c]);
          d.push_back({s, std::uint32_t(q)});
        }
      std::sort(d.begin(), d.end());
      for (std::size_t j = 0; j < k; ++j)
        knn.push_back(d[j].second);
    }
    const CsrGraph g = pcl_ncut_seg::buildSymmetricKnnGraph(xyz.data(), n, knn.data(), k);
    const auto angles = pcl_ncut_seg::faceContactAngles(g, xyz.data(), label);
    ASSERT_EQ(angles.size(), 1u);
    EXPECT_NEAR(angles.begin()->second, fold ? 90.0 : 0.0, 1.0) << (fold ? "fold" : "flat");
  }
}

} // namespace
