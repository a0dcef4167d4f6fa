/*
 * The geometry kernel (core/common/geometry.h): the point distance, the plane fit and its rule
 * for a degenerate neighbourhood; and the exact multi-source search
 * (core/graph/shortest_paths.h) against brute force.
 */
#include "core/common/geometry.h"
#include "core/graph/shortest_paths.h"

#include "support/graphs.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <random>
#include <vector>

using namespace pcl_ncut_seg;

namespace {

/// Points on the plane z = 0.5 x - 0.25 y + 3 (unit normal (0.5, -0.25, -1) / |.|), scattered.
std::vector<float> tiltedPlane(std::size_t n, double noise, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  std::vector<float> xyz;
  for (std::size_t i = 0; i < n; ++i) {
    const double x = u(rng), y = u(rng);
    xyz.push_back(static_cast<float>(x));
    xyz.push_back(static_cast<float>(y));
    xyz.push_back(static_cast<float>(0.5 * x - 0.25 * y + 3.0 + noise * u(rng)));
  }
  return xyz;
}

std::vector<std::uint32_t> allOf(const std::vector<float>& xyz) {
  std::vector<std::uint32_t> ids(xyz.size() / 3);
  for (std::uint32_t i = 0; i < ids.size(); ++i)
    ids[i] = i;
  return ids;
}

double alignment(const Eigen::Vector3d& normal) {
  return std::abs(normal.dot(Eigen::Vector3d(0.5, -0.25, -1.0).normalized()));
}

} // namespace

TEST(GeometryKernel, PointDistanceInFloatAndDouble) {
  const std::vector<float> xyz = {0.f, 0.f, 0.f, 3.f, 4.f, 12.f};
  EXPECT_EQ(pointDistance(xyz.data(), 0, 1), 13.0f);
  EXPECT_EQ(pointDistance<double>(xyz.data(), 1, 0), 13.0);
  EXPECT_EQ(pointDistance(xyz.data(), 1, 1), 0.0f);
}

TEST(GeometryKernel, BothScattersAndBothSolversFindThePlane) {
  const std::vector<float> xyz = tiltedPlane(200, 0.0, 1);
  const std::vector<std::uint32_t> ids = allOf(xyz);
  const Scatter centred = centredScatter(xyz.data(), ids);
  ShiftedMoments<double> moments(&xyz[0]);
  for (std::uint32_t v : ids)
    moments.add(&xyz[3 * v]);
  const Scatter shifted = moments.scatter(MeanProduct::kRowFirst);
  EXPECT_EQ(centred.count, 200.0);
  EXPECT_LT((centred.centroid - shifted.centroid).norm(), 1e-9);
  for (const Scatter* s : {&centred, &shifted})
    for (EigenSolve solve : {EigenSolve::kClosedForm, EigenSolve::kIterative}) {
      const std::optional<Plane> plane = fitPlane(*s, kNotCollinearDouble, solve);
      ASSERT_TRUE(plane);
      EXPECT_NEAR(plane->normal.norm(), 1.0, 1e-12);
      EXPECT_GT(alignment(plane->normal), 1.0 - 1e-9);
      EXPECT_LE(plane->lambda[0], plane->lambda[1]);
      EXPECT_LE(plane->lambda[1], plane->lambda[2]);
      EXPECT_LT(plane->lambda[0], 1e-9 * plane->lambda[2]); // the points lie on it
    }
}

TEST(GeometryKernel, FloatMomentsFarFromTheOrigin) {
  // Moments about the first point keep float sums usable where the coordinates are large.
  std::vector<float> xyz = tiltedPlane(50, 0.01, 2);
  for (std::size_t i = 0; i < xyz.size(); i += 3)
    xyz[i] += 1000.0f;
  ShiftedMoments<float> moments(&xyz[0]);
  for (std::uint32_t v : allOf(xyz))
    moments.add(&xyz[3 * v]);
  for (MeanProduct order : {MeanProduct::kRowFirst, MeanProduct::kColumnFirst}) {
    const std::optional<Plane> plane =
        fitPlane(moments.scatter(order), kNotCollinearFloat, EigenSolve::kClosedForm);
    ASSERT_TRUE(plane);
    EXPECT_GT(alignment(plane->normal), 0.99);
  }
}

TEST(GeometryKernel, DegenerateNeighbourhoodsHaveNoPlane) {
  const std::vector<float> two = {0.f, 0.f, 0.f, 1.f, 1.f, 1.f};
  EXPECT_FALSE(fitPlane(centredScatter(two.data(), allOf(two)), kAnyPlane, EigenSolve::kIterative));
  const std::vector<float> coincident = {1.f, 2.f, 3.f, 1.f, 2.f, 3.f,
                                         1.f, 2.f, 3.f, 1.f, 2.f, 3.f};
  for (EigenSolve solve : {EigenSolve::kClosedForm, EigenSolve::kIterative})
    EXPECT_FALSE(fitPlane(centredScatter(coincident.data(), allOf(coincident)), kAnyPlane, solve));
  std::vector<float> line;
  for (int i = 0; i < 10; ++i)
    for (float c : {1.0f * i, 2.0f * i, -0.5f * i})
      line.push_back(c);
  for (EigenSolve solve : {EigenSolve::kClosedForm, EigenSolve::kIterative})
    EXPECT_FALSE(fitPlane(centredScatter(line.data(), allOf(line)), kNotCollinearDouble, solve));
}

TEST(GeometryKernel, FlatnessThresholdIsRelativeToTheLargestEigenvalue) {
  // A 10 x 0.01 strip: the middle eigenvalue is about 1e-6 of the largest.
  std::vector<float> strip;
  for (int i = 0; i <= 100; ++i)
    for (float w : {0.0f, 0.01f}) {
      strip.push_back(0.1f * static_cast<float>(i));
      strip.push_back(w);
      strip.push_back(0.0f);
    }
  const Scatter s = centredScatter(strip.data(), allOf(strip));
  EXPECT_TRUE(fitPlane(s, kNotCollinearDouble, EigenSolve::kIterative));
  EXPECT_FALSE(fitPlane(s, kFaceFlatness, EigenSolve::kIterative));
  // Scaling the points changes no decision.
  for (float& c : strip)
    c *= 1000.0f;
  const Scatter big = centredScatter(strip.data(), allOf(strip));
  EXPECT_TRUE(fitPlane(big, kNotCollinearDouble, EigenSolve::kIterative));
  EXPECT_FALSE(fitPlane(big, kFaceFlatness, EigenSolve::kIterative));
}

namespace {
/// Multi-source distances by Bellman-Ford in float (the least solution, whatever the order).
std::vector<float> bellmanFord(const CsrGraph& g, const std::vector<std::uint32_t>& sources) {
  std::vector<float> d(g.numVertices(), std::numeric_limits<float>::infinity());
  for (std::uint32_t s : sources)
    d[s] = 0.0f;
  for (bool changed = true; changed;) {
    changed = false;
    for (std::uint32_t p = 0; p < g.numVertices(); ++p)
      for (std::uint32_t e = g.offsets[p]; e < g.offsets[p + 1]; ++e)
        if (d[p] + g.lengths[e] < d[g.targets[e]]) {
          d[g.targets[e]] = d[p] + g.lengths[e];
          changed = true;
        }
  }
  return d;
}

CsrGraph randomGraph(std::size_t n, unsigned seed, bool integer_lengths) {
  std::mt19937 rng(seed);
  std::uniform_int_distribution<int> vertex(0, static_cast<int>(n) - 1), small(1, 3);
  std::uniform_real_distribution<float> length(0.0f, 2.0f);
  std::vector<std::tuple<int, int, float>> edges;
  for (std::size_t i = 0; i < 3 * n; ++i) {
    const int a = vertex(rng), b = vertex(rng);
    if (a != b)
      edges.emplace_back(a, b, integer_lengths ? static_cast<float>(small(rng)) : length(rng));
  }
  return test::graphFromEdges(n, edges);
}
} // namespace

TEST(MultiSourceDijkstra, DistancesAreTheLeastSolution) {
  for (unsigned seed = 1; seed <= 5; ++seed) {
    const CsrGraph g = randomGraph(300, seed, false);
    const std::vector<std::uint32_t> sources = {3, 17, 250};
    std::vector<float> dist(g.numVertices(), std::numeric_limits<float>::infinity());
    for (std::uint32_t s : sources)
      dist[s] = 0.0f;
    std::vector<std::uint32_t> touched;
    multiSourceDijkstra(g, sources, dist.data(), AnyEdge(), ExpandAll(), nullptr, &touched);
    EXPECT_EQ(dist, bellmanFord(g, sources));
    std::size_t reached = 0;
    for (float d : dist)
      reached += d < std::numeric_limits<float>::infinity();
    EXPECT_EQ(touched.size() + sources.size(), reached);
  }
}

TEST(MultiSourceDijkstra, EachVertexTakesItsNearestSourceTheLowestOnTies) {
  // Integer lengths: many vertices are equally near two sources.
  const CsrGraph g = randomGraph(200, 7, true);
  const std::vector<std::uint32_t> sources = {150, 5, 80}; // labels 0, 1, 2 in this order
  std::vector<float> dist(g.numVertices(), std::numeric_limits<float>::infinity());
  std::vector<std::uint32_t> owner(g.numVertices(), std::numeric_limits<std::uint32_t>::max());
  for (std::uint32_t i = 0; i < sources.size(); ++i) {
    dist[sources[i]] = 0.0f;
    owner[sources[i]] = i;
  }
  multiSourceDijkstra(g, sources, dist.data(), AnyEdge(), ExpandAll(), owner.data());
  std::vector<std::vector<float>> from(sources.size());
  for (std::size_t i = 0; i < sources.size(); ++i)
    from[i] = bellmanFord(g, {sources[i]});
  std::size_t ties = 0;
  for (std::uint32_t v = 0; v < g.numVertices(); ++v) {
    if (!(dist[v] < std::numeric_limits<float>::infinity()))
      continue;
    std::uint32_t best = 0;
    for (std::uint32_t i = 1; i < sources.size(); ++i)
      if (from[i][v] < from[best][v])
        best = i;
    for (std::uint32_t i = best + 1; i < sources.size(); ++i)
      ties += from[i][v] == from[best][v];
    EXPECT_EQ(owner[v], best) << "vertex " << v;
    EXPECT_EQ(dist[v], from[best][v]);
  }
  EXPECT_GT(ties, 0u);
}

TEST(MultiSourceDijkstra, MaskBoundAndStop) {
  // A path 0 - 1 - ... - 9 with unit edges.
  std::vector<std::tuple<int, int, float>> edges;
  for (int i = 0; i + 1 < 10; ++i)
    edges.emplace_back(i, i + 1, 1.0f);
  const CsrGraph g = test::graphFromEdges(10, edges);
  const float inf = std::numeric_limits<float>::infinity();
  // Bounded: no vertex beyond distance 3 is reached.
  std::vector<float> dist(10, inf);
  dist[0] = 0.0f;
  std::vector<std::uint32_t> order;
  auto record = [&](std::uint32_t p, float) {
    order.push_back(p);
    return Settle::kExpand;
  };
  multiSourceDijkstra(
      g, {0}, dist.data(), [](std::uint32_t, std::uint32_t, float d) { return d <= 3.0f; }, record);
  EXPECT_EQ(order, (std::vector<std::uint32_t>{0, 1, 2, 3}));
  EXPECT_EQ(dist[4], inf);
  // Masked: vertex 5 is a wall.
  std::fill(dist.begin(), dist.end(), inf);
  dist[9] = 0.0f;
  multiSourceDijkstra(
      g, {9}, dist.data(), [](std::uint32_t, std::uint32_t q, float) { return q != 5; },
      ExpandAll());
  EXPECT_EQ(dist[6], 3.0f);
  EXPECT_EQ(dist[4], inf);
  // Stopped at the third vertex settled: it is not expanded.
  std::fill(dist.begin(), dist.end(), inf);
  dist[0] = 0.0f;
  order.clear();
  multiSourceDijkstra(g, {0}, dist.data(), AnyEdge(), [&](std::uint32_t p, float) {
    order.push_back(p);
    return order.size() == 3 ? Settle::kStop : Settle::kExpand;
  });
  EXPECT_EQ(order, (std::vector<std::uint32_t>{0, 1, 2}));
  EXPECT_EQ(dist[3], inf);
}
