/*
 * Open views: the segments only the rim cut apart
 * (core/views/rim_merge.h, SupernodeNCutSegmentation::setRimMerge).
 */
#include "core/centrality/centrality.h"
#include "core/graph/csr_graph.h"
#include "core/pipeline/cut_stages.h"
#include "core/supernodes/refinement.h"
#include "core/supernodes/supernodes.h"
#include "core/views/rim_merge.h"
#include <pcl_ncut_seg/supernode_ncut_segmentation.h>

#include "support/knn_graph.h"
#include <shapes/shapes.h>

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <map>
#include <set>

using namespace pcl_ncut_seg;

namespace {

/// A flat sheet of w x h points on a unit grid (z = 0), row by row.
std::vector<float> sheet(std::size_t w, std::size_t h) {
  std::vector<float> xyz;
  for (std::size_t y = 0; y < h; ++y)
    for (std::size_t x = 0; x < w; ++x) {
      xyz.push_back(static_cast<float>(x));
      xyz.push_back(static_cast<float>(y));
      xyz.push_back(0.0f);
    }
  return xyz;
}

/// Per point of sheet(w, h), 1 on its outer ring: the rim of a view of the sheet.
std::vector<std::uint8_t> outerRing(std::size_t w, std::size_t h) {
  std::vector<std::uint8_t> rim(w * h, 0);
  for (std::size_t y = 0; y < h; ++y)
    for (std::size_t x = 0; x < w; ++x)
      rim[y * w + x] = x == 0 || y == 0 || x + 1 == w || y + 1 == h;
  return rim;
}

/// A disc in the middle of the sheet and the ring around it cut into four quadrants, the
/// pieces a view's rim cuts a flat region into.
std::vector<std::uint32_t> discAndQuadrants(std::size_t w, std::size_t h) {
  std::vector<std::uint32_t> segment(w * h);
  const double cx = 0.5 * (w - 1), cy = 0.5 * (h - 1);
  for (std::size_t y = 0; y < h; ++y)
    for (std::size_t x = 0; x < w; ++x) {
      const double dx = x - cx, dy = y - cy;
      segment[y * w + x] = std::hypot(dx, dy) < 0.3 * w ? 0u : 1u + (dx > 0) + 2u * (dy > 0);
    }
  return segment;
}

std::size_t countLabels(const std::vector<std::uint32_t>& segment) {
  return std::set<std::uint32_t>(segment.begin(), segment.end()).size();
}

} // namespace

namespace {

/// Each side's band in the tests on unit grids: 3 spacings.
constexpr double kBand = 3.0;

/// Unit normals (0, 0, 1) for n points.
std::vector<float> upNormals(std::size_t n) {
  std::vector<float> normals(3 * n, 0.0f);
  for (std::size_t p = 0; p < n; ++p)
    normals[3 * p + 2] = 1.0f;
  return normals;
}

/// sheet(w, h) folded along x = (w - 1) / 2 by z = slope |x - (w - 1) / 2| (a valley for
/// slope > 0, a ridge for slope < 0), with the normals of its two faces, pointing up; the
/// faces are segments 0 and 1.
struct Fold {
  std::vector<float> xyz, normals;
  std::vector<std::uint32_t> segment;
};
Fold fold(std::size_t w, std::size_t h, double slope) {
  Fold f;
  f.xyz = sheet(w, h);
  const double cx = 0.5 * (w - 1), len = std::sqrt(1.0 + slope * slope);
  for (std::size_t p = 0; p < w * h; ++p) {
    const double dx = f.xyz[3 * p] - cx, sign = dx < 0 ? -1.0 : 1.0;
    f.xyz[3 * p + 2] = static_cast<float>(slope * std::abs(dx));
    f.normals.insert(f.normals.end(), {static_cast<float>(-sign * slope / len), 0.0f,
                                       static_cast<float>(1.0 / len)});
    f.segment.push_back(dx < 0 ? 0u : 1u);
  }
  return f;
}

} // namespace

TEST(RimMerge, MergesTheFlatPiecesOfAnOpenSheet) {
  const std::size_t w = 40, h = 30;
  const std::vector<float> xyz = sheet(w, h);
  const CsrGraph graph = test::kdTreeKnnGraph(xyz, 8);
  std::vector<std::uint32_t> segment = discAndQuadrants(w, h);
  std::size_t t = 5;
  const std::vector<std::uint32_t> map =
      mergeAcrossRim(graph, outerRing(w, h), xyz, upNormals(w * h), 10.0, kBand, segment, t);
  EXPECT_EQ(t, 1u);
  EXPECT_EQ(countLabels(segment), 1u);
  ASSERT_EQ(map.size(), 5u);
  for (std::uint32_t s : map)
    EXPECT_EQ(s, 0u);
}

TEST(RimMerge, KeepsBoundariesAlongConcaveCreases) {
  // Each face 15 x 60: its boundary is wide for its size (a neck of about 2.3, no limb's).
  const std::size_t w = 30, h = 60;
  // A valley whose faces meet at 60 degrees from flat (slope tan 30): a crease; kept.
  Fold valley = fold(w, h, std::tan(30.0 * 3.14159265358979 / 180.0));
  std::size_t t = 2;
  const CsrGraph graph = test::kdTreeKnnGraph(valley.xyz, 8);
  EXPECT_TRUE(mergeAcrossRim(graph, outerRing(w, h), valley.xyz, valley.normals, 10.0, kBand,
                             valley.segment, t)
                  .empty());
  EXPECT_EQ(t, 2u);
  // Below the bound (70 degrees) the same valley is not a crease.
  EXPECT_EQ(mergeAcrossRim(graph, outerRing(w, h), valley.xyz, valley.normals, 70.0, kBand,
                           valley.segment, t)
                .size(),
            2u);
  EXPECT_EQ(t, 1u);
  // A ridge (convex) merges, and so does a valley of 6 degrees (slope tan 3).
  for (double degrees : {-30.0, 3.0}) {
    Fold f = fold(w, h, std::tan(degrees * 3.14159265358979 / 180.0));
    std::size_t two = 2;
    const CsrGraph g = test::kdTreeKnnGraph(f.xyz, 8);
    EXPECT_EQ(
        mergeAcrossRim(g, outerRing(w, h), f.xyz, f.normals, 10.0, kBand, f.segment, two).size(),
        2u)
        << degrees;
    EXPECT_EQ(two, 1u) << degrees;
  }
}

TEST(RimMerge, KeepsALimbOnTheRim) {
  // A 30 x 30 sheet with a strip 3 points wide and 20 long standing out of its top edge: a limb
  // with a narrow neck (3 / sqrt(3 x 20)), flat and reaching the rim like everything else.
  std::vector<float> xyz = sheet(30, 30);
  std::vector<std::uint32_t> segment(30 * 30, 0);
  std::vector<std::uint8_t> rim = outerRing(30, 30);
  for (int y = 30; y < 50; ++y)
    for (int x = 13; x < 16; ++x) {
      xyz.insert(xyz.end(), {float(x), float(y), 0.0f});
      segment.push_back(1);
      rim.push_back(1);
    }
  for (int x = 13; x < 16; ++x)
    rim[29 * 30 + x] = 0; // where the limb joins, the sheet goes on
  const CsrGraph graph = test::kdTreeKnnGraph(xyz, 8);
  std::size_t t = 2;
  EXPECT_TRUE(
      mergeAcrossRim(graph, rim, xyz, upNormals(xyz.size() / 3), 10.0, kBand, segment, t).empty());
  EXPECT_EQ(t, 2u);
}

TEST(RimMerge, NothingWithoutARim) {
  const std::size_t w = 40, h = 30;
  const std::vector<float> xyz = sheet(w, h);
  const CsrGraph graph = test::kdTreeKnnGraph(xyz, 8);
  std::vector<std::uint32_t> segment = discAndQuadrants(w, h);
  const std::vector<std::uint32_t> before = segment;
  std::size_t t = 5;
  const std::vector<std::uint8_t> none(w * h, 0);
  EXPECT_TRUE(mergeAcrossRim(graph, none, xyz, upNormals(w * h), 10.0, kBand, segment, t).empty());
  EXPECT_EQ(segment, before);
  // Sizes that do not match the graph: no merge, no crash.
  EXPECT_TRUE(mergeAcrossRim(graph, std::vector<std::uint8_t>(3, 1), xyz, upNormals(w * h), 10.0,
                             kBand, segment, t)
                  .empty());
  EXPECT_TRUE(
      mergeAcrossRim(graph, outerRing(w, h), xyz, upNormals(3), 10.0, kBand, segment, t).empty());
  EXPECT_EQ(t, 5u);
}

namespace {

/// What a depth camera sees of a flat disc (test::discView), noise drawn from seed 7.
pcl::PointCloud<pcl::PointXYZ>::Ptr discView() {
  return test::discView(7);
}

std::map<std::uint32_t, std::set<std::uint32_t>>
pieces(const std::vector<pcl::PointIndices>& merged, const std::vector<pcl::PointIndices>& unmerged,
       std::size_t cloud_size) {
  std::vector<std::uint32_t> before(cloud_size, kNone);
  for (std::size_t s = 0; s < unmerged.size(); ++s)
    for (int i : unmerged[s].indices)
      before[i] = static_cast<std::uint32_t>(s);
  std::map<std::uint32_t, std::set<std::uint32_t>> owner; // unmerged segment -> merged ones
  for (std::size_t s = 0; s < merged.size(); ++s)
    for (int i : merged[s].indices)
      owner[before[i]].insert(static_cast<std::uint32_t>(s));
  return owner;
}

/// The segments of a cloud with the rim merge (the default) and without it.
struct WithAndWithout {
  std::vector<pcl::PointIndices> merged, unmerged;
};
WithAndWithout segmentWithAndWithoutMerge(const pcl::PointCloud<pcl::PointXYZ>::Ptr& cloud) {
  WithAndWithout r;
  pcl::SupernodeNCutSegmentation<pcl::PointXYZ> seg;
  seg.setInputCloud(cloud);
  seg.setNumberOfThreads(2);
  seg.extract(r.merged);
  seg.setRimMerge(std::nullopt);
  seg.extract(r.unmerged);
  return r;
}

} // namespace

TEST(RimMerge, AnOrganizedViewOfADiscIsOneSegment) {
  const auto cloud = discView();
  const auto [merged, unmerged] = segmentWithAndWithoutMerge(cloud);
  // A flat disc is one part: the rim merge joins what the rim cut it into.
  EXPECT_GT(unmerged.size(), 1u);
  EXPECT_EQ(merged.size(), 1u);
  std::cout << "[ INFO     ] disc view: " << unmerged.size() << " segments without the rim merge, "
            << merged.size() << " with it\n";
  // The merge only joins whole segments: each unmerged segment lies in one merged segment.
  for (const auto& [segment, owners] : pieces(merged, unmerged, cloud->size())) {
    EXPECT_NE(segment, kNone);
    EXPECT_EQ(owners.size(), 1u) << "segment " << segment;
  }
}

TEST(RimMerge, AListOfAViewsPointsIsOneViewFromTheSensor) {
  // The same points as a plain list (no grid), seen from the sensor origin (0, 0, 0): one
  // view (core/views/single_view.h), whose rim the points show.
  const auto view = discView();
  auto list = std::make_shared<pcl::PointCloud<pcl::PointXYZ>>();
  for (const auto& p : *view)
    if (std::isfinite(p.x))
      list->push_back(p);
  const auto [merged, unmerged] = segmentWithAndWithoutMerge(list);
  std::cout << "[ INFO     ] disc view as a list: " << unmerged.size()
            << " segments without the rim merge, " << merged.size() << " with it\n";
  EXPECT_GT(unmerged.size(), 1u);
  EXPECT_EQ(merged.size(), 1u);
}

TEST(RimMerge, AWholeSurfaceIsNoView) {
  // A closed surface around the sensor origin has no rim: the merge changes nothing.
  const test::LabeledShape hand = test::makeHand(4000, 3);
  const auto [on, off] = segmentWithAndWithoutMerge(hand.cloud);
  ASSERT_EQ(on.size(), off.size());
  for (std::size_t s = 0; s < on.size(); ++s)
    EXPECT_EQ(on[s].indices, off[s].indices);
}

TEST(RimMerge, SetterKeepsTheOldValueOnABadOne) {
  pcl::SupernodeNCutSegmentation<pcl::PointXYZ> seg;
  EXPECT_EQ(seg.getRimMerge(), 10.0);
  seg.setRimMerge(-1.0);
  EXPECT_EQ(seg.getRimMerge(), 10.0);
  seg.setRimMerge(200.0);
  EXPECT_EQ(seg.getRimMerge(), 10.0);
  seg.setRimMerge(5.0);
  EXPECT_EQ(seg.getRimMerge(), 5.0);
  seg.setRimMerge(0.0);
  EXPECT_EQ(seg.getRimMerge(), 5.0);
  seg.setRimMerge(std::nullopt);
  EXPECT_EQ(seg.getRimMerge(), std::nullopt);
}

TEST(RimMerge, TheSameForAnyThreadCount) {
  const auto cloud = discView();
  std::vector<pcl::PointIndices> one, two;
  pcl::SupernodeNCutSegmentation<pcl::PointXYZ> seg;
  seg.setInputCloud(cloud);
  seg.setNumberOfThreads(1);
  seg.extract(one);
  pcl::SupernodeNCutSegmentation<pcl::PointXYZ> seg2;
  seg2.setInputCloud(cloud);
  seg2.setNumberOfThreads(2);
  seg2.extract(two);
  ASSERT_EQ(one.size(), two.size());
  for (std::size_t s = 0; s < one.size(); ++s)
    EXPECT_EQ(one[s].indices, two[s].indices);
}

namespace {
/// A valley of w x h units sampled on a grid of the given spacing, faces sloping up at
/// `degrees` on either side of x = w / 2, rounded by a parabola over |x - w / 2| < a; with
/// its normals (pointing up) and its two faces as segments 0 and 1.
Fold roundedValley(double w, double h, double spacing, double degrees, double a) {
  Fold f;
  const double slope = std::tan(degrees * 3.14159265358979 / 180.0), cx = 0.5 * w;
  const auto nx = static_cast<int>(std::lround(w / spacing)),
             ny = static_cast<int>(std::lround(h / spacing));
  for (int j = 0; j <= ny; ++j)
    for (int i = 0; i <= nx; ++i) {
      const double dx = i * spacing - cx, ax = std::abs(dx);
      const double z = ax < a ? slope * dx * dx / (2 * a) : slope * (ax - 0.5 * a);
      const double dz = ax < a ? slope * dx / a : (dx < 0 ? -slope : slope);
      const double len = std::sqrt(1 + dz * dz);
      f.xyz.insert(f.xyz.end(), {static_cast<float>(i * spacing), static_cast<float>(j * spacing),
                                 static_cast<float>(z)});
      f.normals.insert(f.normals.end(),
                       {static_cast<float>(-dz / len), 0.0f, static_cast<float>(1 / len)});
      f.segment.push_back(dx < 0 ? 0u : 1u);
    }
  return f;
}

std::vector<std::uint8_t> outerRingOf(const Fold& f, double w, double h) {
  std::vector<std::uint8_t> rim;
  for (std::size_t p = 0; p < f.segment.size(); ++p) {
    const double x = f.xyz[3 * p], y = f.xyz[3 * p + 1];
    rim.push_back(x < 1e-3 || y < 1e-3 || x > w - 1e-3 || y > h - 1e-3);
  }
  return rim;
}
} // namespace

TEST(RimMerge, MeasuresTheSameBandAtAnyDensity) {
  // Faces at 25 degrees (50 between them) rounded over 8 units: a crease at the scale of a
  // band of 8 units, flat within a few spacings of the boundary once the cloud is dense.
  const double w = 30, h = 60;
  for (double spacing : {1.0, 0.25}) {
    Fold f = roundedValley(w, h, spacing, 25.0, 4.0);
    const CsrGraph graph = test::kdTreeKnnGraph(f.xyz, 8);
    std::size_t t = 2;
    EXPECT_TRUE(
        mergeAcrossRim(graph, outerRingOf(f, w, h), f.xyz, f.normals, 10.0, 8.0, f.segment, t)
            .empty())
        << spacing;
    EXPECT_EQ(t, 2u) << spacing;
    if (spacing < 1.0) { // a band of 3 spacings sees only the rounding's bottom: merged
      EXPECT_EQ(mergeAcrossRim(graph, outerRingOf(f, w, h), f.xyz, f.normals, 10.0, 3 * spacing,
                               f.segment, t)
                    .size(),
                2u);
      EXPECT_EQ(t, 1u);
    }
  }
}

TEST(RimMerge, TheStageMeasuresABandOfTheSameLengthAtAnyDensity) {
  // What rimStage() hands mergeAcrossRim(): a 24 x 16 sheet at spacings 0.5, 0.25 and 0.125
  // (1,600 to 25,000 points, a view's), r(p) from its own centrality as the pipeline has them.
  std::vector<double> widths;
  for (double spacing : {0.5, 0.25, 0.125}) {
    const auto w = static_cast<std::size_t>(std::lround(24 / spacing)) + 1,
               h = static_cast<std::size_t>(std::lround(16 / spacing)) + 1;
    std::vector<float> xyz = sheet(w, h);
    for (float& c : xyz)
      c = static_cast<float>(c * spacing);
    const CsrGraph graph = test::kdTreeKnnGraph(xyz, 10);
    const std::vector<float> radii = pointRadii(graph, computeCentrality(graph, 0, 1).f);
    widths.push_back(rimBandWidth(radii));
    std::cout << "[ INFO     ] spacing " << spacing << ": band " << widths.back() << "\n";
  }
  // A length of the surface: within a few percent at every density (the sheet's border holds
  // a falling share of the points); 3 rings of kNN edges would shrink 4 times.
  for (double width : widths)
    EXPECT_NEAR(width / widths[0], 1.0, 0.05);
  // About a part of 1% of the object (twice the sheet, 768 square units: half-width 1.4),
  // widened by the overlap of the feature discs (Sec. 4.3) but far below the sheet's size.
  EXPECT_GT(widths[0], 1.4);
  EXPECT_LT(widths[0], 8.0);
}
