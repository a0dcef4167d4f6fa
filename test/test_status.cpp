/*
 * The library's reasons as values: getStatus() after extract() and the Status of
 * segmentPoints() carry the reason PCL_ERROR prints (a code and its message) and the warnings
 * PCL_WARN prints; setConsoleMessages(false) keeps them off the console. The public types of
 * getHierarchy() and getSupernodeGraph() hold the tree of bisections and G_s.
 */
#include <pcl_ncut_seg/segment_points.h>
#include <pcl_ncut_seg/segment_tree.h>
#include <pcl_ncut_seg/status.h>
#include <pcl_ncut_seg/supernode_ncut_segmentation.h>
#include <shapes/shapes.h>
#include <support/extract_capturing.h>

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>
#include <string>
#include <vector>

using Seg = pcl::SupernodeNCutSegmentation<pcl::PointXYZ>;
using Cloud = pcl::PointCloud<pcl::PointXYZ>;
using pcl_ncut_seg::Status;
using pcl_ncut_seg::StatusCode;
using pcl_ncut_seg::WarningCode;
using namespace pcl_ncut_seg::test;

namespace {

const std::string kPrefix = "[pcl::SupernodeNCutSegmentation::extract] ";

/** extract() failed with this code and message, which PCL_ERROR printed beside it. */
void expectFailure(const Seg& seg, const Extracted& r, StatusCode code, const std::string& why) {
  EXPECT_TRUE(r.segments.empty());
  const Status& status = seg.getStatus();
  EXPECT_FALSE(status.ok());
  EXPECT_FALSE(static_cast<bool>(status));
  EXPECT_EQ(status.code, code) << pcl_ncut_seg::statusCodeName(status.code);
  EXPECT_EQ(status.message, why);
  EXPECT_NE(r.err.find(kPrefix + why + "\n"), std::string::npos) << r.err;
}

Cloud::Ptr nanCloud(std::size_t n) {
  const float nan = std::numeric_limits<float>::quiet_NaN();
  Cloud::Ptr c(new Cloud);
  for (std::size_t i = 0; i < n; ++i)
    c->push_back(pcl::PointXYZ(nan, static_cast<float>(i), nan));
  return c;
}

std::vector<float> xyzOf(const Cloud& cloud) {
  std::vector<float> xyz;
  for (const auto& p : cloud)
    xyz.insert(xyz.end(), {p.x, p.y, p.z});
  return xyz;
}

} // namespace

TEST(Status, OkWithoutWarningsBeforeAndAfterAGoodExtract) {
  Seg seg;
  EXPECT_TRUE(seg.getStatus().ok());
  seg.setInputCloud(makeDumbbell(600, 1).cloud);
  const Extracted r = extractCapturing(seg);
  ASSERT_FALSE(r.segments.empty());
  EXPECT_TRUE(seg.getStatus().ok());
  EXPECT_TRUE(seg.getStatus().message.empty());
  EXPECT_TRUE(seg.getStatus().warnings.empty());
  EXPECT_EQ(r.err, "");
}

TEST(Status, NoInputEmptyAndAllNanClouds) {
  Seg seg;
  expectFailure(seg, extractCapturing(seg), StatusCode::NoInput, "no input cloud.");
  seg.setInputCloud(Cloud::Ptr(new Cloud));
  expectFailure(seg, extractCapturing(seg), StatusCode::NoFinitePoint,
                "the input has no finite point.");
  seg.setInputCloud(nanCloud(50));
  expectFailure(seg, extractCapturing(seg), StatusCode::NoFinitePoint,
                "the input has no finite point.");
  // The next good extract() forgets the failure.
  seg.setInputCloud(makeDumbbell(600, 1).cloud);
  ASSERT_FALSE(extractCapturing(seg).segments.empty());
  EXPECT_TRUE(seg.getStatus().ok());
  EXPECT_TRUE(seg.getStatus().message.empty());
}

TEST(Status, IndexOutOfRangeAndRepeatedIndices) {
  const Cloud::Ptr cloud = makeDumbbell(500, 2).cloud;
  const std::string n = std::to_string(cloud->size());
  Seg seg;
  seg.setInputCloud(cloud);
  seg.setIndices(pcl::IndicesPtr(new pcl::Indices{0, 1, static_cast<int>(cloud->size())}));
  expectFailure(seg, extractCapturing(seg), StatusCode::IndexOutOfRange,
                "index " + n + " is out of range for a cloud of " + n + " points.");

  pcl::IndicesPtr twice(new pcl::Indices(cloud->size()));
  std::iota(twice->begin(), twice->end(), 0);
  twice->insert(twice->end(), {3, 4, 5});
  seg.setIndices(twice);
  const Extracted r = extractCapturing(seg);
  ASSERT_FALSE(r.segments.empty());
  const Status& status = seg.getStatus();
  EXPECT_TRUE(status.ok());
  ASSERT_EQ(status.warnings.size(), 1u);
  EXPECT_EQ(status.warnings[0].code, WarningCode::RepeatedIndices);
  EXPECT_EQ(status.warnings[0].message, "3 repeated indices ignored.");
  EXPECT_NE(r.err.find(kPrefix + "3 repeated indices ignored.\n"), std::string::npos) << r.err;
}

TEST(Status, FewerPointsThanKPlusOneIsAWarning) {
  const Cloud::Ptr few = randomCube(5, 7);
  Seg seg;
  seg.setInputCloud(few);
  seg.setNumberOfNeighbours(10);
  const Extracted r = extractCapturing(seg);
  ASSERT_FALSE(r.segments.empty());
  const Status& status = seg.getStatus();
  EXPECT_TRUE(status.ok());
  const pcl_ncut_seg::Warning* w = status.find(WarningCode::FewPoints);
  ASSERT_NE(w, nullptr);
  EXPECT_EQ(w->message, "only 5 points: using 4 neighbours instead of 10.");
  EXPECT_NE(r.err.find(kPrefix + w->message + "\n"), std::string::npos) << r.err;
  EXPECT_EQ(status.find(WarningCode::RepeatedIndices), nullptr);

  // Silent: the same status, nothing on the console.
  Seg quiet;
  quiet.setConsoleMessages(false);
  EXPECT_FALSE(quiet.getConsoleMessages());
  quiet.setInputCloud(few);
  const Extracted q = extractCapturing(quiet);
  EXPECT_EQ(q.err, "");
  ASSERT_EQ(quiet.getStatus().warnings.size(), 1u);
  EXPECT_EQ(quiet.getStatus().warnings[0].message, w->message);
  quiet.setInputCloud(nanCloud(3));
  const Extracted qn = extractCapturing(quiet);
  EXPECT_EQ(qn.err, "");
  EXPECT_EQ(quiet.getStatus().code, StatusCode::NoFinitePoint);
  ::testing::internal::CaptureStderr();
  quiet.setNumberOfNeighbours(1); // rejected, silently
  EXPECT_EQ(::testing::internal::GetCapturedStderr(), "");
  EXPECT_EQ(quiet.getNumberOfNeighbours(), 10);
}

TEST(Status, SegmentPointsSaysWhy) {
  const Cloud::Ptr cloud = makeDumbbell(600, 1).cloud;
  const std::vector<float> xyz = xyzOf(*cloud);
  pcl_ncut_seg::Parameters bad;
  bad.graph.k = 1;
  Status status;
  EXPECT_TRUE(pcl_ncut_seg::segmentPoints(xyz.data(), cloud->size(), bad, &status).empty());
  EXPECT_EQ(status.code, StatusCode::BadParameter);
  EXPECT_EQ(status.message.rfind("k must be ", 0), 0u) << status.message;
  EXPECT_NE(status.message.find("got 1"), std::string::npos) << status.message;

  const pcl_ncut_seg::Parameters params;
  EXPECT_TRUE(pcl_ncut_seg::segmentPoints(xyz.data(), 0, params, &status).empty());
  EXPECT_EQ(status.code, StatusCode::NoFinitePoint);
  EXPECT_EQ(status.message, "the input has no finite point.");

  EXPECT_EQ(pcl_ncut_seg::segmentPoints(xyz.data(), 3, params, &status).size(), 3u);
  EXPECT_TRUE(status.ok());
  ASSERT_EQ(status.warnings.size(), 1u);
  EXPECT_EQ(status.warnings[0].code, WarningCode::FewPoints);
  EXPECT_EQ(status.warnings[0].message, "only 3 points: using 2 neighbours instead of 10.");

  // A good call: ok, no warnings, and the labels of a call without a status.
  EXPECT_EQ(pcl_ncut_seg::segmentPoints(xyz.data(), cloud->size(), params, &status),
            pcl_ncut_seg::segmentPoints(xyz.data(), cloud->size(), params));
  EXPECT_TRUE(status.ok());
  EXPECT_TRUE(status.warnings.empty());
}

TEST(Status, CodeNames) {
  EXPECT_STREQ(pcl_ncut_seg::statusCodeName(StatusCode::Ok), "ok");
  EXPECT_STREQ(pcl_ncut_seg::statusCodeName(StatusCode::NoFinitePoint), "no_finite_point");
  EXPECT_STREQ(pcl_ncut_seg::statusCodeName(StatusCode::BadParameter), "bad_parameter");
  EXPECT_STREQ(pcl_ncut_seg::warningCodeName(WarningCode::FewPoints), "few_points");
}

// The public tree: the root holds all of G_s, children divide their parent, NCut in [0, 2],
// the leaves' supernodes in the segments of their points.
TEST(SegmentTree, TheHierarchyAndGraphAsPublicTypes) {
  Seg seg;
  EXPECT_TRUE(seg.getHierarchy().nodes.empty());
  const LabeledShape hand = makeHand(2500, 3);
  seg.setInputCloud(hand.cloud);
  seg.setNumberOfSegments(6);
  std::vector<pcl::PointIndices> segments;
  seg.extract(segments);
  ASSERT_EQ(segments.size(), 6u);
  const std::size_t l = seg.getNumberOfSupernodes(true);
  const pcl_ncut_seg::SupernodeGraph g = seg.getSupernodeGraph();
  EXPECT_EQ(g.num_supernodes, l);
  EXPECT_EQ(g.num_vertices, 2 * l);
  ASSERT_FALSE(g.edges.empty());
  std::size_t features = 0;
  for (const auto& e : g.edges) {
    EXPECT_LT(e.source, g.num_vertices);
    EXPECT_LT(e.target, g.num_vertices);
    EXPECT_TRUE(std::isfinite(e.weight) && e.weight >= 0.0) << e.weight;
    const std::uint32_t lo = std::min(e.source, e.target), hi = std::max(e.source, e.target);
    features += !g.isMember(lo) && g.isMember(hi) && g.supernode(hi) == lo;
  }
  EXPECT_EQ(features, l); // one r_i - m_i edge per supernode

  const pcl_ncut_seg::SegmentTree tree = seg.getHierarchy();
  ASSERT_FALSE(tree.nodes.empty());
  EXPECT_EQ(tree.num_supernodes, l);
  EXPECT_EQ(tree.nodes[0].parent, -1);
  EXPECT_EQ(tree.nodes[0].vertices.size(), 2 * l);
  EXPECT_EQ(tree.nodes[0].supernodes.size(), l);
  for (std::size_t i = 0; i < tree.nodes.size(); ++i) {
    const auto& node = tree.nodes[i];
    if (node.isLeaf()) {
      EXPECT_EQ(node.right, -1);
      continue;
    }
    EXPECT_TRUE(std::isfinite(node.ncut) && node.ncut >= 0.0 && node.ncut <= 2.0) << node.ncut;
    const auto& a = tree.nodes[node.left];
    const auto& b = tree.nodes[node.right];
    EXPECT_EQ(a.parent, static_cast<int>(i));
    EXPECT_EQ(b.parent, static_cast<int>(i));
    std::vector<std::uint32_t> both = a.vertices;
    both.insert(both.end(), b.vertices.begin(), b.vertices.end());
    std::sort(both.begin(), both.end());
    EXPECT_EQ(both, node.vertices) << "node " << i;
  }
  // Each leaf's supernodes: their segment is that of their points.
  const std::vector<int> label = seg.getSupernodeLabels(true);
  std::vector<int> segment_of(hand.cloud->size(), -1);
  for (std::size_t s = 0; s < segments.size(); ++s)
    for (const int i : segments[s].indices)
      segment_of[i] = static_cast<int>(s);
  ASSERT_EQ(tree.supernode_segment.size(), l);
  std::size_t agree = 0, points = 0;
  for (std::size_t i = 0; i < label.size(); ++i)
    if (label[i] >= 0) {
      ++points;
      agree += tree.supernode_segment[label[i]] == segment_of[i];
    }
  EXPECT_GT(static_cast<double>(agree), 0.9 * static_cast<double>(points)); // boundaries move
  EXPECT_GE(tree.leaves().size(), segments.size());
}
