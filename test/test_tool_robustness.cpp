/*
 * Bad and degenerate input through the pcl_ncut_seg command: each case either fails cleanly
 * (non-zero exit, one line on stderr, no file written) or writes a labelling in which every
 * finite point has a segment (label >= 1) and every other point label 0, the same labels the
 * library gives. test_tool.cpp covers the command line itself (missing and malformed files, an
 * empty or all-NaN cloud, bad option values); this file covers degenerate clouds and the edges
 * of every option's range.
 */
#include <pcl_ncut_seg/parameter_table.h>
#include <pcl_ncut_seg/supernode_ncut_segmentation.h>
#include <shapes/metrics.h>
#include <shapes/shapes.h>
#include <support/parameter_values.h>
#include <support/text_files.h>

#include <pcl/common/point_tests.h>
#include <pcl/io/pcd_io.h>

#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <limits>
#include <regex>
#include <set>
#include <sstream>
#include <string>
#include <vector>

namespace fs = std::filesystem;
using Cloud = pcl::PointCloud<pcl::PointXYZ>;
using namespace pcl_ncut_seg::test;

using pcl_ncut_seg::test::lines;
using pcl_ncut_seg::test::listDir;

namespace {

const std::string kTool = PCL_NCUT_SEG_TOOL;
const float kNaN = std::numeric_limits<float>::quiet_NaN();
const float kInf = std::numeric_limits<float>::infinity();

/** The library's labels for a cloud (1..t, 0 for none), with default parameters. */
std::vector<std::uint32_t> libraryLabels(const Cloud::Ptr& cloud) {
  pcl::SupernodeNCutSegmentation<pcl::PointXYZ> seg;
  seg.setInputCloud(cloud);
  std::vector<pcl::PointIndices> segments;
  seg.extract(segments);
  std::vector<std::uint32_t> labels;
  const auto labeled = seg.getLabeledCloud(); // keep the cloud alive through the loop
  for (const auto& p : *labeled)
    labels.push_back(p.label);
  return labels;
}

class ToolRobustness : public ::testing::Test {
protected:
  void SetUp() override {
    dir_ = makeTempDir("pcl_ncut_seg_robust");
    ASSERT_FALSE(dir_.empty());
    ASSERT_TRUE(fs::exists(kTool)) << kTool;
  }
  void TearDown() override {
    std::error_code ec;
    fs::remove_all(dir_, ec);
  }

  using Result = CommandRun;

  /** Run the tool in dir_; stdout and stderr go to files outside what the tool sees. */
  Result run(const std::string& args) const {
    return runCommand("cd '" + dir_.string() + "' && '" + kTool + "' " + args,
                      dir_.string() + ".out", dir_.string() + ".err");
  }

  void save(const std::string& name, const Cloud& cloud) const {
    ASSERT_EQ(pcl::io::savePCDFileBinary((dir_ / name).string(), cloud), 0);
  }

  /** Runs the tool on `cloud` with `options`; expects success and returns the labels, after
   * checking that they cover every finite point and no other. */
  std::vector<std::uint32_t> segment(const Cloud& cloud, const std::string& options = "") {
    std::vector<std::uint32_t> labels;
    save("in.pcd", cloud);
    fs::remove(dir_ / "out.pcd");
    const Result r = run("in.pcd out.pcd -quiet " + options);
    EXPECT_EQ(r.status, 0) << "pcl_ncut_seg " << options << "\n" << r.out << r.err;
    pcl::PointCloud<pcl::PointXYZL> out;
    if (r.status != 0 || pcl::io::loadPCDFile((dir_ / "out.pcd").string(), out) != 0) {
      ADD_FAILURE() << "no output for " << options;
      return labels;
    }
    EXPECT_EQ(out.size(), cloud.size());
    EXPECT_EQ(out.width, cloud.width);
    EXPECT_EQ(out.height, cloud.height);
    std::size_t wrong = 0;
    for (std::size_t i = 0; i < out.size() && i < cloud.size(); ++i) {
      wrong += (out[i].label > 0) != pcl::isXYZFinite(cloud[i]);
      labels.push_back(out[i].label);
    }
    EXPECT_EQ(wrong, 0u) << "points labelled but not finite, or finite but not labelled";
    return labels;
  }

  /** The tool fails cleanly: non-zero exit, one line on stderr (holding mention), no new
   * file. */
  void expectCleanFailure(const std::string& args, const std::string& mention = "") {
    SCOPED_TRACE("pcl_ncut_seg " + args);
    const std::set<std::string> before = listDir(dir_);
    const Result r = run(args);
    EXPECT_NE(r.status, 0);
    EXPECT_NE(r.status, -1) << "the tool crashed";
    EXPECT_EQ(lines(r.err).size(), 1u) << r.err;
    EXPECT_NE(r.err.find(mention), std::string::npos) << r.err;
    EXPECT_EQ(listDir(dir_), before) << "the run left files behind";
  }

  fs::path dir_;
};

TEST_F(ToolRobustness, NonFiniteCloudsFailCleanly) {
  Cloud bad;
  for (int i = 0; i < 60; ++i)
    bad.push_back(i % 3 == 0   ? pcl::PointXYZ(kInf, 0, 0)
                  : i % 3 == 1 ? pcl::PointXYZ(0, 0, -kInf)
                               : pcl::PointXYZ(kNaN, 1, 2));
  bad.is_dense = false;
  save("bad.pcd", bad);
  expectCleanFailure("bad.pcd out.pcd");
  Cloud organized(8, 5, pcl::PointXYZ(kNaN, kNaN, kNaN));
  organized.is_dense = false;
  save("organized.pcd", organized);
  expectCleanFailure("organized.pcd out.pcd");
}

TEST_F(ToolRobustness, NonFinitePointsGetLabelZeroAndChangeNothingElse) {
  const Cloud::Ptr clean = makeDumbbell(1500, 1).cloud;
  Cloud dirty;
  std::vector<std::size_t> where;
  for (std::size_t i = 0; i < clean->size(); ++i) {
    if (i % 50 == 0)
      dirty.push_back(pcl::PointXYZ(kNaN, 0, 0));
    if (i % 70 == 0)
      dirty.push_back(pcl::PointXYZ(1, -kInf, 0));
    where.push_back(dirty.size());
    dirty.push_back((*clean)[i]);
  }
  dirty.is_dense = false;
  const auto a = segment(*clean), b = segment(dirty);
  ASSERT_EQ(b.size(), dirty.size());
  for (std::size_t i = 0; i < a.size(); ++i)
    ASSERT_EQ(a[i], b[where[i]]);
}

TEST_F(ToolRobustness, OrganizedCloudWithNanHoles) {
  const std::uint32_t w = 64, h = 48;
  Cloud::Ptr organized(new Cloud(w, h));
  for (std::uint32_t v = 0; v < h; ++v)
    for (std::uint32_t u = 0; u < w; ++u) {
      const float x = u * 0.05f, y = v * 0.05f;
      const bool hole = (u > 20 && u < 30 && v > 10 && v < 30) || (u * 7 + v * 3) % 11 == 0;
      (*organized)(u, v) =
          hole ? pcl::PointXYZ(kNaN, kNaN, kNaN)
               : pcl::PointXYZ(x, y, 0.5f * std::exp(-((x - 1) * (x - 1) + (y - 1) * (y - 1))));
    }
  organized->is_dense = false;
  const auto labels = segment(*organized); // checks the layout is kept
  EXPECT_EQ(labels, libraryLabels(organized));
}

TEST_F(ToolRobustness, FewPoints) {
  // 1, 2, k and k + 1 points (k = 10), and fewer points than a k of 50.
  for (std::size_t n : {1u, 2u, 10u, 11u}) {
    const Cloud::Ptr c = randomCube(n, n);
    const auto labels = segment(*c);
    EXPECT_EQ(labels, libraryLabels(c)) << n << " points";
  }
  segment(*randomCube(7, 7), "-k 50 -segments 3");
}

TEST_F(ToolRobustness, DuplicatedPoints) {
  Cloud same;
  for (int i = 0; i < 2000; ++i)
    same.push_back(pcl::PointXYZ(0.25f, 0.5f, -1.0f));
  const auto one = segment(same);
  EXPECT_EQ(std::set<std::uint32_t>(one.begin(), one.end()), std::set<std::uint32_t>{1});
  // Every point of a shape written twice: copies get their original's label.
  const Cloud::Ptr shape = makeDumbbell(1000, 2).cloud;
  Cloud twice(*shape);
  twice += *shape;
  const auto labels = segment(twice, "-segments 3");
  ASSERT_EQ(labels.size(), twice.size());
  for (std::size_t i = 0; i < shape->size(); ++i)
    ASSERT_EQ(labels[i], labels[i + shape->size()]);
}

TEST_F(ToolRobustness, CollinearAndCoplanarPoints) {
  Cloud line, plane;
  for (int i = 0; i < 800; ++i)
    line.push_back(pcl::PointXYZ(0.01f * i, -0.02f * i, 3.0f));
  for (int i = 0; i < 35; ++i)
    for (int j = 0; j < 35; ++j)
      plane.push_back(pcl::PointXYZ(static_cast<float>(i), static_cast<float>(j), 1.0f));
  segment(line);
  segment(plane);
  segment(plane, "-segments 4");
}

TEST_F(ToolRobustness, FarApartObjectsNeverShareASegment) {
  const Cloud::Ptr hand = makeHand(1200, 3).cloud;
  Cloud c;
  for (const float offset : {0.0f, 500.0f, -2e4f})
    for (const auto& p : *hand)
      c.push_back(pcl::PointXYZ(p.x + offset, p.y, p.z - offset));
  const auto labels = segment(c);
  ASSERT_EQ(labels.size(), c.size());
  std::vector<std::set<std::uint32_t>> per_object(3);
  for (std::size_t i = 0; i < c.size(); ++i)
    per_object[i / hand->size()].insert(labels[i]);
  for (std::size_t a = 0; a < 3; ++a)
    for (std::size_t b = a + 1; b < 3; ++b)
      for (std::uint32_t label : per_object[a])
        EXPECT_EQ(per_object[b].count(label), 0u) << "label " << label << " on two objects";
}

TEST_F(ToolRobustness, ScaledModelsSegmentTheSame) {
  const Cloud::Ptr hand = makeHand(2500, 5).cloud;
  const auto reference = segment(*hand, "-segments 6");
  const std::vector<int> ref(reference.begin(), reference.end());
  for (const double scale : {1e-3, 1e3}) {
    Cloud c;
    for (const auto& p : *hand)
      c.push_back(pcl::PointXYZ(static_cast<float>(p.x * scale), static_cast<float>(p.y * scale),
                                static_cast<float>(p.z * scale)));
    const auto labels = segment(c, "-segments 6");
    const double ri = randIndex(std::vector<int>(labels.begin(), labels.end()), ref);
    std::printf("tool, hand scaled by %g: Rand index vs original %.4f\n", scale, ri);
    EXPECT_GE(ri, 0.99);
  }
}

/** The tool's arguments that give a row this value: "-name value", or a switch alone when on
 * (empty when off, its default). A row that only CAD mode reads gets -cad as well. */
std::string optionFor(const pcl_ncut_seg::ParameterInfo& row, const std::string& value) {
  if (row.kind == pcl_ncut_seg::ValueKind::Switch)
    return value == "on" ? "-" + row.name : "";
  const std::string mode = row.stage == pcl_ncut_seg::Stage::Cad ? "-cad " : "";
  return mode + "-" + row.name + " " + value;
}

TEST_F(ToolRobustness, EveryOptionAtTheEdgesOfItsRange) {
  // Few points: -k 2147483647 joins every pair of them.
  const Cloud::Ptr shape = makeDumbbell(400, 3).cloud;
  // Every row of the parameter table at both ends of its range, its off word, each of its
  // choices, on and off (support/parameter_values.h); each shorthand; -paper.
  std::vector<std::string> options = {"-paper"};
  for (const pcl_ncut_seg::Shorthand& s : pcl_ncut_seg::parameterShorthands())
    options.push_back("-" + s.name);
  for (const pcl_ncut_seg::ParameterInfo& row : pcl_ncut_seg::parameterTable())
    for (const std::string& value : valuesAtTheEdges(row))
      if (!optionFor(row, value).empty())
        options.push_back(optionFor(row, value));
  for (const std::string& option : options) {
    SCOPED_TRACE(option);
    segment(*shape, option);
  }
}

TEST_F(ToolRobustness, EveryOptionJustPastItsRangeFailsCleanly) {
  save("in.pcd", *makeDumbbell(300, 4).cloud);
  for (const pcl_ncut_seg::ParameterInfo& row : pcl_ncut_seg::parameterTable()) {
    if (row.kind == pcl_ncut_seg::ValueKind::Switch)
      continue; // it takes no value
    std::vector<std::string> values = valuesJustPast(row);
    if (row.kind == pcl_ncut_seg::ValueKind::Integer && !std::isfinite(row.hi))
      values.push_back("2147483648"); // the tool reads an int
    for (const std::string& value : values)
      expectCleanFailure("in.pcd out.pcd -" + row.name + " " + value, "for -" + row.name + ":");
  }
  // Numbers written other than plainly.
  for (const char* options : {"-k 10.0", "-k 0x10", "-beta 0x1p3"})
    expectCleanFailure(std::string("in.pcd out.pcd ") + options);
}

} // namespace
