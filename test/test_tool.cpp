/*
 * The pcl_ncut_seg command, driven as a user would: run it in a scratch directory, read what it
 * wrote, and check that every kind of bad input fails with one line on stderr, a non-zero exit
 * status and no file left behind.
 */
#include <gtest/gtest.h>

#include <pcl/PCLPointCloud2.h>
#include <pcl/PolygonMesh.h>
#include <pcl/conversions.h>
#include <pcl/io/pcd_io.h>
#include <pcl/io/ply_io.h>
#include <pcl/point_cloud.h>
#include <pcl/point_types.h>

#include "support/text_files.h"

#include <pcl_ncut_seg/parameter_table.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <map>
#include <random>
#include <regex>
#include <set>
#include <sstream>
#include <string>
#include <vector>

namespace fs = std::filesystem;

using pcl_ncut_seg::test::lines;
using pcl_ncut_seg::test::listDir;
using pcl_ncut_seg::test::quote;
using pcl_ncut_seg::test::readText;

namespace {

const std::string kTool = PCL_NCUT_SEG_TOOL;
const std::string kDataDir = PCL_NCUT_SEG_DATA_DIR;

using ToolRun = pcl_ncut_seg::test::CommandRun;

/** A sphere of radius 1 with three capsules (radius 0.3, length 2.2) sticking out of it along
 * +x, +y and -x: a palm with three fingers, surface points only. Deterministic. */
pcl::PointCloud<pcl::PointXYZ>::Ptr makeShape() {
  struct Capsule {
    Eigen::Vector3f a, b; // axis from a to b
    float r;
  };
  const float R = 1.0f, r = 0.3f, len = 2.2f;
  const std::vector<Eigen::Vector3f> dirs = {{1, 0, 0}, {0, 1, 0}, {-1, 0, 0}};
  std::vector<Capsule> capsules;
  for (const auto& d : dirs)
    capsules.push_back({d * 0.5f * R, d * (R + len), r});
  auto distToSegment = [](const Eigen::Vector3f& p, const Capsule& c) {
    const Eigen::Vector3f ab = c.b - c.a;
    const float t = std::clamp((p - c.a).dot(ab) / ab.squaredNorm(), 0.0f, 1.0f);
    return (p - (c.a + t * ab)).norm();
  };
  auto inside = [&](const Eigen::Vector3f& p, int skip_capsule, bool skip_sphere) {
    if (!skip_sphere && p.norm() < R - 1e-4f)
      return true;
    for (int i = 0; i < static_cast<int>(capsules.size()); ++i)
      if (i != skip_capsule && distToSegment(p, capsules[i]) < capsules[i].r - 1e-4f)
        return true;
    return false;
  };

  std::mt19937 rng(42);
  std::normal_distribution<float> gauss(0.0f, 1.0f);
  std::uniform_real_distribution<float> uni(0.0f, 1.0f);
  auto randomDirection = [&]() {
    Eigen::Vector3f v(gauss(rng), gauss(rng), gauss(rng));
    return Eigen::Vector3f(v.normalized());
  };

  pcl::PointCloud<pcl::PointXYZ>::Ptr cloud(new pcl::PointCloud<pcl::PointXYZ>);
  auto add = [&](const Eigen::Vector3f& p) {
    cloud->push_back(pcl::PointXYZ(p.x(), p.y(), p.z()));
  };
  for (int i = 0; i < 1400; ++i) {
    const Eigen::Vector3f p = R * randomDirection();
    if (!inside(p, -1, true))
      add(p);
  }
  for (int c = 0; c < static_cast<int>(capsules.size()); ++c) {
    const Capsule& cap = capsules[c];
    const Eigen::Vector3f axis = (cap.b - cap.a).normalized();
    const Eigen::Vector3f u = axis.unitOrthogonal(), v = axis.cross(u);
    const float height = (cap.b - cap.a).norm();
    // Cylinder side and the end cap, by area.
    const float side = 2 * float(M_PI) * cap.r * height, end = 2 * float(M_PI) * cap.r * cap.r;
    const int n = 500;
    for (int i = 0; i < n; ++i) {
      Eigen::Vector3f p;
      if (uni(rng) < side / (side + end)) {
        const float phi = 2 * float(M_PI) * uni(rng);
        p = cap.a + uni(rng) * height * axis + cap.r * (std::cos(phi) * u + std::sin(phi) * v);
      } else {
        Eigen::Vector3f d = randomDirection();
        if (d.dot(axis) < 0)
          d -= 2 * d.dot(axis) * axis;
        p = cap.b + cap.r * d;
      }
      if (!inside(p, c, false))
        add(p);
    }
  }
  cloud->width = static_cast<std::uint32_t>(cloud->size());
  cloud->height = 1;
  cloud->is_dense = true;
  return cloud;
}

/** Two spheres far apart. */
pcl::PointCloud<pcl::PointXYZ>::Ptr makeTwoSpheres() {
  pcl::PointCloud<pcl::PointXYZ>::Ptr cloud(new pcl::PointCloud<pcl::PointXYZ>);
  const int n = 600;
  for (int s = 0; s < 2; ++s)
    for (int i = 0; i < n; ++i) { // Fibonacci sphere
      const float z = 1.0f - 2.0f * (i + 0.5f) / n, rho = std::sqrt(1.0f - z * z);
      const float phi = static_cast<float>(i) * 2.39996323f;
      cloud->push_back(pcl::PointXYZ(rho * std::cos(phi) + 10.0f * s, rho * std::sin(phi), z));
    }
  return cloud;
}

/** What the tool wrote: fields and points. */
struct Output {
  std::vector<std::string> fields;
  pcl::PointCloud<pcl::PointXYZRGBL> cloud;
};

::testing::AssertionResult readOutput(const fs::path& path, Output& output) {
  pcl::PCLPointCloud2 blob;
  if (pcl::io::loadPCDFile(path.string(), blob) < 0)
    return ::testing::AssertionFailure() << "cannot read " << path;
  for (const auto& f : blob.fields)
    output.fields.push_back(f.name);
  pcl::fromPCLPointCloud2(blob, output.cloud);
  return ::testing::AssertionSuccess();
}

/** A closed triangle mesh: a UV sphere of radius 1 stretched to 3 along x (a cigar), with
 * the given numbers of rings and segments. Faces are triangles, or quads where quads = true. */
struct TestMesh {
  std::vector<Eigen::Vector3f> vertices;
  std::vector<std::vector<int>> faces;
};

TestMesh makeCigar(int rings, int sectors, bool quads) {
  TestMesh m;
  m.vertices.emplace_back(-3.0f, 0.0f, 0.0f); // pole 0
  for (int i = 1; i < rings; ++i) {
    const float theta = float(M_PI) * i / rings;
    for (int j = 0; j < sectors; ++j) {
      const float phi = 2 * float(M_PI) * j / sectors;
      m.vertices.emplace_back(-3.0f * std::cos(theta), std::sin(theta) * std::cos(phi),
                              std::sin(theta) * std::sin(phi));
    }
  }
  m.vertices.emplace_back(3.0f, 0.0f, 0.0f); // pole 1
  const int last = static_cast<int>(m.vertices.size()) - 1;
  auto ring = [&](int i, int j) { return 1 + (i - 1) * sectors + (j % sectors); };
  for (int j = 0; j < sectors; ++j) {
    m.faces.push_back({0, ring(1, j + 1), ring(1, j)});
    m.faces.push_back({last, ring(rings - 1, j), ring(rings - 1, j + 1)});
  }
  for (int i = 1; i + 1 < rings; ++i)
    for (int j = 0; j < sectors; ++j) {
      const int a = ring(i, j), b = ring(i, j + 1), c = ring(i + 1, j + 1), d = ring(i + 1, j);
      if (quads) {
        m.faces.push_back({a, b, c, d});
      } else {
        m.faces.push_back({a, b, c});
        m.faces.push_back({a, c, d});
      }
    }
  return m;
}

std::string toOff(const TestMesh& m) {
  std::ostringstream s;
  s.precision(9); // every float exactly, as in the PLY
  s << "OFF\n" << m.vertices.size() << " " << m.faces.size() << " 0\n";
  for (const auto& v : m.vertices)
    s << v.x() << " " << v.y() << " " << v.z() << "\n";
  for (const auto& f : m.faces) {
    s << f.size();
    for (int i : f)
      s << " " << i;
    s << "\n";
  }
  return s.str();
}

std::string toObj(const TestMesh& m) {
  std::ostringstream s;
  s.precision(9);
  s << "# a cigar\no cigar\n";
  for (const auto& v : m.vertices)
    s << "v " << v.x() << " " << v.y() << " " << v.z() << "\n";
  s << "vn 0 0 1\n";
  for (const auto& f : m.faces) {
    s << "f";
    for (int i : f)
      s << " " << (i + 1) << "//1";
    s << "\n";
  }
  return s.str();
}

pcl::PolygonMesh toPolygonMesh(const TestMesh& m) {
  pcl::PointCloud<pcl::PointXYZ> vertices;
  for (const auto& v : m.vertices)
    vertices.push_back(pcl::PointXYZ(v.x(), v.y(), v.z()));
  pcl::PolygonMesh mesh;
  pcl::toPCLPointCloud2(vertices, mesh.cloud);
  for (const auto& f : m.faces) {
    pcl::Vertices polygon;
    for (int i : f)
      polygon.vertices.push_back(static_cast<std::uint32_t>(i));
    mesh.polygons.push_back(polygon);
  }
  return mesh;
}

/** The number after "t :" in the tool's report, or -1. */
long printedSegments(const std::string& out) {
  const std::regex t_line("^t\\s*:\\s*([0-9]+)\\b.*");
  for (const std::string& line : lines(out)) {
    std::smatch m;
    if (std::regex_match(line, m, t_line))
      return std::stol(m[1]);
  }
  return -1;
}

class ToolTest : public ::testing::Test {
protected:
  void SetUp() override {
    root_ = pcl_ncut_seg::test::makeTempDir("pcl_ncut_seg_tool");
    ASSERT_FALSE(root_.empty());
    dir_ = root_ / "run";
    fs::create_directory(dir_);
    ASSERT_TRUE(fs::exists(kTool)) << kTool;
  }
  void TearDown() override {
    std::error_code ec;
    fs::permissions(dir_, fs::perms::owner_all, fs::perm_options::add, ec);
    for (const auto& entry : fs::recursive_directory_iterator(root_, ec))
      if (entry.is_directory())
        fs::permissions(entry.path(), fs::perms::owner_all, fs::perm_options::add, ec);
    fs::remove_all(root_, ec);
  }

  /** Run the tool in dir_ with these (shell-quoted where needed) arguments. */
  ToolRun run(const std::string& args) const {
    return pcl_ncut_seg::test::runCommand("cd " + quote(dir_.string()) + " && " + quote(kTool) +
                                              " " + args,
                                          root_ / "stdout.txt", root_ / "stderr.txt");
  }

  /** The tool failed as it should: non-zero exit, exactly one line on stderr, and the run
   * directory holds exactly what it held before. */
  void expectCleanFailure(const std::string& args, const std::string& mention = "") {
    SCOPED_TRACE("pcl_ncut_seg " + args);
    const std::set<std::string> before = listDir(dir_);
    const ToolRun r = run(args);
    EXPECT_NE(r.status, 0);
    EXPECT_NE(r.status, -1) << "the tool crashed";
    const std::vector<std::string> err_lines = lines(r.err);
    ASSERT_EQ(err_lines.size(), 1u) << "stderr:\n" << r.err;
    EXPECT_FALSE(err_lines[0].empty());
    if (!mention.empty()) {
      EXPECT_NE(err_lines[0].find(mention), std::string::npos) << err_lines[0];
    }
    EXPECT_EQ(listDir(dir_), before) << "the run left files behind";
  }

  void writeFile(const std::string& name, const std::string& contents) const {
    std::ofstream(dir_ / name, std::ios::binary) << contents;
  }

  fs::path root_, dir_;
};

TEST_F(ToolTest, HelpListsEveryOptionWithItsDefault) {
  const ToolRun r = run("-h");
  EXPECT_EQ(r.status, 0);
  // Every parameter of the table, then the tool's own flags.
  std::vector<std::string> options;
  for (const pcl_ncut_seg::ParameterInfo& row : pcl_ncut_seg::parameterTable())
    options.push_back("-" + row.name);
  for (const char* option :
       {"-paper", "-exact", "-samples", "-seed", "-add", "-ascii", "-binary", "-split", "-quiet"})
    options.push_back(option);
  for (const std::string& option : options) {
    bool found = false;
    for (const std::string& line : lines(r.out))
      if (line.find(option + " ") != std::string::npos && line.find("default") != std::string::npos)
        found = true;
    EXPECT_TRUE(found) << option << " missing from the help, or without a default:\n" << r.out;
  }
  EXPECT_TRUE(listDir(dir_).empty());
}

TEST_F(ToolTest, DefaultRunSegmentsTheBundledModel) {
  if (!fs::exists(fs::path(kDataDir) / "armadillo.pcd"))
    GTEST_SKIP() << "no bundled model in " << kDataDir;
  const ToolRun r = run("");
  ASSERT_EQ(r.status, 0) << r.out << r.err;
  EXPECT_EQ(listDir(dir_), std::set<std::string>{"armadillo_segments.pcd"});

  for (const char* phase : {"kNN", "Cen", "Snod", "LRef", "HSeg", "PSeg"}) {
    const std::regex phase_line(std::string("^") + phase + "\\s*:\\s*[0-9.]+ s$");
    bool found = false;
    for (const std::string& line : lines(r.out))
      found = found || std::regex_match(line, phase_line);
    EXPECT_TRUE(found) << "no time for " << phase << " in:\n" << r.out;
  }
  for (const char* count : {"n", "m", "l"}) {
    const std::regex count_line(std::string("^") + count + "\\s*:\\s*[0-9]+ .*");
    bool found = false;
    for (const std::string& line : lines(r.out))
      found = found || std::regex_match(line, count_line);
    EXPECT_TRUE(found) << "no " << count << " in:\n" << r.out;
  }
  const long t = printedSegments(r.out);
  // At least its arms, legs and tail apart from the body (data/README.md).
  ASSERT_GE(t, 6) << r.out;

  Output output;
  ASSERT_TRUE(readOutput(dir_ / "armadillo_segments.pcd", output));
  for (const char* field : {"x", "y", "z", "rgb", "label"})
    EXPECT_NE(std::find(output.fields.begin(), output.fields.end(), field), output.fields.end())
        << "no field " << field;

  pcl::PointCloud<pcl::PointXYZ> input;
  ASSERT_EQ(pcl::io::loadPCDFile(kDataDir + "/armadillo.pcd", input), 0);
  ASSERT_EQ(output.cloud.size(), input.size());

  // Labels 1..t, all used; one colour per label, different labels in different colours.
  std::map<std::uint32_t, std::uint32_t> colour_of;
  std::set<std::uint32_t> colours;
  for (std::size_t i = 0; i < output.cloud.size(); ++i) {
    const auto& p = output.cloud[i];
    EXPECT_EQ(p.x, input[i].x);
    ASSERT_GE(p.label, 1u);
    ASSERT_LE(p.label, static_cast<std::uint32_t>(t));
    const std::uint32_t rgb = p.rgba & 0xFFFFFFu;
    const auto it = colour_of.emplace(p.label, rgb).first;
    ASSERT_EQ(it->second, rgb) << "label " << p.label << " has two colours";
  }
  EXPECT_EQ(static_cast<long>(colour_of.size()), t);
  for (const auto& lc : colour_of)
    colours.insert(lc.second);
  EXPECT_EQ(colours.size(), colour_of.size()) << "two segments share a colour";
}

TEST_F(ToolTest, SegmentsAGeneratedShapeIntoTheRequestedNumberOfSegments) {
  auto cloud = makeShape();
  // One point with no coordinates: kept in the output, in no segment.
  pcl::PointXYZ nan_point;
  nan_point.x = nan_point.y = nan_point.z = std::numeric_limits<float>::quiet_NaN();
  cloud->push_back(nan_point);
  cloud->is_dense = false;
  ASSERT_EQ(pcl::io::savePCDFileBinary((dir_ / "shape.pcd").string(), *cloud), 0);

  const ToolRun r = run("shape.pcd out.pcd -segments 2 -k 10 -threads 2");
  ASSERT_EQ(r.status, 0) << r.out << r.err;
  EXPECT_EQ(printedSegments(r.out), 2) << r.out;
  EXPECT_EQ(listDir(dir_), (std::set<std::string>{"shape.pcd", "out.pcd"}));

  Output output;
  ASSERT_TRUE(readOutput(dir_ / "out.pcd", output));
  ASSERT_EQ(output.cloud.size(), cloud->size());
  std::set<std::uint32_t> labels;
  for (std::size_t i = 0; i + 1 < output.cloud.size(); ++i) {
    EXPECT_EQ(output.cloud[i].x, (*cloud)[i].x);
    EXPECT_EQ(output.cloud[i].z, (*cloud)[i].z);
    labels.insert(output.cloud[i].label);
  }
  EXPECT_EQ(labels, (std::set<std::uint32_t>{1, 2}));
  EXPECT_EQ(output.cloud.back().label, 0u) << "a NaN point must be in no segment";
  EXPECT_EQ(output.cloud.back().rgba & 0xFFFFFFu, 0u) << "a point in no segment is black";
}

TEST_F(ToolTest, ReadsPlyAndNamesTheOutputAfterTheInput) {
  ASSERT_EQ(pcl::io::savePLYFileBinary((dir_ / "spheres.ply").string(), *makeTwoSpheres()), 0);
  const ToolRun r = run("spheres.ply -quiet");
  ASSERT_EQ(r.status, 0) << r.out << r.err;
  EXPECT_TRUE(lines(r.out).empty()) << "-quiet printed:\n" << r.out;
  EXPECT_EQ(listDir(dir_), (std::set<std::string>{"spheres.ply", "spheres_segments.pcd"}));
  Output output;
  ASSERT_TRUE(readOutput(dir_ / "spheres_segments.pcd", output));
  ASSERT_EQ(output.cloud.size(), 1200u);
  // The two spheres never share a segment.
  std::set<std::uint32_t> left, right;
  for (std::size_t i = 0; i < output.cloud.size(); ++i)
    (i < 600 ? left : right).insert(output.cloud[i].label);
  for (std::uint32_t label : left)
    EXPECT_EQ(right.count(label), 0u) << "label " << label << " on both spheres";
}

TEST_F(ToolTest, AcceptsEveryOption) {
  ASSERT_EQ(pcl::io::savePCDFileBinary((dir_ / "shape.pcd").string(), *makeShape()), 0);
  const ToolRun r =
      run("shape.pcd out.pcd -k 12 -cen_samples 30 -crossing 0.3 -area 0.01 -height 0.01 "
          "-beta 2 -alpha1 2 -alpha2 0.5 -threshold 0.05 -splits 50 -threads 1 -paper");
  ASSERT_EQ(r.status, 0) << r.out << r.err;
  EXPECT_GE(printedSegments(r.out), 1) << r.out;
  EXPECT_TRUE(fs::exists(dir_ / "out.pcd"));
}

TEST_F(ToolTest, PaperIsAPresetTheFlagsApplyOnTop) {
  ASSERT_EQ(pcl::io::savePCDFileBinary((dir_ / "shape.pcd").string(), *makeShape()), 0);
  // -paper is every parameter at its value in Parameters::paper(), spelt out...
  const pcl_ncut_seg::Parameters paper = pcl_ncut_seg::Parameters::paper();
  std::string spelt;
  for (const pcl_ncut_seg::ParameterInfo& row : pcl_ncut_seg::parameterTable())
    if (row.kind != pcl_ncut_seg::ValueKind::Switch && row.name != "segments")
      spelt += " -" + row.name + " " + row.get(paper);
  ASSERT_EQ(run("shape.pcd paper.pcd -paper").status, 0);
  ASSERT_EQ(run("shape.pcd spelt.pcd" + spelt).status, 0);
  EXPECT_EQ(readText(dir_ / "paper.pcd"), readText(dir_ / "spelt.pcd"));
  ASSERT_EQ(run("shape.pcd spelt.pcd -threshold 0.05" + spelt).status, 1) << "given twice";
  // ... and a flag given with it changes its parameter only, wherever it stands.
  ASSERT_EQ(run("shape.pcd paper_k.pcd -paper -k 14 -concavity 3").status, 0);
  ASSERT_EQ(run("shape.pcd k_paper.pcd -k 14 -concavity 3 -paper").status, 0);
  EXPECT_EQ(readText(dir_ / "paper_k.pcd"), readText(dir_ / "k_paper.pcd"));
  std::string spelt_k = spelt;
  for (const auto& [from, to] : {std::pair<std::string, std::string>{" -k 10", " -k 14"},
                                 {" -concavity off", " -concavity 3"}}) {
    ASSERT_NE(spelt_k.find(from), std::string::npos) << spelt_k;
    spelt_k.replace(spelt_k.find(from), from.size(), to);
  }
  ASSERT_EQ(run("shape.pcd spelt_k.pcd" + spelt_k).status, 0);
  EXPECT_EQ(readText(dir_ / "paper_k.pcd"), readText(dir_ / "spelt_k.pcd"));
  EXPECT_NE(readText(dir_ / "paper_k.pcd"), readText(dir_ / "spelt.pcd"));
}

TEST_F(ToolTest, OldSpellingsAreAliases) {
  ASSERT_EQ(pcl::io::savePCDFileBinary((dir_ / "shape.pcd").string(), *makeShape()), 0);
  ASSERT_EQ(run("shape.pcd new.pcd -crossing_fraction 0.25 -crease_split 0.5 -crease_cut 0.5 "
                "-flat_elongation 0.2 -neck_exponent 2 -boundary_band 0.1 -centrality_samples 40")
                .status,
            0);
  ASSERT_EQ(run("shape.pcd old.pcd -crossing 0.25 -crease 0.5 -creasecut 0.5 -flat 0.2 -neck 2 "
                "-band 0.1 -cen_samples 40")
                .status,
            0);
  EXPECT_EQ(readText(dir_ / "new.pcd"), readText(dir_ / "old.pcd"));
  expectCleanFailure("shape.pcd twice.pcd -crease 0.5 -crease_split 0.5", "-crease");
}

TEST_F(ToolTest, OverwritesAnExistingOutput) {
  ASSERT_EQ(pcl::io::savePCDFileBinary((dir_ / "shape.pcd").string(), *makeShape()), 0);
  writeFile("out.pcd", "old contents\n");
  const ToolRun r = run("shape.pcd out.pcd -segments 3");
  ASSERT_EQ(r.status, 0) << r.out << r.err;
  Output output;
  ASSERT_TRUE(readOutput(dir_ / "out.pcd", output));
  EXPECT_EQ(listDir(dir_), (std::set<std::string>{"shape.pcd", "out.pcd"}));
}

TEST_F(ToolTest, BadInputFilesFailCleanly) {
  ASSERT_EQ(pcl::io::savePCDFileBinary((dir_ / "shape.pcd").string(), *makeShape()), 0);
  expectCleanFailure("missing.pcd out.pcd", "missing.pcd");
  expectCleanFailure("missing.ply out.pcd", "missing.ply");

  writeFile("zero_bytes.pcd", "");
  expectCleanFailure("zero_bytes.pcd out.pcd", "zero_bytes.pcd");
  writeFile("garbage.ply", "this is not a ply file\n");
  expectCleanFailure("garbage.ply out.pcd", "garbage.ply");

  writeFile("empty_cloud.pcd", "# .PCD v0.7 - Point Cloud Data file format\n"
                               "VERSION 0.7\nFIELDS x y z\nSIZE 4 4 4\nTYPE F F F\nCOUNT 1 1 1\n"
                               "WIDTH 0\nHEIGHT 1\nVIEWPOINT 0 0 0 1 0 0 0\nPOINTS 0\n"
                               "DATA ascii\n");
  expectCleanFailure("empty_cloud.pcd out.pcd", "empty_cloud.pcd");

  pcl::PointCloud<pcl::Intensity> intensity;
  for (int i = 0; i < 50; ++i) {
    pcl::Intensity p;
    p.intensity = static_cast<float>(i);
    intensity.push_back(p);
  }
  ASSERT_EQ(pcl::io::savePCDFileASCII((dir_ / "intensity.pcd").string(), intensity), 0);
  expectCleanFailure("intensity.pcd out.pcd", "intensity.pcd");

  pcl::PointCloud<pcl::PointXYZ> nans;
  nans.push_back(pcl::PointXYZ(std::nanf(""), 0, 0));
  nans.push_back(pcl::PointXYZ(0, std::nanf(""), 0));
  nans.is_dense = false;
  ASSERT_EQ(pcl::io::savePCDFileBinary((dir_ / "nans.pcd").string(), nans), 0);
  expectCleanFailure("nans.pcd out.pcd", "nans.pcd");

  fs::create_directory(dir_ / "a_directory.pcd");
  expectCleanFailure("a_directory.pcd out.pcd", "a_directory.pcd");
  expectCleanFailure("shape.xyz out.pcd", "shape.xyz");
  expectCleanFailure("shape.pcd out.pcd extra.pcd");
}

TEST_F(ToolTest, UnknownFlagsFailCleanly) {
  ASSERT_EQ(pcl::io::savePCDFileBinary((dir_ / "shape.pcd").string(), *makeShape()), 0);
  expectCleanFailure("shape.pcd out.pcd -bogus", "-bogus");
  expectCleanFailure("shape.pcd out.pcd -bogus 3", "-bogus");
  expectCleanFailure("-K 10 shape.pcd out.pcd", "-K");
  expectCleanFailure("shape.pcd out.pcd --k 10", "--k");
}

TEST_F(ToolTest, BadParameterValuesFailCleanly) {
  ASSERT_EQ(pcl::io::savePCDFileBinary((dir_ / "shape.pcd").string(), *makeShape()), 0);
  const std::vector<std::pair<std::string, std::string>> bad = {
      {"-k", "1"},        {"-k", "abc"},          {"-k", "2.5"},          {"-k", "10x"},
      {"-k", "''"},       {"-cen_samples", "-1"}, {"-crossing", "1.5"},   {"-crossing", "-0.1"},
      {"-area", "2"},     {"-height", "nan"},     {"-beta", "0"},         {"-beta", "-1"},
      {"-alpha1", "inf"}, {"-alpha2", "0"},       {"-threshold", "-0.1"}, {"-threshold", "nan"},
      {"-segments", "0"}, {"-splits", "0"},       {"-threads", "-1"},     {"-k", "99999999999999"}};
  for (const auto& option_value : bad)
    expectCleanFailure("shape.pcd out.pcd " + option_value.first + " " + option_value.second,
                       option_value.first);
  expectCleanFailure("shape.pcd out.pcd -k", "-k");        // no value
  expectCleanFailure("shape.pcd out.pcd -k 8 -k 9", "-k"); // given twice
  expectCleanFailure("shape.pcd out.pcd -threshold 0.1 -segments 3");
}

TEST_F(ToolTest, UnwritableOutputFailsCleanly) {
  ASSERT_EQ(pcl::io::savePCDFileBinary((dir_ / "shape.pcd").string(), *makeShape()), 0);
  expectCleanFailure("shape.pcd no_such_dir/out.pcd", "no_such_dir/out.pcd");
  expectCleanFailure("shape.pcd out.txt", "out.txt");
  expectCleanFailure("shape.pcd /proc/out.pcd", "/proc/out.pcd");

  // A read-only directory (root writes anywhere, so only as another user).
  if (::geteuid() != 0) {
    fs::create_directory(dir_ / "read_only");
    fs::permissions(dir_ / "read_only", fs::perms::owner_read | fs::perms::owner_exec);
    expectCleanFailure("shape.pcd read_only/out.pcd", "read_only/out.pcd");
    EXPECT_TRUE(fs::is_empty(dir_ / "read_only"));
  }

  // A failed run leaves an existing output as it was.
  writeFile("out.pcd", "old contents\n");
  expectCleanFailure("missing.pcd out.pcd");
  EXPECT_EQ(readText(dir_ / "out.pcd"), "old contents\n");
}

} // namespace

namespace {

/** The DATA line of a PCD file. */
std::string pcdDataType(const fs::path& path) {
  std::ifstream in(path);
  std::string line;
  while (std::getline(in, line))
    if (line.rfind("DATA ", 0) == 0)
      return line.substr(5);
  return "";
}

TEST_F(ToolTest, ReportsPhasesCountsAndPeakMemory) {
  ASSERT_EQ(pcl::io::savePCDFileBinary((dir_ / "shape.pcd").string(), *makeShape()), 0);
  const ToolRun r = run("shape.pcd out.pcd -segments 3");
  ASSERT_EQ(r.status, 0) << r.out << r.err;
  EXPECT_TRUE(r.err.empty()) << "stderr is not a terminal: no progress bar expected\n" << r.err;
  const std::vector<std::string> out = lines(r.out);
  for (const char* phase : {"kNN", "Cen", "Snod", "LRef", "HSeg", "PSeg", "total"}) {
    const std::regex phase_line(std::string("^") + phase + "\\s*:\\s*[0-9.]+ s$");
    EXPECT_TRUE(std::any_of(out.begin(), out.end(),
                            [&](const std::string& l) { return std::regex_match(l, phase_line); }))
        << phase << " missing:\n"
        << r.out;
  }
  for (const char* count : {"n", "m", "l", "t"}) {
    const std::regex count_line(std::string("^") + count + "\\s*:\\s*[0-9]+ .*");
    EXPECT_TRUE(std::any_of(out.begin(), out.end(),
                            [&](const std::string& l) { return std::regex_match(l, count_line); }))
        << count << " missing:\n"
        << r.out;
  }
  const std::regex mem_line("^mem\\s*:\\s*([0-9.]+) MiB peak resident memory$");
  double mib = -1;
  for (const std::string& l : out) {
    std::smatch m;
    if (std::regex_match(l, m, mem_line))
      mib = std::stod(m[1]);
  }
  EXPECT_GT(mib, 1.0) << r.out; // a process with PCL loaded uses more than 1 MiB
  EXPECT_LT(mib, 4096.0) << r.out;
}

TEST_F(ToolTest, ProgressBarOnATerminalOnly) {
  if (std::system("command -v script >/dev/null 2>&1") != 0)
    GTEST_SKIP() << "no 'script' command (util-linux) to run the tool on a terminal";
  ASSERT_EQ(pcl::io::savePCDFileBinary((dir_ / "shape.pcd").string(), *makeShape()), 0);
  // On a pseudo-terminal, with the bar's delay at 0 s instead of 1 s so that every phase shows.
  auto onTerminal = [&](const std::string& args) {
    const fs::path typescript = root_ / "typescript.txt";
    const std::string cmd = "cd " + quote(dir_.string()) +
                            " && PCL_NCUT_SEG_PROGRESS_DELAY=0 script -qec " +
                            quote(quote(kTool) + " " + args) + " /dev/null >" +
                            quote(typescript.string()) + " 2>&1 </dev/null";
    EXPECT_EQ(std::system(cmd.c_str()), 0);
    return readText(typescript);
  };
  const std::string shown = onTerminal("shape.pcd out.pcd -segments 3 -cen_samples 200");
  EXPECT_NE(shown.find("Cen   ["), std::string::npos) << shown;
  EXPECT_NE(shown.find("%"), std::string::npos) << shown;
  EXPECT_NE(shown.find("\r\x1b[K"), std::string::npos) << "the bar is not cleared";
  const std::string quiet = onTerminal("shape.pcd out2.pcd -segments 3 -quiet");
  EXPECT_EQ(quiet.find("Cen   ["), std::string::npos) << quiet;
  EXPECT_TRUE(fs::exists(dir_ / "out.pcd"));
  EXPECT_TRUE(fs::exists(dir_ / "out2.pcd"));
}

TEST_F(ToolTest, BinaryByDefaultAsciiOnRequest) {
  ASSERT_EQ(pcl::io::savePCDFileBinary((dir_ / "shape.pcd").string(), *makeShape()), 0);
  ASSERT_EQ(run("shape.pcd binary.pcd -segments 3 -quiet").status, 0);
  ASSERT_EQ(run("shape.pcd ascii.pcd -segments 3 -quiet -ascii").status, 0);
  ASSERT_EQ(run("shape.pcd old.pcd -segments 3 -quiet -binary").status, 0); // older scripts
  EXPECT_EQ(pcdDataType(dir_ / "binary.pcd"), "binary");
  EXPECT_EQ(pcdDataType(dir_ / "ascii.pcd"), "ascii");
  EXPECT_EQ(readText(dir_ / "old.pcd"), readText(dir_ / "binary.pcd"));
  Output a, b;
  ASSERT_TRUE(readOutput(dir_ / "ascii.pcd", a));
  ASSERT_TRUE(readOutput(dir_ / "binary.pcd", b));
  ASSERT_EQ(a.cloud.size(), b.cloud.size());
  for (std::size_t i = 0; i < a.cloud.size(); ++i) { // ASCII keeps every float exactly
    ASSERT_EQ(a.cloud[i].x, b.cloud[i].x);
    ASSERT_EQ(a.cloud[i].y, b.cloud[i].y);
    ASSERT_EQ(a.cloud[i].label, b.cloud[i].label);
    ASSERT_EQ(a.cloud[i].rgba & 0xFFFFFFu, b.cloud[i].rgba & 0xFFFFFFu);
  }
  expectCleanFailure("shape.pcd both.pcd -segments 3 -ascii -binary", "-ascii");
}

TEST_F(ToolTest, AddKeepsEveryInputFieldAndAddsLabel) {
  pcl::PointCloud<pcl::PointXYZI> input;
  const auto shape = makeShape(); // kept alive: a range-for does not extend a temporary's owner
  for (const auto& p : *shape) {
    pcl::PointXYZI q;
    q.x = p.x, q.y = p.y, q.z = p.z;
    q.intensity = static_cast<float>(input.size()) * 0.5f;
    input.push_back(q);
  }
  ASSERT_EQ(pcl::io::savePCDFileBinary((dir_ / "intensity.pcd").string(), input), 0);
  const ToolRun r = run("intensity.pcd out.pcd -segments 3 -add");
  ASSERT_EQ(r.status, 0) << r.out << r.err;
  EXPECT_TRUE(r.err.empty()) << r.err;
  pcl::PCLPointCloud2 blob;
  ASSERT_EQ(pcl::io::loadPCDFile((dir_ / "out.pcd").string(), blob), 0);
  std::vector<std::string> fields;
  for (const auto& f : blob.fields)
    fields.push_back(f.name);
  EXPECT_EQ(fields, (std::vector<std::string>{"x", "y", "z", "intensity", "label"}));
  struct XYZIL {
    float x, y, z, intensity;
    std::uint32_t label;
  };
  ASSERT_EQ(blob.point_step, sizeof(XYZIL));
  ASSERT_EQ(blob.width * blob.height, input.size());
  std::set<std::uint32_t> labels;
  for (std::size_t i = 0; i < input.size(); ++i) {
    XYZIL p;
    std::memcpy(&p, &blob.data[i * blob.point_step], sizeof(p));
    ASSERT_EQ(p.x, input[i].x);
    ASSERT_EQ(p.intensity, input[i].intensity);
    labels.insert(p.label);
  }
  EXPECT_EQ(labels, (std::set<std::uint32_t>{1, 2, 3}));

  // An input that has a label already: a warning, and the label is replaced.
  pcl::PointCloud<pcl::PointXYZL> labelled;
  for (const auto& p : *shape) {
    pcl::PointXYZL q;
    q.x = p.x, q.y = p.y, q.z = p.z;
    q.label = 77;
    labelled.push_back(q);
  }
  ASSERT_EQ(pcl::io::savePCDFileBinary((dir_ / "labelled.pcd").string(), labelled), 0);
  const ToolRun w = run("labelled.pcd out2.pcd -segments 2 -add");
  ASSERT_EQ(w.status, 0) << w.out << w.err;
  ASSERT_EQ(lines(w.err).size(), 1u) << w.err;
  EXPECT_NE(lines(w.err)[0].find("label"), std::string::npos) << w.err;
  pcl::PointCloud<pcl::PointXYZL> relabelled;
  ASSERT_EQ(pcl::io::loadPCDFile((dir_ / "out2.pcd").string(), relabelled), 0);
  std::set<std::uint32_t> new_labels;
  for (const auto& p : relabelled)
    new_labels.insert(p.label);
  EXPECT_EQ(new_labels, (std::set<std::uint32_t>{1, 2}));
}

TEST_F(ToolTest, SplitWritesOneFilePerSegment) {
  ASSERT_EQ(pcl::io::savePCDFileBinary((dir_ / "shape.pcd").string(), *makeShape()), 0);
  const ToolRun r = run("shape.pcd out.pcd -segments 3 -split part");
  ASSERT_EQ(r.status, 0) << r.out << r.err;
  EXPECT_EQ(listDir(dir_), (std::set<std::string>{"shape.pcd", "out.pcd", "part_1.pcd",
                                                  "part_2.pcd", "part_3.pcd"}));
  Output all;
  ASSERT_TRUE(readOutput(dir_ / "out.pcd", all));
  std::size_t total = 0;
  for (std::uint32_t label = 1; label <= 3; ++label) {
    Output part;
    ASSERT_TRUE(readOutput(dir_ / ("part_" + std::to_string(label) + ".pcd"), part));
    EXPECT_EQ(part.fields, all.fields);
    std::size_t expected = 0;
    for (const auto& p : all.cloud)
      expected += p.label == label;
    EXPECT_EQ(part.cloud.size(), expected);
    for (const auto& p : part.cloud)
      EXPECT_EQ(p.label, label);
    total += part.cloud.size();
  }
  EXPECT_EQ(total, all.cloud.size());
  // An unwritable prefix fails before any work, and leaves nothing.
  expectCleanFailure("shape.pcd out3.pcd -segments 3 -split no_such_dir/part", "no_such_dir");
}

TEST_F(ToolTest, ReadsMeshesAsFaceCentroidsOrAreaSamples) {
  const TestMesh triangles = makeCigar(24, 32, false), quads = makeCigar(24, 32, true);
  writeFile("cigar.off", toOff(triangles));
  writeFile("cigar.obj", toObj(triangles));
  writeFile("quads.obj", toObj(quads));
  ASSERT_EQ(pcl::io::savePLYFileBinary((dir_ / "cigar.ply").string(), toPolygonMesh(triangles)), 0);

  // One point per face: as many points as faces, the same from every format.
  std::vector<Output> outputs;
  for (const char* name : {"cigar.off", "cigar.obj", "cigar.ply"}) {
    SCOPED_TRACE(name);
    const std::string out = std::string(name) + ".pcd";
    const ToolRun r = run(std::string(name) + " " + out + " -segments 2");
    ASSERT_EQ(r.status, 0) << r.out << r.err;
    EXPECT_NE(r.out.find("one point per face"), std::string::npos) << r.out;
    outputs.emplace_back();
    ASSERT_TRUE(readOutput(dir_ / out, outputs.back()));
    ASSERT_EQ(outputs.back().cloud.size(), triangles.faces.size());
  }
  for (std::size_t i = 0; i < triangles.faces.size(); ++i) {
    EXPECT_NEAR(outputs[0].cloud[i].x, outputs[1].cloud[i].x, 1e-5f);
    EXPECT_NEAR(outputs[0].cloud[i].x, outputs[2].cloud[i].x, 1e-5f);
    // The centroid of a face of the cigar lies inside its bounding box.
    EXPECT_LE(std::abs(outputs[0].cloud[i].x), 3.0f);
  }
  // Quads: one point per polygon, not per triangle.
  Output q;
  ASSERT_EQ(run("quads.obj quads.pcd -segments 2 -quiet").status, 0);
  ASSERT_TRUE(readOutput(dir_ / "quads.pcd", q));
  EXPECT_EQ(q.cloud.size(), quads.faces.size());

  // N area-uniform samples: N points on the surface, the same for the same seed.
  ASSERT_EQ(run("cigar.off s1.pcd -samples 3000 -seed 5 -segments 2 -quiet").status, 0);
  ASSERT_EQ(run("cigar.off s2.pcd -samples 3000 -seed 5 -segments 2 -quiet").status, 0);
  ASSERT_EQ(run("cigar.off s3.pcd -samples 3000 -seed 6 -segments 2 -quiet").status, 0);
  EXPECT_EQ(readText(dir_ / "s1.pcd"), readText(dir_ / "s2.pcd"));
  EXPECT_NE(readText(dir_ / "s1.pcd"), readText(dir_ / "s3.pcd"));
  Output s;
  ASSERT_TRUE(readOutput(dir_ / "s1.pcd", s));
  ASSERT_EQ(s.cloud.size(), 3000u);
  for (const auto& p : s.cloud) { // on the (flat-faceted) ellipsoid x^2/9 + y^2 + z^2 = 1
    const float e = p.x * p.x / 9 + p.y * p.y + p.z * p.z;
    ASSERT_GT(e, 0.95f);
    ASSERT_LT(e, 1.0001f);
  }
  // Equal areas get equal shares: as many samples at x < 0 as at x > 0, within 5 sigma.
  std::size_t left = 0;
  for (const auto& p : s.cloud)
    left += p.x < 0;
  EXPECT_NEAR(static_cast<double>(left), 1500.0, 5 * std::sqrt(3000 * 0.25));
}

TEST_F(ToolTest, BadMeshesAndMeshFlagsFailCleanly) {
  ASSERT_EQ(pcl::io::savePCDFileBinary((dir_ / "shape.pcd").string(), *makeShape()), 0);
  expectCleanFailure("shape.pcd out.pcd -samples 100", "-samples");
  expectCleanFailure("shape.pcd out.pcd -seed 3", "-seed");
  writeFile("no_faces.off", "OFF\n3 0 0\n0 0 0\n1 0 0\n0 1 0\n");
  expectCleanFailure("no_faces.off out.pcd", "no_faces.off");
  writeFile("bad_index.off", "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 7\n");
  expectCleanFailure("bad_index.off out.pcd", "bad_index.off");
  writeFile("flat.obj", "v 0 0 0\nv 1 0 0\nv 2 0 0\nf 1 2 3\n");
  expectCleanFailure("flat.obj out.pcd -samples 10", "flat.obj");
  writeFile("garbage.obj", "this is not a mesh\n");
  expectCleanFailure("garbage.obj out.pcd", "garbage.obj");
  writeFile("bad_face.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 9\n");
  expectCleanFailure("bad_face.obj out.pcd", "bad_face.obj");
  expectCleanFailure("missing.off out.pcd", "missing.off");
  expectCleanFailure("shape.pcd out.pcd -samples 0", "-samples");
}

} // namespace
