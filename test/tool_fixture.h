/*
 * The fixture of the pcl_ncut_seg command's tests (test_tool.cpp, test_tool_output.cpp): a
 * scratch directory per test, the tool run in it, and the shapes and meshes the tests give it.
 */
#pragma once

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

namespace pcl_ncut_seg {
namespace test {

namespace fs = std::filesystem;

inline const std::string kTool = PCL_NCUT_SEG_TOOL;
inline const std::string kDataDir = PCL_NCUT_SEG_DATA_DIR;

using ToolRun = pcl_ncut_seg::test::CommandRun;

/** A sphere of radius 1 with three capsules (radius 0.3, length 2.2) sticking out of it along
 * +x, +y and -x: a palm with three fingers, surface points only. Deterministic. */
inline pcl::PointCloud<pcl::PointXYZ>::Ptr makeShape() {
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
inline pcl::PointCloud<pcl::PointXYZ>::Ptr makeTwoSpheres() {
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

inline ::testing::AssertionResult readOutput(const fs::path& path, Output& output) {
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

inline TestMesh makeCigar(int rings, int sectors, bool quads) {
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

inline std::string toOff(const TestMesh& m) {
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

inline std::string toObj(const TestMesh& m) {
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

inline pcl::PolygonMesh toPolygonMesh(const TestMesh& m) {
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
inline long printedSegments(const std::string& out) {
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

} // namespace test
} // namespace pcl_ncut_seg
