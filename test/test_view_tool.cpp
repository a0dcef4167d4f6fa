/*
 * pcl_ncut_seg_sample_mesh -view: an organized PCD of what a depth camera sees of a mesh, with
 * the sensor pose; and its failures (one line, exit 1, no file).
 */
#include <gtest/gtest.h>

#include <pcl/io/pcd_io.h>
#include <pcl/point_cloud.h>
#include <pcl/point_types.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include <sys/wait.h>
#include <unistd.h>

namespace {

namespace fs = std::filesystem;

class ViewTool : public ::testing::Test {
protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() / ("pcl_ncut_seg_view_" + std::to_string(::getpid()));
    fs::remove_all(dir_);
    fs::create_directories(dir_ / "out");
    // A box 2 x 1 x 0.5, six quads.
    std::ofstream(dir_ / "box.off")
        << "OFF\n8 6 0\n0 0 0\n2 0 0\n2 1 0\n0 1 0\n0 0 0.5\n2 0 0.5\n2 1 0.5\n0 1 0.5\n"
           "4 0 3 2 1\n4 4 5 6 7\n4 0 1 5 4\n4 3 7 6 2\n4 0 4 7 3\n4 1 2 6 5\n";
  }
  void TearDown() override { fs::remove_all(dir_); }

  int run(const std::string& args) const {
    const std::string cmd = std::string(PCL_NCUT_SEG_SAMPLE_MESH) + " " + args + " > " +
                            (dir_ / "stdout.txt").string() + " 2> " +
                            (dir_ / "stderr.txt").string();
    const int status = std::system(cmd.c_str());
    return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  }
  std::string read(const fs::path& p) const {
    std::ifstream in(p, std::ios::binary);
    std::stringstream s;
    s << in.rdbuf();
    return s.str();
  }
  fs::path dir_;
};

TEST_F(ViewTool, WritesAnOrganizedBinaryPcdWithTheSensorPose) {
  const fs::path out = dir_ / "out" / "view.pcd";
  ASSERT_EQ(run((dir_ / "box.off").string() + " " + out.string() +
                " -view 4 -resolution 96x72 -range_noise 0"),
            0)
      << read(dir_ / "stderr.txt");
  EXPECT_NE(read(out).find("DATA binary\n"), std::string::npos);
  pcl::PointCloud<pcl::PointXYZ> cloud;
  ASSERT_EQ(pcl::io::loadPCDFile(out.string(), cloud), 0);
  EXPECT_EQ(cloud.width, 96u);
  EXPECT_EQ(cloud.height, 72u);
  EXPECT_FALSE(cloud.is_dense);
  std::size_t valid = 0;
  const Eigen::Vector3f o = cloud.sensor_origin_.head<3>();
  EXPECT_NEAR(o.norm(), 1.0f, 1e-5f); // 1 m from the box's centre, the world origin
  const Eigen::Matrix3f R = cloud.sensor_orientation_.toRotationMatrix();
  const float f = 48.0f / std::tan(28.5f * static_cast<float>(M_PI) / 180.0f);
  for (std::uint32_t v = 0; v < cloud.height; ++v)
    for (std::uint32_t u = 0; u < cloud.width; ++u) {
      const pcl::PointXYZ& p = cloud.at(u, v);
      if (!std::isfinite(p.x))
        continue;
      ++valid;
      // Back in the camera frame (z forward, x right, y down), the point is on its pixel.
      const Eigen::Vector3f c = R.transpose() * (p.getVector3fMap() - o);
      EXPECT_NEAR(c.x() / c.z() * f + 48.0f, u + 0.5f, 1e-2f);
      EXPECT_NEAR(c.y() / c.z() * f + 36.0f, v + 0.5f, 1e-2f);
      EXPECT_LT(p.getVector3fMap().norm(), 0.15f + 1e-4f); // the box, scaled to 0.3 m
    }
  EXPECT_GT(valid, 200u);
  EXPECT_LT(valid, 96u * 72u);
  EXPECT_NE(read(dir_ / "stdout.txt").find(std::to_string(valid) + " points"), std::string::npos);
}

TEST_F(ViewTool, TheSegmenterSeesTheViewFromItsViewpointAndKeepsIt) {
  const fs::path view = dir_ / "out" / "view.pcd", labelled = dir_ / "out" / "labelled.pcd";
  ASSERT_EQ(run((dir_ / "box.off").string() + " " + view.string() + " -view 4 -resolution 96x72"),
            0);
  for (const char* encoding : {"", " -ascii"}) {
    const std::string cmd = std::string(PCL_NCUT_SEG_TOOL) + " " + view.string() + " " +
                            labelled.string() + std::string(encoding) + " > " +
                            (dir_ / "stdout.txt").string() + " 2>&1";
    ASSERT_EQ(std::system(cmd.c_str()), 0) << read(dir_ / "stdout.txt");
    // The PCD's VIEWPOINT is the sensor origin: not read off the points.
    EXPECT_NE(read(dir_ / "stdout.txt").find("view: one view from the sensor origin"),
              std::string::npos)
        << read(dir_ / "stdout.txt");
    pcl::PointCloud<pcl::PointXYZ> in, out;
    ASSERT_EQ(pcl::io::loadPCDFile(view.string(), in), 0);
    ASSERT_EQ(pcl::io::loadPCDFile(labelled.string(), out), 0);
    EXPECT_TRUE(out.sensor_origin_.isApprox(in.sensor_origin_, 1e-6f)) << encoding;
    EXPECT_TRUE(out.sensor_orientation_.coeffs().isApprox(in.sensor_orientation_.coeffs(), 1e-6f))
        << encoding;
  }
}

TEST_F(ViewTool, TheSameSeedGivesTheSameView) {
  const std::string box = (dir_ / "box.off").string() + " ";
  ASSERT_EQ(run(box + (dir_ / "out" / "a.pcd").string() + " -view 7 -resolution 64x48"), 0);
  ASSERT_EQ(run(box + (dir_ / "out" / "b.pcd").string() + " -view 7 -resolution 64x48"), 0);
  ASSERT_EQ(run(box + (dir_ / "out" / "c.pcd").string() + " -view 8 -resolution 64x48"), 0);
  EXPECT_EQ(read(dir_ / "out" / "a.pcd"), read(dir_ / "out" / "b.pcd"));
  EXPECT_NE(read(dir_ / "out" / "a.pcd"), read(dir_ / "out" / "c.pcd"));
}

TEST_F(ViewTool, FailsWithOneLineAndNoFile) {
  const std::string box = (dir_ / "box.off").string() + " ";
  const std::string out = (dir_ / "out" / "v.pcd").string();
  std::ofstream(dir_ / "empty.off") << "OFF\n0 0 0\n";
  for (const std::string& args :
       {box + out + " -view", box + out + " -view x", box + out + " -view -1",
        box + out + " -view 1 -resolution 4x48", box + out + " -view 1 -resolution 64x1e9",
        box + out + " -view 1 -resolution 4097x8", box + out + " -view 1 -range_noise -0.1",
        box + out + " -view 1 -resolution 64.5x48", box + out + " -view 1 -resolution 64",
        box + out + " -view 1 -resolution", box + out + " -resolution 64x48",
        box + out + " -range_noise 0", box + out + " -view 1 -n 100",
        box + out + " -view 1 -centroids", (dir_ / "empty.off").string() + " " + out + " -view 1",
        (dir_ / "none.off").string() + " " + out + " -view 1",
        box + (dir_ / "no" / "v.pcd").string() + " -view 1"}) {
    EXPECT_EQ(run(args), 1) << args;
    const std::string err = read(dir_ / "stderr.txt");
    EXPECT_FALSE(err.empty()) << args;
    EXPECT_EQ(err.find('\n'), err.size() - 1) << "one line: " << err;
    EXPECT_TRUE(fs::is_empty(dir_ / "out")) << args;
  }
}

} // namespace
