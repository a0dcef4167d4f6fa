/*
 * pcl_ncut_seg_viewer, driven as a script or CI would: render every view of a generated hand
 * off-screen under xvfb-run and check the pictures. Each must have the requested size and not
 * be blank; the segment views must show exactly the segment colours of the cut the library
 * computes for the same cloud; the centrality view must show its heat map and its markers.
 */
#include <gtest/gtest.h>

#include <pcl_ncut_seg/supernode_ncut_segmentation.h>

#include "png_image.h"
#include "support/text_files.h"
#include <shapes/shapes.h>

#include <pcl/io/pcd_io.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <regex>
#include <set>
#include <sstream>
#include <string>
#include <vector>

namespace fs = std::filesystem;
using Segmenter = pcl::SupernodeNCutSegmentation<pcl::PointXYZ>;

using pcl_ncut_seg::test::lines;

namespace {

const std::string kViewer = PCL_NCUT_SEG_VIEWER;

using ViewerRun = pcl_ncut_seg::test::CommandRun;

bool haveXvfbRun() {
  return std::system("command -v xvfb-run >/dev/null 2>&1") == 0;
}

/** Pixel counts by colour. */
std::map<std::uint32_t, std::size_t> histogram(const pcl_ncut_seg::RgbImage& image) {
  std::map<std::uint32_t, std::size_t> count;
  for (std::size_t i = 0; i + 2 < image.rgb.size(); i += 3)
    ++count[(std::uint32_t(image.rgb[i]) << 16) | (std::uint32_t(image.rgb[i + 1]) << 8) |
            image.rgb[i + 2]];
  return count;
}

std::uint32_t packed(std::uint8_t r, std::uint8_t g, std::uint8_t b) {
  return (std::uint32_t(r) << 16) | (std::uint32_t(g) << 8) | b;
}

/** The segment ids whose colour (Segmenter::segmentColor) covers at least min_pixels pixels.
 * A point is drawn as a square of several pixels, so a colour seen on fewer is an edge blend. */
std::set<std::size_t> paletteIdsShown(const std::map<std::uint32_t, std::size_t>& hist,
                                      std::size_t palette_size, std::size_t min_pixels = 10) {
  std::set<std::size_t> ids;
  for (std::size_t i = 0; i < palette_size; ++i) {
    std::uint8_t r, g, b;
    Segmenter::segmentColor(i, r, g, b);
    const auto it = hist.find(packed(r, g, b));
    if (it != hist.end() && it->second >= min_pixels)
      ids.insert(i);
  }
  return ids;
}

std::set<std::size_t> range(std::size_t n) {
  std::set<std::size_t> s;
  for (std::size_t i = 0; i < n; ++i)
    s.insert(i);
  return s;
}

class ViewerTest : public ::testing::Test {
protected:
  void SetUp() override {
    ASSERT_TRUE(fs::exists(kViewer)) << kViewer;
    dir_ = pcl_ncut_seg::test::makeTempDir("pcl_ncut_seg_viewer");
    ASSERT_FALSE(dir_.empty());
    auth_dir_ = pcl_ncut_seg::test::makeTempDir("pcl_ncut_seg_xauth");
    ASSERT_FALSE(auth_dir_.empty());
    // A hand with its fingers in one plane: seen from the front, every part is visible.
    shape_ = pcl_ncut_seg::test::makeHand(4000, 7);
    ASSERT_EQ(pcl::io::savePCDFileBinary((dir_ / "hand.pcd").string(), *shape_.cloud), 0);
  }
  void TearDown() override {
    std::error_code ec;
    fs::remove_all(dir_, ec);
    fs::remove_all(auth_dir_, ec);
  }

  /** Run the viewer in dir_ (under xvfb-run unless told otherwise). xvfb-run gets its
   * authority file from the test: with a directory of its own, its clean-up sometimes failed (exit
   * 5, "problem while cleaning up temporary directory") after the viewer had exited. */
  ViewerRun run(const std::string& args, bool xvfb = true) const {
    const std::string prefix =
        xvfb ? "xvfb-run -a -f '" + (auth_dir_ / "Xauthority").string() + "' " : "env -u DISPLAY ";
    return pcl_ncut_seg::test::runCommand("cd '" + dir_.string() + "' && " + prefix + "'" +
                                              kViewer + "' " + args,
                                          dir_ / "stdout.txt", dir_ / "stderr.txt");
  }

  /** The number of segments the library gives for the shape, by threshold or by count. */
  std::size_t librarySegments(int requested) const {
    Segmenter seg;
    seg.setInputCloud(shape_.cloud);
    if (requested > 0)
      seg.setNumberOfSegments(requested);
    std::vector<pcl::PointIndices> segments;
    seg.extract(segments);
    return segments.size();
  }

  /** Read a screenshot and check its size and that it shows something. */
  void readShot(const fs::path& path, int width, int height, pcl_ncut_seg::RgbImage& image,
                std::map<std::uint32_t, std::size_t>& hist) const {
    SCOPED_TRACE(path.string());
    ASSERT_TRUE(fs::exists(path));
    ASSERT_TRUE(pcl_ncut_seg::readPng(path.string(), image));
    EXPECT_EQ(image.width, width);
    EXPECT_EQ(image.height, height);
    hist = histogram(image);
    // Not blank: the most common colour (the background) leaves at least 5% to the points.
    std::size_t most = 0;
    for (const auto& c : hist)
      most = std::max(most, c.second);
    const std::size_t pixels = static_cast<std::size_t>(width) * height;
    EXPECT_LT(most, pixels * 95 / 100) << "the picture is (nearly) one colour";
    EXPECT_GT(hist.size(), 3u);
  }

  fs::path dir_;
  fs::path auth_dir_; ///< xvfb-run's authority file, outside dir_ (whose files are checked)
  pcl_ncut_seg::test::LabeledShape shape_;
};

TEST_F(ViewerTest, RendersEveryViewOffScreen) {
  if (!haveXvfbRun())
    GTEST_SKIP() << "xvfb-run is not installed (Debian package xvfb): cannot render off-screen";
  const ViewerRun r = run("hand.pcd -screenshot shot.png -view all -size 640x480");
  ASSERT_EQ(r.status, 0) << r.out << r.err;
  EXPECT_TRUE(r.err.empty()) << r.err;

  const std::size_t t = librarySegments(0);
  ASSERT_GE(t, 2u);
  const std::map<std::string, std::size_t> segment_views = {
      {"segments", t}, {"coarser", t - 1}, {"finer", librarySegments(static_cast<int>(t) + 1)}};
  EXPECT_EQ(segment_views.at("finer"), t + 1);

  Segmenter seg;
  seg.setInputCloud(shape_.cloud);
  std::vector<pcl::PointIndices> segments;
  seg.extract(segments);
  const std::size_t m = seg.getNumberOfSupernodes(false), l = seg.getNumberOfSupernodes(true);

  for (const char* view : {"segments", "centrality", "supernodes", "refined", "coarser", "finer"}) {
    SCOPED_TRACE(view);
    pcl_ncut_seg::RgbImage image;
    std::map<std::uint32_t, std::size_t> hist;
    readShot(dir_ / (std::string("shot_") + view + ".png"), 640, 480, image, hist);
    if (segment_views.count(view)) {
      // Exactly the colours of segments 0 .. t-1: one per segment, no other.
      EXPECT_EQ(paletteIdsShown(hist, 64), range(segment_views.at(view)))
          << "expected " << segment_views.at(view) << " segment colours";
    } else if (std::string(view) == "centrality") {
      EXPECT_GE(hist[packed(255, 255, 255)], 20u) << "no local maxima (white) drawn";
      EXPECT_GE(hist[packed(255, 0, 255)], 20u) << "no saddles (magenta) drawn";
      EXPECT_GT(hist.size(), 50u) << "no heat map";
    } else {
      // Supernode colours: only ids of existing supernodes, several of them (some lie on the
      // far side of the shape and are hidden).
      const std::size_t count = std::string(view) == "supernodes" ? m : l;
      const std::set<std::size_t> shown = paletteIdsShown(hist, count);
      const std::set<std::size_t> beyond = paletteIdsShown(hist, count + 64);
      EXPECT_GE(shown.size(), std::min<std::size_t>(count, 3));
      for (std::size_t id : beyond) {
        std::uint8_t r, g, b, r2, g2, b2;
        Segmenter::segmentColor(id, r, g, b);
        bool same_as_a_supernode = id < count;
        for (std::size_t j = 0; j < count && !same_as_a_supernode; ++j) {
          Segmenter::segmentColor(j, r2, g2, b2);
          same_as_a_supernode = r == r2 && g == g2 && b == b2;
        }
        EXPECT_TRUE(same_as_a_supernode) << "colour of id " << id << " >= " << count << " shown";
      }
    }
  }
}

TEST_F(ViewerTest, OneViewToTheGivenFileWithTheRequestedSegments) {
  if (!haveXvfbRun())
    GTEST_SKIP() << "xvfb-run is not installed (Debian package xvfb): cannot render off-screen";
  const ViewerRun r =
      run("hand.pcd -segments 4 -screenshot out.png -view segments -size 320x240 -quiet");
  ASSERT_EQ(r.status, 0) << r.out << r.err;
  EXPECT_TRUE(lines(r.out).empty()) << r.out;
  pcl_ncut_seg::RgbImage image;
  std::map<std::uint32_t, std::size_t> hist;
  readShot(dir_ / "out.png", 320, 240, image, hist);
  EXPECT_EQ(paletteIdsShown(hist, 64, 4), range(librarySegments(4)));
  // Nothing else was written.
  std::set<std::string> files;
  for (const auto& entry : fs::directory_iterator(dir_))
    files.insert(entry.path().filename().string());
  EXPECT_EQ(files, (std::set<std::string>{"hand.pcd", "out.png"}));
}

TEST_F(ViewerTest, KeysMoveThroughTheHierarchyAndListThemselves) {
  if (!haveXvfbRun())
    GTEST_SKIP() << "xvfb-run is not installed (Debian package xvfb): cannot render off-screen";
  const std::size_t t = librarySegments(0);
  ASSERT_EQ(run("hand.pcd -screenshot plain.png -quiet").status, 0);
  ASSERT_EQ(run("hand.pcd -screenshot up.png -keys 'Up Up Down' -quiet").status, 0);
  ASSERT_EQ(run("hand.pcd -screenshot down.png -keys Down -quiet").status, 0);
  ASSERT_EQ(run("hand.pcd -screenshot keys.png -keys h -quiet").status, 0);
  pcl_ncut_seg::RgbImage image;
  std::map<std::uint32_t, std::size_t> plain, up, down, keys;
  readShot(dir_ / "plain.png", 640, 480, image, plain);
  readShot(dir_ / "up.png", 640, 480, image, up);
  readShot(dir_ / "down.png", 640, 480, image, down);
  readShot(dir_ / "keys.png", 640, 480, image, keys);
  EXPECT_EQ(paletteIdsShown(plain, 64), range(t));
  EXPECT_EQ(paletteIdsShown(up, 64), range(librarySegments(static_cast<int>(t) + 1)));
  EXPECT_EQ(paletteIdsShown(down, 64), range(librarySegments(static_cast<int>(t) - 1)));
  // h lists the keys: far more text pixels (light grey, blended into the background).
  auto greyPixels = [](const std::map<std::uint32_t, std::size_t>& hist) {
    std::size_t n = 0;
    for (const auto& [rgb, count] : hist) {
      const int r = rgb >> 16, g = (rgb >> 8) & 255, b = rgb & 255;
      if (r == g && g == b && r > 60)
        n += count;
    }
    return n;
  };
  EXPECT_GT(greyPixels(keys), 3 * greyPixels(plain) + 500);
}

TEST_F(ViewerTest, BadCommandLinesFailWithOneLine) {
  const std::vector<std::pair<std::string, bool>> bad = {
      {"hand.pcd -screenshot out.png -view nonsense", true},
      {"hand.pcd -screenshot out.jpg", true},
      {"missing.pcd -screenshot out.png", true},
      {"hand.pcd -screenshot out.png -size 10", true},
      {"hand.pcd -bogus", true},
      {"hand.pcd -screenshot out.png -keys 'Up x'", true},
      {"hand.pcd -screenshot out.png -up +w", true},
      {"hand.pcd -screenshot no_such_dir/out.png", true},
      {"hand.pcd -screenshot out.png", false}, // no X display
  };
  for (const auto& [args, xvfb] : bad) {
    if (xvfb && !haveXvfbRun())
      continue;
    SCOPED_TRACE(args);
    const ViewerRun r = run(args, xvfb);
    EXPECT_EQ(r.status, 1);
    EXPECT_EQ(lines(r.err).size(), 1u) << r.err;
    EXPECT_FALSE(fs::exists(dir_ / "out.png"));
    EXPECT_FALSE(fs::exists(dir_ / "out.jpg"));
  }
}

} // namespace
