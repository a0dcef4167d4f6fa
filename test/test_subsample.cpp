/*
 * The analysis' resolution (core/graph/subsample.h, graph.max_points): a dense cloud is analysed on
 * an even subset of its points (one per cube of a grid), and every other point takes its nearest
 * analysed point's segment.
 */
#include "core/graph/subsample.h"
#include "core/pipeline/pipeline.h"
#include <pcl_ncut_seg/supernode_ncut_segmentation.h>

#include <shapes/shapes.h>

#include <gtest/gtest.h>

#include <algorithm>
#include <map>
#include <numeric>
#include <random>
#include <set>
#include <tuple>

using namespace pcl_ncut_seg;

namespace {

using Position = std::tuple<float, float, float>;

std::vector<float> toArray(const pcl::PointCloud<pcl::PointXYZ>& cloud) {
  std::vector<float> xyz;
  for (const auto& p : cloud)
    xyz.insert(xyz.end(), {p.x, p.y, p.z});
  return xyz;
}

Position at(const std::vector<float>& xyz, std::size_t i) {
  return {xyz[3 * i], xyz[3 * i + 1], xyz[3 * i + 2]};
}

/// The indices of the points evenSubset() keeps, ascending.
std::vector<std::size_t> evenIndices(const std::vector<float>& xyz, std::size_t max_points) {
  const std::vector<char> keep = evenSubset(xyz.data(), xyz.size() / 3, max_points);
  std::vector<std::size_t> ids;
  for (std::size_t i = 0; i < keep.size(); ++i)
    if (keep[i])
      ids.push_back(i);
  return ids;
}

double squaredDistance(const std::vector<float>& xyz, std::size_t a, std::size_t b) {
  double s = 0;
  for (int d = 0; d < 3; ++d)
    s += (xyz[3 * a + d] - xyz[3 * b + d]) * double(xyz[3 * a + d] - xyz[3 * b + d]);
  return s;
}

} // namespace

TEST(Subsample, EvenSubsetKeepsThePointNearestTheCentreOfEachOccupiedCube) {
  const auto shape = test::makeQuadruped(6000, 5);
  const std::vector<float> xyz = toArray(*shape.cloud);
  const std::size_t n = xyz.size() / 3, max_points = 1500;
  double edge = 0.0;
  const std::vector<char> keep = evenSubset(xyz.data(), n, max_points, &edge);
  ASSERT_GT(edge, 0.0);
  float lo[3] = {xyz[0], xyz[1], xyz[2]};
  for (std::size_t i = 0; i < n; ++i)
    for (int d = 0; d < 3; ++d)
      lo[d] = std::min(lo[d], xyz[3 * i + d]);
  // Brute force: per cube, its points; the kept one is the nearest to the centre.
  std::map<std::tuple<long, long, long>, std::vector<std::size_t>> cubes;
  for (std::size_t i = 0; i < n; ++i)
    cubes[{static_cast<long>((xyz[3 * i] - lo[0]) / edge),
           static_cast<long>((xyz[3 * i + 1] - lo[1]) / edge),
           static_cast<long>((xyz[3 * i + 2] - lo[2]) / edge)}]
        .push_back(i);
  EXPECT_LE(cubes.size(), max_points);
  EXPECT_GE(cubes.size(), 0.97 * max_points);
  for (const auto& [cube, members] : cubes) {
    std::size_t kept = 0, nearest = members[0];
    double best = 1e300;
    for (std::size_t i : members) {
      kept += keep[i];
      double s = 0;
      for (int d = 0; d < 3; ++d) {
        const long c = d == 0 ? std::get<0>(cube) : d == 1 ? std::get<1>(cube) : std::get<2>(cube);
        const double centre = (c + 0.5) * edge + lo[d];
        s += (xyz[3 * i + d] - centre) * (xyz[3 * i + d] - centre);
      }
      if (s < best) {
        best = s;
        nearest = i;
      }
    }
    EXPECT_EQ(kept, 1u);
    EXPECT_TRUE(keep[nearest]);
  }
}

TEST(Subsample, NothingHappensAtOrBelowTheResolution) {
  const auto shape = test::makeDumbbell(800, 3);
  const std::vector<float> xyz = toArray(*shape.cloud);
  const PreparedPoints plain = preparePoints(xyz);
  for (const std::size_t max_points : {std::size_t(0), xyz.size() / 3, std::size_t(5000)}) {
    const PreparedPoints prepared = prepareAtResolution(xyz, max_points, 1);
    EXPECT_EQ(prepared.set.xyz, plain.set.xyz);
    EXPECT_EQ(prepared.point, plain.point);
    EXPECT_TRUE(prepared.copies.empty());
  }
}

TEST(Subsample, KeepsTheEvenSubsetAndGivesEveryOtherPointItsNearestKeptPoint) {
  const auto shape = test::makeHand(3000, 7);
  std::vector<float> xyz = toArray(*shape.cloud);
  const std::size_t n = xyz.size() / 3;
  // Two copies of point 5, to check that copies of a dropped point follow it.
  xyz.insert(xyz.end(), {xyz[15], xyz[16], xyz[17]});
  const std::size_t max_points = 700;
  const PreparedPoints all = preparePoints(xyz);
  ASSERT_EQ(all.point.size(), n);
  const PreparedPoints prepared = prepareAtResolution(xyz, max_points, 2);
  const std::size_t w = prepared.point.size(); // the kept points
  ASSERT_LE(w, max_points);
  // The kept vertices come in the order they have among all the points.
  std::vector<std::uint32_t> kept_in_order;
  for (const std::uint32_t p : all.point)
    if (std::find(prepared.point.begin(), prepared.point.end(), p) != prepared.point.end())
      kept_in_order.push_back(p);
  EXPECT_EQ(kept_in_order, prepared.point);
  ASSERT_EQ(prepared.point.size(), w);
  ASSERT_EQ(prepared.set.xyz.size(), 3 * w);
  ASSERT_EQ(prepared.raw.size(), 3 * w);

  // The kept points are the even subset; their raw positions are the input's.
  const std::vector<std::size_t> expected =
      evenIndices(std::vector<float>(xyz.begin(), xyz.begin() + 3 * static_cast<std::ptrdiff_t>(n)),
                  max_points);
  std::vector<std::size_t> kept(prepared.point.begin(), prepared.point.end());
  std::sort(kept.begin(), kept.end());
  EXPECT_EQ(kept, expected);
  for (std::size_t v = 0; v < w; ++v)
    EXPECT_EQ(at(prepared.raw, v), at(xyz, prepared.point[v]));

  // Every input point is a kept vertex or a copy of one, once; a dropped point's vertex is its
  // nearest kept point.
  std::vector<int> seen(n + 1, 0);
  for (std::size_t v = 0; v < w; ++v)
    ++seen[prepared.point[v]];
  for (const auto& [copy, vertex] : prepared.copies) {
    ASSERT_LT(vertex, w);
    ++seen[copy];
    double best = 1e300;
    for (std::size_t u = 0; u < w; ++u) {
      double s = 0;
      for (int d = 0; d < 3; ++d)
        s += (prepared.raw[3 * u + d] - xyz[3 * copy + d]) *
             double(prepared.raw[3 * u + d] - xyz[3 * copy + d]);
      best = std::min(best, s);
    }
    double mine = 0;
    for (int d = 0; d < 3; ++d)
      mine += (prepared.raw[3 * vertex + d] - xyz[3 * copy + d]) *
              double(prepared.raw[3 * vertex + d] - xyz[3 * copy + d]);
    EXPECT_EQ(mine, best) << "point " << copy;
  }
  EXPECT_TRUE(std::all_of(seen.begin(), seen.end(), [](int s) { return s == 1; }));

  // The ranks are dense and keep the input's order; the points are centred on their centroid.
  std::vector<std::uint32_t> ranks = prepared.set.order;
  std::sort(ranks.begin(), ranks.end());
  for (std::size_t r = 0; r < w; ++r)
    ASSERT_EQ(ranks[r], r);
  for (std::size_t v = 0; v + 1 < w; ++v)
    for (std::size_t u = v + 1; u < std::min(w, v + 20); ++u)
      EXPECT_EQ(prepared.set.order[v] < prepared.set.order[u],
                prepared.point[v] < prepared.point[u]);
  for (int d = 0; d < 3; ++d) {
    double mean = 0;
    for (std::size_t v = 0; v < w; ++v)
      mean += prepared.set.xyz[3 * v + d];
    EXPECT_NEAR(mean / w, 0.0, 1e-5);
  }
}

TEST(Subsample, TheSubsetDoesNotDependOnTheOrderOfThePoints) {
  const auto shape = test::makeQuadruped(2500, 2);
  const std::vector<float> xyz = toArray(*shape.cloud);
  const std::size_t n = xyz.size() / 3;
  std::vector<std::size_t> perm(n);
  std::iota(perm.begin(), perm.end(), 0);
  std::shuffle(perm.begin(), perm.end(), std::mt19937_64(11));
  std::vector<float> shuffled;
  for (std::size_t i : perm)
    shuffled.insert(shuffled.end(), {xyz[3 * i], xyz[3 * i + 1], xyz[3 * i + 2]});
  auto keptPositions = [](const std::vector<float>& points) {
    const PreparedPoints prepared = prepareAtResolution(points, 900, 1);
    std::set<Position> kept;
    for (std::size_t v = 0; v < prepared.point.size(); ++v)
      kept.insert(at(prepared.raw, v));
    return kept;
  };
  const auto a = keptPositions(xyz), b = keptPositions(shuffled);
  EXPECT_GE(a.size(), 0.97 * 900);
  EXPECT_LE(a.size(), 900u);
  EXPECT_EQ(a, b);
}

TEST(Subsample, ADenseCloudIsSegmentedAsItsSubsetWithTheOthersTakingTheNearestLabel) {
  const auto shape = test::makeHand(6000, 4);
  const std::vector<float> xyz = toArray(*shape.cloud);
  const std::size_t n = xyz.size() / 3, max_points = 2000;
  Parameters params;
  params.graph.max_points = static_cast<int>(max_points);
  const std::vector<std::uint32_t> dense = segmentPoints(xyz.data(), n, params);
  ASSERT_EQ(dense.size(), n);

  const std::vector<std::size_t> kept = evenIndices(xyz, max_points);
  std::vector<float> subset;
  for (std::size_t i : kept)
    subset.insert(subset.end(), {xyz[3 * i], xyz[3 * i + 1], xyz[3 * i + 2]});
  params.graph.max_points.reset();
  const std::vector<std::uint32_t> alone = segmentPoints(subset.data(), kept.size(), params);
  ASSERT_EQ(alone.size(), kept.size());
  EXPECT_GE(*std::max_element(alone.begin(), alone.end()), 3u); // the hand has parts
  // The same partition of the kept points (numbering may differ: the dense cloud's first
  // point of a segment can be a dropped one).
  std::map<std::uint32_t, std::uint32_t> dense_to_alone;
  for (std::size_t j = 0; j < kept.size(); ++j) {
    const auto [it, inserted] = dense_to_alone.emplace(dense[kept[j]], alone[j]);
    EXPECT_EQ(it->second, alone[j]) << "kept point " << kept[j];
  }
  std::set<std::uint32_t> images;
  for (const auto& m : dense_to_alone)
    images.insert(m.second);
  EXPECT_EQ(images.size(), dense_to_alone.size());
  // Every other point carries the label of its nearest kept point.
  std::vector<char> is_kept(n, 0);
  for (std::size_t i : kept)
    is_kept[i] = 1;
  for (std::size_t i = 0; i < n; i += 7) {
    if (is_kept[i])
      continue;
    std::size_t nearest = kept[0];
    for (std::size_t j : kept)
      if (squaredDistance(xyz, i, j) < squaredDistance(xyz, i, nearest))
        nearest = j;
    EXPECT_EQ(dense[i], dense[nearest]) << "point " << i;
  }
}

TEST(Subsample, ThePclClassAnalysesAtMostMaxPointsAndLabelsEveryPoint) {
  const auto shape = test::makeQuadruped(5000, 9);
  pcl::SupernodeNCutSegmentation<pcl::PointXYZ> seg;
  EXPECT_EQ(seg.getMaxPoints(), 60000); // the default
  seg.setMaxPoints(1500);
  seg.setNumberOfThreads(1);
  seg.setInputCloud(shape.cloud);
  std::vector<pcl::PointIndices> one;
  seg.extract(one);
  ASSERT_FALSE(one.empty());
  EXPECT_GT(seg.getNumberOfSupernodes(false), 0u);
  std::size_t labelled = 0;
  for (const auto& s : one)
    labelled += s.indices.size();
  EXPECT_EQ(labelled, shape.cloud->size());

  seg.setNumberOfThreads(2); // the same labels on two threads
  std::vector<pcl::PointIndices> two;
  seg.extract(two);
  ASSERT_EQ(one.size(), two.size());
  for (std::size_t s = 0; s < one.size(); ++s)
    EXPECT_EQ(one[s].indices, two[s].indices);
}

TEST(Subsample, TheSetterKeepsItsOldValueOnABadOne) {
  pcl::SupernodeNCutSegmentation<pcl::PointXYZ> seg;
  seg.setMaxPoints(20000);
  for (int bad : {0, -1, 1, 99})
    seg.setMaxPoints(bad);
  EXPECT_EQ(seg.getMaxPoints(), 20000);
  seg.setMaxPoints(std::nullopt); // off: every point
  EXPECT_EQ(seg.getMaxPoints(), std::nullopt);
}
