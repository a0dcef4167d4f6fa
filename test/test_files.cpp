// The tools' one reader of files (kit/files): what the formats allow is read as PCL's own
// readers read valid files; what they do not allow is refused with a reason that says what is
// wrong, before anything is allocated that the file cannot hold.
#include "files/point_file.h"

#include <gtest/gtest.h>

#include <pcl/PolygonMesh.h>
#include <pcl/conversions.h>
#include <pcl/io/pcd_io.h>
#include <pcl/io/ply_io.h>

#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>

#include <unistd.h>

namespace fs = std::filesystem;
using pcl_ncut_seg::files::PointFile;
using pcl_ncut_seg::files::readPointFile;

namespace {

class Files : public ::testing::Test {
protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() /
           ("pcl_ncut_seg_files_" + std::to_string(::getpid()) + "_" +
            ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }

  std::string write(const std::string& name, const std::string& contents) {
    const std::string path = (dir_ / name).string();
    std::ofstream(path, std::ios::binary) << contents;
    return path;
  }
  /** The reason the reader gives for a file; "" when it reads it. */
  std::string refusal(const std::string& name, const std::string& contents) {
    PointFile file;
    std::string error;
    const std::string path = write(name, contents);
    if (readPointFile(path, {}, file, error))
      return "";
    EXPECT_EQ(error.find('\n'), std::string::npos) << error;
    EXPECT_NE(error.find(path), std::string::npos) << error;
    EXPECT_FALSE(file.cloud) << "a refused file left points";
    return error;
  }
  PointFile read(const std::string& path) {
    PointFile file;
    std::string error;
    EXPECT_TRUE(readPointFile(path, {}, file, error)) << error;
    return file;
  }
  fs::path dir_;
};

std::string pcdHeader(const std::string& fields, const std::string& size, const std::string& type,
                      const std::string& count, std::size_t n, const std::string& data) {
  return "VERSION 0.7\nFIELDS " + fields + "\nSIZE " + size + "\nTYPE " + type + "\nCOUNT " +
         count + "\nWIDTH " + std::to_string(n) + "\nHEIGHT 1\nVIEWPOINT 0 0 0 1 0 0 0\nPOINTS " +
         std::to_string(n) + "\nDATA " + data + "\n";
}

const std::string kXyz = pcdHeader("x y z", "4 4 4", "F F F", "1 1 1", 2, "ascii");

/** The x, y, z PCL's own reader gives for a valid file. */
pcl::PointCloud<pcl::PointXYZ> pclPoints(const pcl::PCLPointCloud2& blob) {
  pcl::PointCloud<pcl::PointXYZ> cloud;
  pcl::fromPCLPointCloud2(blob, cloud);
  return cloud;
}

void expectSamePoints(const pcl::PointCloud<pcl::PointXYZ>& a,
                      const pcl::PointCloud<pcl::PointXYZ>& b) {
  ASSERT_EQ(a.size(), b.size());
  EXPECT_EQ(a.width, b.width);
  EXPECT_EQ(a.height, b.height);
  for (std::size_t i = 0; i < a.size(); ++i)
    EXPECT_EQ(std::memcmp(a[i].data, b[i].data, 12), 0) << "point " << i;
}

} // namespace

TEST_F(Files, RefusesPcdFieldsTheFormatDoesNotAllow) {
  const auto fields = [](const std::string& size, const std::string& type) {
    return pcdHeader("x y z", size, type, "1 1 1", 1, "ascii") + "1 2 3\n";
  };
  EXPECT_NE(refusal("a.pcd", fields("4 3 4", "F F F")).find("field 'y' has TYPE F SIZE 3"),
            std::string::npos);
  EXPECT_NE(refusal("b.pcd", fields("0 4 4", "F F F")).find("field 'x' has TYPE F SIZE 0"),
            std::string::npos);
  EXPECT_NE(refusal("c.pcd", fields("4 4 4", "F X F")).find("field 'y' has TYPE X"),
            std::string::npos);
  EXPECT_NE(refusal("d.pcd", fields("4 4", "F F F")).find("they must match"), std::string::npos);
  EXPECT_NE(refusal("e.pcd", pcdHeader("x y z", "4 4 4", "F F F", "1 0 1", 1, "ascii") + "1 2\n")
                .find("field 'y' has COUNT 0"),
            std::string::npos);
}

TEST_F(Files, RefusesAsciiPcdDataThatIsNotThePoints) {
  // The header is 10 lines: the points are lines 11 and 12.
  EXPECT_NE(refusal("f.pcd", kXyz + "1 2 3\n1.0f 2 3\n").find("line 12: '1.0f' is not a value"),
            std::string::npos);
  EXPECT_NE(refusal("g.pcd", kXyz + "1 2 3 4\n1 2 3\n").find("line 11 has more than the 3"),
            std::string::npos);
  EXPECT_NE(refusal("h.pcd", kXyz + "1 2 3\n   \t\n1 2 3\n").find("line 12 has 0 values"),
            std::string::npos);
  EXPECT_NE(refusal("i.pcd", kXyz + "1 2 3\n").find("ends after 1 of 2 points"), std::string::npos);
  EXPECT_NE(refusal("j.pcd", kXyz + "1 2 3\n4 5 6\n7 8 9\n").find("data after the 2 points"),
            std::string::npos);
  EXPECT_NE(refusal("k.pcd", kXyz + "1 2 3\n4 5\n").find("line 12 has 2 values"),
            std::string::npos);
  EXPECT_EQ(refusal("l.pcd", kXyz + "1 2 3\r\n+4 nan -6e-1\r\n\n"), "");
}

TEST_F(Files, RefusesPcdHeadersThatDisagreeWithTheirData) {
  // POINTS beyond what the data could hold: refused before anything is allocated.
  std::string huge = pcdHeader("x y z", "4 4 4", "F F F", "1 1 1", 1, "ascii") + "1 2 3\n";
  huge.replace(huge.find("WIDTH 1"), 7, "WIDTH 4000000000");
  huge.replace(huge.find("POINTS 1"), 8, "POINTS 4000000000");
  EXPECT_NE(refusal("m.pcd", huge).find("cannot fit"), std::string::npos);
  EXPECT_NE(refusal("n.pcd", pcdHeader("x y z", "4 4 4", "F F F", "1 1 1", 3, "binary") +
                                 std::string(24, '\0'))
                .find("holds 2 of the 3 points"),
            std::string::npos);
  std::string mismatch = kXyz + "1 2 3\n4 5 6\n";
  mismatch.replace(mismatch.find("POINTS 2"), 8, "POINTS 3");
  EXPECT_NE(refusal("o.pcd", mismatch).find("POINTS 3 is not WIDTH x HEIGHT"), std::string::npos);
  EXPECT_NE(refusal("p.pcd", "VERSION 0.7\nFIELDS x y z\n").find("without a DATA line"),
            std::string::npos);
  EXPECT_NE(refusal("q.pcd", "FIELDS x\nWIDTH 1\nPOINTS 1\nFOO 3\nDATA ascii\n1\n")
                .find("is not a header line"),
            std::string::npos);
}

TEST_F(Files, RefusesACompressedBlockThatDoesNotHoldThePoints) {
  // PCL 1.13's reader crashes on this one: a COUNT the block does not hold.
  pcl::PointCloud<pcl::PointXYZ> cloud;
  for (int i = 0; i < 50; ++i)
    cloud.push_back(pcl::PointXYZ(float(i), float(i % 7), 0.5f));
  const std::string path = (dir_ / "c.pcd").string();
  ASSERT_EQ(pcl::io::savePCDFileBinaryCompressed(path, cloud), 0);
  std::ifstream in(path, std::ios::binary);
  std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  expectSamePoints(*read(path).cloud, cloud);
  std::string counts = bytes, huge = bytes;
  counts.replace(counts.find("COUNT 1 1 1"), 11, "COUNT 1 1000 1");
  EXPECT_NE(refusal("d.pcd", counts)
                .find("the compressed block holds 600 bytes, the 50 points of "
                      "4008 bytes need 200400"),
            std::string::npos);
  huge.replace(huge.find("COUNT 1 1 1"), 11, "COUNT 1 1000000 1");
  EXPECT_NE(refusal("g.pcd", huge).find("a point of these fields takes more than"),
            std::string::npos);
  EXPECT_NE(refusal("e.pcd", bytes.substr(0, bytes.size() - 40)).find("cut short"),
            std::string::npos);
  std::string corrupt = bytes;
  corrupt[corrupt.find("DATA binary_compressed\n") + 23 + 8] = '\xff';
  EXPECT_NE(refusal("f.pcd", corrupt).find("corrupt"), std::string::npos);
}

TEST_F(Files, ReadsEveryPcdEncodingAsPclDoes) {
  pcl::PointCloud<pcl::PointXYZRGBNormal> cloud;
  cloud.width = 6;
  cloud.height = 4;
  for (int i = 0; i < 24; ++i) {
    pcl::PointXYZRGBNormal p;
    p.x = 0.1f * i;
    p.y = i % 3 == 0 ? std::nanf("") : 1.0f / (i + 1);
    p.z = -2.5f * i;
    p.rgba = 0xff000000u + 77u * i;
    p.normal_x = p.normal_y = p.normal_z = 0.5f;
    p.curvature = 0.25f;
    cloud.push_back(p);
  }
  cloud.width = 6;
  cloud.height = 4;
  cloud.sensor_origin_ = Eigen::Vector4f(1, 2, 3, 0);
  for (int encoding = 0; encoding < 3; ++encoding) {
    const std::string path = (dir_ / ("e" + std::to_string(encoding) + ".pcd")).string();
    pcl::PCDWriter writer;
    ASSERT_EQ(encoding == 0   ? writer.writeASCII(path, cloud, 8)
              : encoding == 1 ? writer.writeBinary(path, cloud)
                              : writer.writeBinaryCompressed(path, cloud),
              0);
    pcl::PCLPointCloud2 theirs;
    Eigen::Vector4f origin;
    Eigen::Quaternionf orientation;
    ASSERT_EQ(pcl::io::loadPCDFile(path, theirs, origin, orientation), 0);
    const PointFile ours = read(path);
    ASSERT_TRUE(ours.cloud);
    EXPECT_EQ(ours.blob.fields.size(), theirs.fields.size());
    EXPECT_EQ(ours.blob.data, theirs.data) << "encoding " << encoding;
    expectSamePoints(*ours.cloud, pclPoints(theirs));
    EXPECT_EQ(ours.sensor.origin, origin);
    EXPECT_EQ(ours.cloud->sensor_origin_, origin);
    EXPECT_FALSE(ours.cloud->is_dense);
  }
}

TEST_F(Files, ReadsTheSharedCloudsAsPclDoes) {
  const fs::path data = fs::path(PCL_NCUT_SEG_SHARED_DATA) / "pcl";
  if (!fs::is_directory(data))
    GTEST_SKIP() << "no shared data at " << data << " (a user's clone)";
  std::size_t clouds = 0;
  for (const auto& entry : fs::directory_iterator(data)) {
    if (entry.path().extension() != ".pcd")
      continue;
    pcl::PCLPointCloud2 theirs;
    ASSERT_EQ(pcl::io::loadPCDFile(entry.path().string(), theirs), 0) << entry.path();
    const PointFile ours = read(entry.path().string());
    ASSERT_TRUE(ours.cloud) << entry.path();
    EXPECT_EQ(ours.blob.data, theirs.data) << entry.path();
    expectSamePoints(*ours.cloud, pclPoints(theirs));
    ++clouds;
  }
  EXPECT_GE(clouds, 9u);
}

TEST_F(Files, ReadsPointsOfAnyNumericType) {
  // x as a double and y, z as integers: read as their values, not as zeros.
  const PointFile f =
      read(write("t.pcd", pcdHeader("x y z", "8 2 1", "F I U", "1 1 1", 2, "ascii") +
                              "0.5 -3 200\n1e3 32767 0\n"));
  ASSERT_TRUE(f.cloud);
  EXPECT_EQ((*f.cloud)[0].x, 0.5f);
  EXPECT_EQ((*f.cloud)[0].y, -3.0f);
  EXPECT_EQ((*f.cloud)[0].z, 200.0f);
  EXPECT_EQ((*f.cloud)[1].y, 32767.0f);
  EXPECT_NE(
      refusal("u.pcd", pcdHeader("x y z", "8 2 1", "F I U", "1 1 1", 1, "ascii") + "0.5 -3 256\n")
          .find("'256' is not a value of field 'z'"),
      std::string::npos);
}

TEST_F(Files, ReadsPlyPointsAndMeshesAsPclWritesThem) {
  pcl::PointCloud<pcl::PointXYZ> cloud;
  for (int i = 0; i < 30; ++i)
    cloud.push_back(pcl::PointXYZ(0.25f * i, std::sin(float(i)), -1.0f * i));
  for (const bool binary : {false, true}) {
    const std::string path = (dir_ / (binary ? "b.ply" : "a.ply")).string();
    ASSERT_EQ(pcl::io::savePLYFile(path, cloud, binary), 0);
    expectSamePoints(*read(path).cloud, cloud);
  }
  const std::string mesh = "ply\nformat binary_big_endian 1.0\nelement vertex 4\n"
                           "property float x\nproperty float y\nproperty float z\n"
                           "property list uchar float texture\nelement face 2\n"
                           "property list uchar int vertex_indices\nend_header\n";
  std::string body;
  const float v[4][3] = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}};
  const auto big = [&](const void* p, std::size_t n) {
    const char* c = static_cast<const char*>(p);
    for (std::size_t i = n; i-- > 0;)
      body += c[i];
  };
  for (const auto& p : v) {
    for (float c : p)
      big(&c, 4);
    body += '\0'; // an empty list among the vertex's properties (PCL's reader aborts on it)
  }
  const std::int32_t triangles[2][3] = {{0, 1, 2}, {0, 2, 3}};
  for (const auto& f : triangles) {
    body += '\3';
    for (int i = 0; i < 3; ++i)
      big(&f[i], 4);
  }
  const PointFile m = read(write("m.ply", mesh + body));
  ASSERT_TRUE(m.cloud);
  EXPECT_TRUE(m.mesh);
  EXPECT_EQ(m.num_faces, 2u);
  EXPECT_EQ(m.cloud->size(), 2u);
  EXPECT_FLOAT_EQ((*m.cloud)[0].x, 2.0f / 3.0f);
}

TEST_F(Files, RefusesPlyCountsTheFileCannotHold) {
  const std::string head = "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\n"
                           "property float y\nproperty float z\n";
  const std::string faces = "element face 1\nproperty list uchar int vertex_indices\nend_header\n";
  const std::string vertices = "0 0 0\n1 0 0\n0 1 0\n";
  EXPECT_EQ(refusal("a.ply", head + faces + vertices + "3 0 1 2\n"), "");
  std::string many = head + faces + vertices + "3 0 1 2\n";
  many.replace(many.find("vertex 3"), 8, "vertex 3000000000");
  EXPECT_NE(refusal("b.ply", many).find("element 'vertex' of 3000000000 records cannot fit"),
            std::string::npos);
  EXPECT_NE(refusal("c.ply", head + faces + vertices + "3 0 1\n").find("a list of 3 values"),
            std::string::npos);
  EXPECT_NE(refusal("d.ply", head + faces + vertices + "3 0 1 7\n")
                .find("face 0 refers to a vertex that does not exist"),
            std::string::npos);
  EXPECT_NE(refusal("e.ply", head + faces + "0 0 0 5\n1 0 0\n0 1 0\n3 0 1 2\n")
                .find("line 10: element 'vertex' record 0: more values"),
            std::string::npos);
  EXPECT_NE(refusal("f.ply", head +
                                 "element face 1\nproperty list uchar float vertex_indices\n"
                                 "end_header\n" +
                                 vertices + "3 0 1 2\n")
                .find("vertex indices are integers"),
            std::string::npos);
  std::string binary = head + faces;
  binary.replace(binary.find("ascii"), 5, "binary_little_endian");
  binary += std::string(36, '\0') + "\xff";
  EXPECT_NE(refusal("g.ply", binary).find("a list of 255 values cannot be read"),
            std::string::npos);
  EXPECT_NE(refusal("h.ply", "ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\n"
                             "end_header\n1\n")
                .find("has no y field"),
            std::string::npos);
}

TEST_F(Files, ReadsNpyArraysOfPoints) {
  // (2, 2, 3) float64 in Fortran order: point (h, w) is at h + 2 w + 4 c.
  std::string header = "{'descr': '<f8', 'fortran_order': True, 'shape': (2, 2, 3), }";
  header += std::string(118 - header.size(), ' ') + "\n";
  std::string npy = std::string("\x93NUMPY\x01\x00", 8) + char(header.size()) + '\0' + header;
  for (int i = 0; i < 12; ++i) {
    const double v = i;
    npy.append(reinterpret_cast<const char*>(&v), 8);
  }
  const PointFile f = read(write("a.npy", npy));
  ASSERT_TRUE(f.cloud);
  EXPECT_EQ(f.cloud->width, 2u);
  EXPECT_EQ(f.cloud->height, 2u);
  const pcl::PointXYZ& p = f.cloud->at(1, 0); // column 1, row 0: h = 0, w = 1
  EXPECT_EQ(p.x, 2.0f);
  EXPECT_EQ(p.y, 6.0f);
  EXPECT_EQ(p.z, 10.0f);
  std::string flat = npy;
  flat.replace(flat.find("(2, 2, 3)"), 9, "(4, 2)   ");
  EXPECT_NE(refusal("b.npy", flat).find("must be (N, 3) or (H, W, 3), not (4, 2)"),
            std::string::npos);
  EXPECT_NE(refusal("c.npy", npy.substr(0, npy.size() - 8)).find("fewer than its 4 x 3"),
            std::string::npos);
  EXPECT_NE(refusal("d.npy", "not an array").find("not a valid .npy file"), std::string::npos);
}

TEST_F(Files, SaysWhyAFileCannotBeOpened) {
  PointFile file;
  std::string error;
  EXPECT_FALSE(readPointFile((dir_ / "none.pcd").string(), {}, file, error));
  EXPECT_NE(error.find("No such file or directory"), std::string::npos) << error;
  fs::create_directories(dir_ / "folder.pcd");
  EXPECT_FALSE(readPointFile((dir_ / "folder.pcd").string(), {}, file, error));
  EXPECT_NE(error.find("not a regular file"), std::string::npos) << error;
  EXPECT_FALSE(readPointFile((dir_ / "cloud.xyz").string(), {}, file, error));
  EXPECT_NE(error.find("is not a .pcd, .ply, .npy, .off or .obj file"), std::string::npos);
  EXPECT_NE(refusal("empty.pcd", kXyz.substr(0, kXyz.find("WIDTH")) +
                                     "WIDTH 0\nHEIGHT 1\nPOINTS 0\nDATA ascii\n")
                .find("contains no points"),
            std::string::npos);
  EXPECT_NE(refusal("nan.pcd", kXyz + "nan 1 2\n1 inf 2\n").find("no point with finite"),
            std::string::npos);
}
