/*
 * Bad and degenerate input through the library: each case gets either an empty result with a
 * PCL_ERROR saying why, or a correct segmentation (every finite selected point in exactly one
 * segment). test_segmentation.cpp covers the basic cases (no input, an empty or all-NaN cloud,
 * NaN/inf points, bad indices, a few points on a line, a cloud repeated three times, rejected
 * setter values); this file adds what those leave out, and checks the messages. Parameters at
 * the edges of their ranges, and determinism: test_parameter_edges.cpp.
 */
#include <pcl_ncut_seg/segment_points.h>
#include <pcl_ncut_seg/supernode_ncut_segmentation.h>
#include <shapes/metrics.h>
#include <shapes/shapes.h>
#include <support/extract_capturing.h>
#include <support/graphs.h>
#include <support/partition.h>

#include <pcl/common/point_tests.h>

#include <gtest/gtest.h>

#include <algorithm>
#include <climits>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <functional>
#include <limits>
#include <random>
#include <set>
#include <string>
#include <vector>

using Seg = pcl::SupernodeNCutSegmentation<pcl::PointXYZ>;
using Cloud = pcl::PointCloud<pcl::PointXYZ>;
using Segments = std::vector<pcl::PointIndices>;
using namespace pcl_ncut_seg::test;

namespace {

const float kNaN = std::numeric_limits<float>::quiet_NaN();
const float kInf = std::numeric_limits<float>::infinity();

/** The user gets nothing, and is told why in one PCL_ERROR naming extract(). */
void expectErrorAndNothing(const Seg& seg, const Extracted& r, const std::string& mention) {
  EXPECT_TRUE(r.segments.empty());
  EXPECT_NE(r.err.find("[pcl::SupernodeNCutSegmentation::extract]"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find(mention), std::string::npos) << r.err;
  EXPECT_TRUE(seg.getLabeledCloud()->empty());
  EXPECT_TRUE(seg.getColoredCloud()->empty());
  EXPECT_EQ(seg.getAnalysis(), nullptr);
  EXPECT_TRUE(seg.getAnalysedIndices().empty());
}

/** Segment `cloud` with default parameters changed by `setup`; expects no error. */
Segments segment(const Cloud::Ptr& cloud, const std::function<void(Seg&)>& setup = nullptr) {
  Seg seg;
  seg.setInputCloud(cloud);
  if (setup)
    setup(seg);
  Segments out;
  seg.extract(out);
  return out;
}

Cloud::Ptr transformed(const Cloud& in, double scale, double offset) {
  Cloud::Ptr out(new Cloud);
  for (const auto& p : in)
    out->push_back(pcl::PointXYZ(static_cast<float>(p.x * scale + offset),
                                 static_cast<float>(p.y * scale + offset),
                                 static_cast<float>(p.z * scale + offset)));
  return out;
}

} // namespace

// ---------------------------------------------------------------------------------------------
// No usable input: an empty result and a PCL_ERROR that says why.

// PointSegmenter (segment_points.h) used out of order: no analysis and no segments, no crash.
TEST(Robustness, PointSegmenterOutOfOrderGivesNoSegments) {
  pcl_ncut_seg::PointSegmenter segmenter;
  pcl_ncut_seg::PhaseTimes times;
  const pcl_ncut_seg::Parameters params;
  segmenter.cut(params, times); // before any analysis
  EXPECT_FALSE(segmenter.analysed());
  EXPECT_EQ(segmenter.numSegments(), 0u);
  EXPECT_TRUE(segmenter.pointSegments().empty());
  segmenter.analyze(params, times); // before prepare()
  EXPECT_FALSE(segmenter.analysed());
  EXPECT_FALSE(segmenter.serves(params));
  EXPECT_EQ(segmenter.analysis(), nullptr);
  segmenter.cut(params, times);
  EXPECT_EQ(segmenter.numSegments(), 0u);
}

TEST(Robustness, NoInputOrNullInputSaysWhy) {
  Seg seg;
  Extracted r = extractCapturing(seg);
  expectErrorAndNothing(seg, r, "no input cloud");
  seg.setInputCloud(Cloud::ConstPtr());
  r = extractCapturing(seg);
  expectErrorAndNothing(seg, r, "no input cloud");
}

TEST(Robustness, EmptyAndNonFiniteCloudsSayWhy) {
  Seg seg;
  seg.setInputCloud(Cloud::Ptr(new Cloud));
  expectErrorAndNothing(seg, extractCapturing(seg), "no finite point");

  Cloud::Ptr bad(new Cloud);
  for (int i = 0; i < 200; ++i) // every kind of non-finite coordinate, in every position
    bad->push_back(i % 4 == 0   ? pcl::PointXYZ(kNaN, kNaN, kNaN)
                   : i % 4 == 1 ? pcl::PointXYZ(0, kInf, 0)
                   : i % 4 == 2 ? pcl::PointXYZ(0, 0, -kInf)
                                : pcl::PointXYZ(static_cast<float>(i), kNaN, 1));
  seg.setInputCloud(bad);
  expectErrorAndNothing(seg, extractCapturing(seg), "no finite point");
}

TEST(Robustness, BadInputAfterAGoodOneLeavesNoStaleResult) {
  Seg seg;
  seg.setInputCloud(makeDumbbell(600, 1).cloud);
  Extracted r = extractCapturing(seg);
  ASSERT_FALSE(r.segments.empty());
  ASSERT_FALSE(seg.getLabeledCloud()->empty());
  Cloud::Ptr nan(new Cloud);
  nan->push_back(pcl::PointXYZ(kNaN, 0, 0));
  seg.setInputCloud(nan);
  r = extractCapturing(seg);
  expectErrorAndNothing(seg, r, "no finite point");
  EXPECT_TRUE(seg.getCentrality().size() == 1 && std::isnan(seg.getCentrality()[0]));
  EXPECT_TRUE(seg.getLocalMaxima().empty());
  EXPECT_EQ(seg.getNumberOfSupernodes(true), 0u);
}

// ---------------------------------------------------------------------------------------------
// Non-finite points: in no segment; the rest segmented as if they were absent.

TEST(Robustness, OrganizedCloudWithNanHoles) {
  // A range image of a bumpy surface: 80 x 60, with a rectangular hole, a ragged border and
  // scattered dropouts, as a depth sensor produces.
  const std::uint32_t w = 80, h = 60;
  Cloud::Ptr organized(new Cloud(w, h));
  Cloud::Ptr dense(new Cloud);
  std::vector<int> dense_index;
  std::mt19937_64 rng(7);
  for (std::uint32_t v = 0; v < h; ++v)
    for (std::uint32_t u = 0; u < w; ++u) {
      const float x = u * 0.05f, y = v * 0.05f;
      const float z = 0.4f * std::exp(-((x - 1) * (x - 1) + (y - 1.5f) * (y - 1.5f)) * 4) +
                      0.4f * std::exp(-((x - 3) * (x - 3) + (y - 1.5f) * (y - 1.5f)) * 4);
      const bool hole =
          (u >= 35 && u < 45 && v >= 20 && v < 40) || u < (v % 5) || (rng() % 10 == 0);
      pcl::PointXYZ& p = (*organized)(u, v);
      p = hole ? pcl::PointXYZ(kNaN, kNaN, kNaN) : pcl::PointXYZ(x, y, z);
      if (!hole) {
        dense_index.push_back(static_cast<int>(v * w + u));
        dense->push_back(p);
      }
    }
  organized->is_dense = false;
  // The sensor looks down on the surface, as a depth camera would (one view's normals face
  // it); the dense cloud is seen from the same place.
  organized->sensor_origin_ = Eigen::Vector4f(2.0f, 1.5f, 3.0f, 0.0f);
  dense->sensor_origin_ = organized->sensor_origin_;
  ASSERT_TRUE(organized->isOrganized());

  Seg seg;
  seg.setInputCloud(organized);
  Extracted merged = extractCapturing(seg);
  ASSERT_FALSE(merged.segments.empty()) << merged.err;
  expectPartition(merged.segments, *organized);
  // Without the rim merge, which only an organized cloud's rim allows here
  // (core/views/rim_merge.h): the same segmentation as the cloud without the holes.
  seg.setRimMerge(std::nullopt);
  Extracted r = extractCapturing(seg);
  ASSERT_FALSE(r.segments.empty()) << r.err;
  expectPartition(r.segments, *organized);
  std::vector<int> merged_of(w * h, -1);
  for (std::size_t s = 0; s < merged.segments.size(); ++s)
    for (int i : merged.segments[s].indices)
      merged_of[i] = static_cast<int>(s);
  for (const auto& segment : r.segments) // the merge joins whole segments
    for (int i : segment.indices)
      EXPECT_EQ(merged_of[i], merged_of[segment.indices[0]]);
  const Segments clean = segment(dense, [](Seg& s) { s.setRimMerge(std::nullopt); });
  ASSERT_EQ(clean.size(), r.segments.size());
  for (std::size_t s = 0; s < clean.size(); ++s) {
    ASSERT_EQ(clean[s].indices.size(), r.segments[s].indices.size());
    for (std::size_t j = 0; j < clean[s].indices.size(); ++j)
      ASSERT_EQ(dense_index[clean[s].indices[j]], r.segments[s].indices[j]);
  }
  // The labelled cloud keeps the image layout; holes have label 0.
  const auto labeled = seg.getLabeledCloud();
  EXPECT_EQ(labeled->width, w);
  EXPECT_EQ(labeled->height, h);
  for (std::size_t i = 0; i < organized->size(); ++i)
    if (!pcl::isXYZFinite((*organized)[i])) {
      EXPECT_EQ((*labeled)[i].label, 0u);
    }
}

// ---------------------------------------------------------------------------------------------
// Few points.

TEST(Robustness, OneTwoAndKPointsInGeneralPosition) {
  const int k = 10;
  for (std::size_t n : {1u, 2u, 3u, 9u, 10u, 11u, 12u}) {
    SCOPED_TRACE(std::to_string(n) + " points");
    Cloud::Ptr c = randomCube(n, n);
    Seg seg;
    seg.setInputCloud(c);
    seg.setNumberOfNeighbours(k);
    const Extracted r = extractCapturing(seg);
    ASSERT_FALSE(r.segments.empty()) << r.err;
    expectPartition(r.segments, *c);
    EXPECT_EQ(r.err.find("[pcl::SupernodeNCutSegmentation::extract] the input"), std::string::npos);
    if (n == 1) {
      EXPECT_EQ(r.segments.size(), 1u);
    }
    // Fewer points than k + 1: k drops to n - 1, with a warning.
    if (n <= static_cast<std::size_t>(k)) {
      EXPECT_NE(r.err.find("neighbours instead of 10"), std::string::npos) << r.err;
    } else {
      EXPECT_EQ(r.err.find("neighbours instead of"), std::string::npos) << r.err;
    }
    EXPECT_EQ(seg.getLabeledCloud()->size(), n);
  }
}

TEST(Robustness, FewerPointsThanKWithTheRequestedSegments) {
  // 6 points, k = 50, asking for 4 segments: at most as many segments as can be split off.
  Cloud::Ptr c = randomCube(6, 3);
  const Segments out = segment(c, [](Seg& s) {
    s.setNumberOfNeighbours(50);
    s.setNumberOfSegments(4);
  });
  ASSERT_FALSE(out.empty());
  EXPECT_LE(out.size(), 4u);
  expectPartition(out, *c);
}

// ---------------------------------------------------------------------------------------------
// Degenerate geometry: every finite point in exactly one segment, no error.

TEST(Robustness, ManyExactDuplicatesOfSomePoints) {
  // A hand where one point in ten is repeated twenty times, interleaved: each copy is in the
  // segment of its original, and the originals are segmented as without the copies.
  const Cloud::Ptr hand = makeHand(2000, 4).cloud;
  Cloud::Ptr c(new Cloud);
  std::vector<int> origin, position;
  for (std::size_t i = 0; i < hand->size(); ++i) {
    position.push_back(static_cast<int>(c->size()));
    c->push_back((*hand)[i]);
    origin.push_back(static_cast<int>(i));
    if (i % 10 == 0)
      for (int r = 0; r < 20; ++r) {
        c->push_back((*hand)[i]);
        origin.push_back(static_cast<int>(i));
      }
  }
  const auto six = [](Seg& s) { s.setNumberOfSegments(6); };
  const Segments out = segment(c, six);
  ASSERT_FALSE(out.empty());
  const auto label = expectPartition(out, *c);
  const auto reference = segmentsToLabels(segment(hand, six), hand->size());
  std::size_t differ = 0;
  for (std::size_t i = 0; i < c->size(); ++i)
    differ += label[i] != reference[origin[i]];
  EXPECT_EQ(differ, 0u) << "points whose segment changed with the copies";
}

TEST(Robustness, AllPointsIdenticalGiveOneSegment) {
  Cloud::Ptr c(new Cloud);
  for (int i = 0; i < 5000; ++i)
    c->push_back(pcl::PointXYZ(1.5f, -2.f, 3.f));
  const Segments out = segment(c);
  ASSERT_EQ(out.size(), 1u);
  expectPartition(out, *c);
}

TEST(Robustness, CollinearPoints) {
  for (const bool duplicates : {false, true}) {
    Cloud::Ptr c(new Cloud);
    for (int i = 0; i < 1000; ++i) { // a line, not along an axis, unevenly spaced
      const float t = static_cast<float>(i) * (1.0f + 0.3f * std::sin(0.1f * i));
      c->push_back(pcl::PointXYZ(t, 2 * t, -t));
      if (duplicates && i % 3 == 0)
        c->push_back(c->back());
    }
    const Segments out = segment(c);
    ASSERT_FALSE(out.empty());
    expectPartition(out, *c);
  }
}

TEST(Robustness, CoplanarPoints) {
  // A regular grid (equal distances everywhere: ties in every neighbour search and in the
  // centrality) and random points in a tilted disk.
  Cloud::Ptr grid(new Cloud), disk(new Cloud);
  for (int i = 0; i < 40; ++i)
    for (int j = 0; j < 40; ++j)
      grid->push_back(pcl::PointXYZ(static_cast<float>(i), static_cast<float>(j), 0));
  std::mt19937_64 rng(5);
  std::uniform_real_distribution<float> u(-1.0f, 1.0f);
  while (disk->size() < 1500) {
    const float a = u(rng), b = u(rng);
    if (a * a + b * b <= 1)
      disk->push_back(pcl::PointXYZ(a, b, 0.5f * a - 0.25f * b));
  }
  for (const auto& c : {grid, disk}) {
    const Segments out = segment(c);
    ASSERT_FALSE(out.empty());
    expectPartition(out, *c);
  }
}

TEST(Robustness, SeveralFarApartObjects) {
  // Four hands far apart (1e3 and 1e5 units): no segment spans two of them.
  const LabeledShape hand = makeHand(1500, 6);
  const float offsets[4][3] = {{0, 0, 0}, {1e3f, 0, 0}, {0, -1e3f, 0}, {0, 0, 1e5f}};
  Cloud::Ptr c(new Cloud);
  std::vector<int> object;
  for (int o = 0; o < 4; ++o)
    for (const auto& p : *hand.cloud) {
      c->push_back(pcl::PointXYZ(p.x + offsets[o][0], p.y + offsets[o][1], p.z + offsets[o][2]));
      object.push_back(o);
    }
  const Segments out = segment(c);
  ASSERT_GE(out.size(), 4u);
  expectPartition(out, *c);
  for (const auto& s : out)
    for (int i : s.indices)
      ASSERT_EQ(object[i], object[s.indices.front()]) << "a segment spans two objects";
}

TEST(Robustness, DenseClusterWithOneFarOutlier) {
  // The outlier is its own connected component, so its own segment; the rest is segmented
  // as without it (its sampling starts from its own centroid, core/centrality/starts.h).
  const LabeledShape hand = makeHand(3000, 8);
  Cloud::Ptr c(new Cloud(*hand.cloud));
  c->push_back(pcl::PointXYZ(1e4f, -3e3f, 5e2f));
  const Segments with = segment(c, [](Seg& s) { s.setNumberOfSegments(7); });
  const Segments without = segment(hand.cloud, [](Seg& s) { s.setNumberOfSegments(6); });
  ASSERT_FALSE(with.empty());
  const auto label = expectPartition(with, *c);
  const int outlier = static_cast<int>(c->size() - 1);
  const bool alone = with.back().indices == std::vector<int>{outlier};
  std::vector<int> a(label.begin(), label.end() - 1);
  const double ri = randIndex(a, segmentsToLabels(without, hand.cloud->size()));
  std::printf("hand + far outlier vs hand: Rand index %.4f; outlier %s\n", ri,
              alone ? "alone" : "shares a segment");
  EXPECT_TRUE(alone) << "the outlier shares a segment";
  EXPECT_GE(ri, 0.99);
}

TEST(Robustness, PointsTooFarToMeasureAreInNoSegment) {
  // Coordinates near FLT_MAX (a corrupt file's garbage) overflow the squared distances of the
  // kNN search: FLANN's tree recursed until the stack ran out. They are in no segment, as NaN
  // points are, and the rest is segmented as without them.
  const LabeledShape hand = makeHand(2000, 8);
  Cloud::Ptr c(new Cloud(*hand.cloud));
  for (int i = 0; i < 300; ++i)
    c->push_back(pcl::PointXYZ(i % 2 ? 3.3e38f : -2e38f, 1e19f * float(i % 7), 0.5f));
  const Segments with = segment(c, [](Seg& s) { s.setNumberOfSegments(6); });
  const Segments without = segment(hand.cloud, [](Seg& s) { s.setNumberOfSegments(6); });
  ASSERT_EQ(with.size(), without.size());
  for (std::size_t s = 0; s < with.size(); ++s)
    EXPECT_EQ(with[s].indices, without[s].indices) << "segment " << s;

  Cloud::Ptr far(new Cloud);
  for (int i = 0; i < 100; ++i)
    far->push_back(pcl::PointXYZ(2e18f * float(i + 1), 0, 0));
  Seg seg;
  seg.setInputCloud(far);
  expectErrorAndNothing(seg, extractCapturing(seg), "no finite point within 1e18");
}

TEST(Robustness, KnnGraphDropsTheEdgesOfALoneFarPoint) {
  // Points 1 apart on a line, k = 2: kNN radius 1 inside, 2 at the end point 49. A single
  // point p beyond the end has 49 and 48 as its nearest; an edge is used unless it is over 10
  // times the radius of the point it reaches. At 15 beyond: p-49 (15 <= 20) is used, p-48
  // (16 > 10) is not; at 25 beyond neither is, and p is on its own.
  for (const float gap : {15.0f, 25.0f}) {
    std::vector<float> xyz;
    for (int i = 0; i < 50; ++i)
      xyz.insert(xyz.end(), {static_cast<float>(i), 0, 0});
    xyz.insert(xyz.end(), {49 + gap, 0, 0});
    const auto knn = pcl_ncut_seg::test::bruteForceKnn(xyz, 2);
    const pcl_ncut_seg::CsrGraph g =
        pcl_ncut_seg::buildSymmetricKnnGraph(xyz.data(), 51, knn.data(), 2);
    std::vector<std::uint32_t> component;
    EXPECT_EQ(pcl_ncut_seg::connectedComponents(g, component), gap < 20 ? 1u : 2u) << gap;
    EXPECT_EQ(g.degree(50), gap < 20 ? 1u : 0u) << gap;
  }
}

TEST(Robustness, ScaledModelsSegmentTheSame) {
  // A unit-size model (the hand is 2.2 units tall) scaled by 1e-3 and 1e3: Rand index against
  // the original's segmentation at least 0.99.
  const LabeledShape hand = makeHand(3000, 9);
  const auto six = [](Seg& s) { s.setNumberOfSegments(6); };
  const auto reference = segmentsToLabels(segment(hand.cloud, six), hand.cloud->size());
  const auto by_threshold = segmentsToLabels(segment(hand.cloud), hand.cloud->size());
  for (const double scale : {1e-3, 1e3}) {
    const Cloud::Ptr c = transformed(*hand.cloud, scale, 0);
    const double ri = randIndex(expectPartition(segment(c, six), *c), reference);
    const double ri_t = randIndex(expectPartition(segment(c), *c), by_threshold);
    std::printf("hand scaled by %g: Rand index vs original %.4f (6 segments), %.4f (threshold)\n",
                scale, ri, ri_t);
    EXPECT_GE(ri, 0.99) << scale;
    EXPECT_GE(ri_t, 0.99) << scale;
  }
}

TEST(Robustness, ModelFarFromTheOrigin) {
  // The hand (2.2 units tall, mean point spacing 0.02) moved away from the origin: what float
  // coordinates there keep, the segmentation must keep.
  const LabeledShape hand = makeHand(3000, 9);
  const auto six = [](Seg& s) { s.setNumberOfSegments(6); };
  const std::vector<int> origin = segmentsToLabels(segment(hand.cloud, six), hand.cloud->size());
  const std::vector<int> origin_t = segmentsToLabels(segment(hand.cloud), hand.cloud->size());

  // Moved by 1 and 10, the coordinates are rounded by at most 4.8e-7 (2^-21 below 16), 2.4e-5
  // point spacings: the same segmentation, label for label. (Measured on the hands of seeds
  // 1-20: the same for all at 10, but not for 1 of them at 100, rounded by 3.8e-6, nor for 4
  // at 300: a change of a few 1e-4 point spacings can pick another of two nearly equal cuts.)
  for (const double offset : {1.0, 10.0}) {
    const Cloud::Ptr c = transformed(*hand.cloud, 1.0, offset);
    EXPECT_EQ(expectPartition(segment(c, six), *c), origin) << offset;
    EXPECT_EQ(expectPartition(segment(c), *c), origin_t) << offset;
  }

  // Moved by 1e4, where floats are 2^-10 apart, the points move by up to 4.9e-4. The library
  // loses nothing beyond that rounding: the moved cloud segments exactly as the same points
  // moved back in double.
  const Cloud::Ptr moved = transformed(*hand.cloud, 1.0, 1e4);
  const Cloud::Ptr back = transformed(*moved, 1.0, -1e4); // exact: float values near 0
  const auto labels = expectPartition(segment(moved, six), *moved);
  const auto labels_t = expectPartition(segment(moved), *moved);
  EXPECT_EQ(labels, segmentsToLabels(segment(back, six), back->size()));
  EXPECT_EQ(labels_t, segmentsToLabels(segment(back), back->size()));
  // The rounding is a perturbation of the size of a random jitter of 5e-4, and on generated
  // hands changes the segmentation about as much as such a jitter; the Rand index against the
  // unmoved hand's can fall short of the goal of 0.99 (docs/limitations.md;
  // pcl_ncut_seg_bench_perturbation prints it, and the jitter). What the test checks is what
  // matters on a hand: its palm, four fingers and thumb each keep a segment of their own
  // holding over half of their points, moved and unmoved, with six segments asked for and with
  // the threshold.
  std::printf("hand moved by 1e4: Rand index vs unmoved %.4f (6 segments), %.4f (threshold)\n",
              randIndex(labels, origin), randIndex(labels_t, origin_t));
  const std::pair<const char*, const std::vector<int>*> runs[] = {{"unmoved, 6 segments", &origin},
                                                                  {"unmoved, threshold", &origin_t},
                                                                  {"moved, 6 segments", &labels},
                                                                  {"moved, threshold", &labels_t}};
  for (const auto& [what, run] : runs) {
    const std::vector<MainSegment> main = mainSegments(*run, hand.labels, hand.num_parts);
    std::set<int> own;
    std::printf("  %s: share of each part in its main segment", what);
    for (int part = 0; part < hand.num_parts; ++part) {
      std::printf(" %.3f", main[part].share);
      EXPECT_GT(main[part].share, 0.5) << what << ", part " << part;
      own.insert(main[part].segment);
    }
    std::printf("\n");
    EXPECT_EQ(own.size(), static_cast<std::size_t>(hand.num_parts))
        << what << ": two parts share their main segment";
  }
}

// ---------------------------------------------------------------------------------------------
// Indices.

TEST(Robustness, BadIndicesSayWhy) {
  Cloud::Ptr c = makeDumbbell(500, 2).cloud;
  Seg seg;
  seg.setInputCloud(c);
  for (const int bad : {static_cast<int>(c->size()), -1, INT_MAX, INT_MIN}) {
    pcl::IndicesPtr idx(new pcl::Indices{0, 1, bad, 3});
    seg.setIndices(idx);
    expectErrorAndNothing(seg, extractCapturing(seg), "out of range");
  }
  seg.setIndices(pcl::IndicesPtr(new pcl::Indices));
  expectErrorAndNothing(seg, extractCapturing(seg), "no finite point");
  // Indices that select only NaN points.
  Cloud::Ptr mixed(new Cloud(*c));
  mixed->push_back(pcl::PointXYZ(kNaN, 0, 0));
  mixed->push_back(pcl::PointXYZ(0, kInf, 0));
  seg.setInputCloud(mixed);
  seg.setIndices(pcl::IndicesPtr(new pcl::Indices{501, 500, 501}));
  expectErrorAndNothing(seg, extractCapturing(seg), "no finite point");
}

TEST(Robustness, RepeatedAndUnsortedIndicesCountOnce) {
  // Shuffled, with repeats and NaN points selected: the same segments as the sorted set of
  // finite selected points, and a warning about the repeats.
  Cloud::Ptr c(new Cloud(*makeDumbbell(1500, 3).cloud));
  for (int i = 0; i < 20; ++i)
    c->push_back(pcl::PointXYZ(kNaN, kNaN, kNaN));
  pcl::Indices sorted;
  for (int i = 0; i < static_cast<int>(c->size()); i += 3)
    sorted.push_back(i);
  pcl::IndicesPtr messy(new pcl::Indices(sorted));
  messy->insert(messy->end(), sorted.begin(), sorted.begin() + 100);
  std::mt19937 rng(11);
  std::shuffle(messy->begin(), messy->end(), rng);

  Seg a, b;
  a.setInputCloud(c);
  a.setIndices(pcl::IndicesPtr(new pcl::Indices(sorted)));
  b.setInputCloud(c);
  b.setIndices(messy);
  Segments sa;
  a.extract(sa);
  const Extracted rb = extractCapturing(b);
  ASSERT_FALSE(sa.empty());
  expectPartition(rb.segments, *c, &sorted);
  EXPECT_NE(rb.err.find("100 repeated indices ignored"), std::string::npos) << rb.err;
  ASSERT_EQ(sa.size(), rb.segments.size());
  for (std::size_t s = 0; s < sa.size(); ++s)
    EXPECT_EQ(sa[s].indices, rb.segments[s].indices);
}

TEST(Robustness, PointIndicesOnAnOrganizedCloud) {
  // A region of interest of an organized cloud, given as pcl::PointIndices.
  const std::uint32_t w = 50, h = 40;
  Cloud::Ptr organized(new Cloud(w, h));
  pcl::PointIndices::Ptr roi(new pcl::PointIndices);
  for (std::uint32_t v = 0; v < h; ++v)
    for (std::uint32_t u = 0; u < w; ++u) {
      (*organized)(u, v) = (u + v) % 7 == 0 ? pcl::PointXYZ(kNaN, kNaN, kNaN)
                                            : pcl::PointXYZ(0.1f * u, 0.1f * v, 0.01f * u * v);
      if (u >= 10 && u < 40 && v >= 5 && v < 30)
        roi->indices.push_back(static_cast<int>(v * w + u));
    }
  Seg seg;
  seg.setInputCloud(organized);
  seg.setIndices(pcl::PointIndicesConstPtr(roi));
  const Extracted r = extractCapturing(seg);
  ASSERT_FALSE(r.segments.empty()) << r.err;
  expectPartition(r.segments, *organized, &roi->indices);
}
