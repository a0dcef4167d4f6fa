/*
 * The surface's local thickness from medial balls (core/cut/thickness.h) and its place in
 * eq. (9) (SimilarityParams::thickness).
 */
#include "core/cut/supernode_graph.h"
#include "core/cut/thickness.h"
#include <support/graphs.h>

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numeric>
#include <random>
#include <vector>

using namespace pcl_ncut_seg;

namespace {

struct Oriented {
  std::vector<float> xyz, normals;
  void add(float x, float y, float z, float nx, float ny, float nz) {
    xyz.insert(xyz.end(), {x, y, z});
    normals.insert(normals.end(), {nx, ny, nz});
  }
  std::size_t size() const { return xyz.size() / 3; }
};

/// n points spread evenly over a sphere of radius r (a Fibonacci lattice), normals outward.
Oriented sphere(std::size_t n, float r) {
  Oriented s;
  const double golden = M_PI * (3.0 - std::sqrt(5.0));
  for (std::size_t i = 0; i < n; ++i) {
    const double z = 1.0 - 2.0 * (static_cast<double>(i) + 0.5) / static_cast<double>(n);
    const double rho = std::sqrt(1.0 - z * z), phi = golden * static_cast<double>(i);
    const auto x = static_cast<float>(rho * std::cos(phi)),
               y = static_cast<float>(rho * std::sin(phi));
    s.add(r * x, r * y, r * static_cast<float>(z), x, y, static_cast<float>(z));
  }
  return s;
}

/// A closed slab [-a, a]^2 x [-t/2, t/2] sampled on a grid of step h, normals outward.
Oriented slab(float a, float t, float h) {
  Oriented s;
  const int m = static_cast<int>(std::round(2 * a / h)), mt = static_cast<int>(std::round(t / h));
  for (int i = 0; i <= m; ++i)
    for (int j = 0; j <= m; ++j) {
      const float x = -a + h * i, y = -a + h * j;
      s.add(x, y, t / 2, 0, 0, 1);
      s.add(x, y, -t / 2, 0, 0, -1);
    }
  for (int i = 0; i <= m; ++i)
    for (int k = 1; k < mt; ++k) {
      const float u = -a + h * i, z = -t / 2 + h * k;
      s.add(u, -a, z, 0, -1, 0);
      s.add(u, a, z, 0, 1, 0);
      if (i > 0 && i < m) { // the corners' columns are the faces' above
        s.add(-a, u, z, -1, 0, 0);
        s.add(a, u, z, 1, 0, 0);
      }
    }
  return s;
}

std::vector<float> finite(const std::vector<float>& v) {
  std::vector<float> f;
  for (float x : v)
    if (std::isfinite(x))
      f.push_back(x);
  return f;
}

} // namespace

TEST(Thickness, ASpheresMedialBallIsTheSphere) {
  const Oriented s = sphere(3000, 2.0f);
  const std::vector<float> r = finite(medialRadii(s.xyz.data(), s.size(), s.normals, 1));
  ASSERT_GT(r.size(), s.size() * 9 / 10);
  for (float x : r)
    EXPECT_NEAR(x, 2.0f, 0.1f);
}

TEST(Thickness, ASlabsMedialBallsAreHalfItsThickness) {
  const Oriented s = slab(1.0f, 0.2f, 0.02f);
  const std::vector<float> r = medialRadii(s.xyz.data(), s.size(), s.normals, 1);
  std::vector<float> faces; // points of the two large faces, away from the rim
  for (std::size_t i = 0; i < s.size(); ++i)
    if (std::abs(s.normals[3 * i + 2]) > 0.5f && std::abs(s.xyz[3 * i]) < 0.7f &&
        std::abs(s.xyz[3 * i + 1]) < 0.7f && std::isfinite(r[i]))
      faces.push_back(r[i]);
  ASSERT_GT(faces.size(), 100u);
  std::nth_element(faces.begin(), faces.begin() + faces.size() / 2, faces.end());
  EXPECT_NEAR(faces[faces.size() / 2], 0.1f, 0.02f);
}

TEST(Thickness, AnOpenSheetHasNone) {
  Oriented s; // one side of a sheet: nothing behind it
  for (int i = 0; i < 60; ++i)
    for (int j = 0; j < 60; ++j)
      s.add(0.01f * i, 0.01f * j, 0.0f, 0, 0, 1);
  const std::vector<float> r = medialRadii(s.xyz.data(), s.size(), s.normals, 1);
  EXPECT_TRUE(finite(r).empty());
}

TEST(Thickness, ZeroNormalsAndTinyCloudsGiveNaNNotACrash) {
  Oriented s = sphere(50, 1.0f);
  std::fill(s.normals.begin(), s.normals.begin() + 30, 0.0f); // ten points with no normal
  const std::vector<float> r = medialRadii(s.xyz.data(), s.size(), s.normals, 1);
  for (int i = 0; i < 10; ++i)
    EXPECT_TRUE(std::isnan(r[i]));
  EXPECT_TRUE(std::isnan(medialRadii(s.xyz.data(), 1, s.normals, 1)[0]));
  EXPECT_TRUE(medialRadii(s.xyz.data(), 0, s.normals, 1).empty());
}

TEST(Thickness, NeitherThreadsNorPointOrderChangeIt) {
  // More points than probes: the even subset must not depend on the order either.
  const Oriented s = slab(1.0f, 0.3f, 0.01f);
  ASSERT_GT(s.size(), 8192u);
  const std::vector<float> one = medialRadii(s.xyz.data(), s.size(), s.normals, 1);
  const std::vector<float> two = medialRadii(s.xyz.data(), s.size(), s.normals, 2);
  ASSERT_EQ(one.size(), two.size());
  for (std::size_t i = 0; i < one.size(); ++i)
    EXPECT_TRUE((std::isnan(one[i]) && std::isnan(two[i])) || one[i] == two[i]) << i;
  EXPECT_GT(finite(one).size(), 1000u);
  std::vector<std::size_t> perm(s.size());
  std::iota(perm.begin(), perm.end(), 0);
  std::shuffle(perm.begin(), perm.end(), std::mt19937(7));
  Oriented shuffled;
  for (std::size_t i : perm)
    shuffled.add(s.xyz[3 * i], s.xyz[3 * i + 1], s.xyz[3 * i + 2], s.normals[3 * i],
                 s.normals[3 * i + 1], s.normals[3 * i + 2]);
  const std::vector<float> other = medialRadii(shuffled.xyz.data(), s.size(), shuffled.normals, 2);
  for (std::size_t j = 0; j < perm.size(); ++j) {
    const float a = one[perm[j]], b = other[j];
    EXPECT_TRUE((std::isnan(a) && std::isnan(b)) || a == b) << j;
  }
}

TEST(Thickness, ASupernodesThicknessIsItsMedian) {
  const float nan = std::nanf("");
  const std::vector<float> t = supernodeThickness({1, 5, 2, nan, 7, nan}, {0, 0, 0, 1, 1, 2}, 3);
  ASSERT_EQ(t.size(), 3u);
  EXPECT_EQ(t[0], 2.0f);
  EXPECT_EQ(t[1], 7.0f);
  EXPECT_TRUE(std::isnan(t[2]));
}

TEST(Thickness, AThinnerNeighbourMeetsAtAWeakerEdge) {
  // Fig. 6's three supernodes; m0 - m2 joined at a saddle, with d2 > 0 in eq. (9).
  FeatureStats st;
  st.height = {1, 2, 4};
  st.area = {2, 2, 8};
  st.width = {2, 1, 2};
  const Connectivity conn = {
      {{0, 0}, 4.0}, {{1, 1}, 2.0}, {{2, 2}, 8.0}, {{0, 2}, 1.0}, {{1, 2}, 3.0}};
  SimilarityParams p;
  p.adjacency = Adjacency::Saddles;
  const Supernodes sn = test::threeSupernodes();
  const auto weight = [&](const std::vector<float>* thickness) {
    return test::edgeWeight(buildSupernodeGraph(sn, st, conn, p, nullptr, thickness), 3, 5);
  };
  const std::vector<float> even = {1, 1, 1}, thin = {1, 1, 0.1f}, unknown = {1, 1, NAN};
  EXPECT_GT(weight(&even), 0.0);
  EXPECT_LT(weight(&thin), weight(&even));
  EXPECT_EQ(weight(&even), weight(nullptr));    // equal thickness: eq. (9) as without the cue
  EXPECT_EQ(weight(&unknown), weight(nullptr)); // an open view's supernodes: eq. (9) unchanged
  p.thickness = false;
  EXPECT_EQ(weight(&thin), weight(nullptr));
}
