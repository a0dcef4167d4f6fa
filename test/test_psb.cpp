/*
 * The Princeton Segmentation Benchmark's development split (shared data): hands, four-legged
 * animals and a human, one point per face at its centroid, segmented into the benchmark's
 * number of segments and scored as the benchmark does (1 - Rand index per face, averaged over
 * every human segmentation of the model), against one segment, k-means and the paper's pipeline
 * with the same count. Skipped when the shared data is absent.
 *
 * First, the mesh reading and sampling these tests (and the tools) rely on.
 */
#include <pcl_ncut_seg/supernode_ncut_segmentation.h>

#include <shapes/metrics.h>
#include <surfaces/mesh_sampling.h>

#include <pcl/io/pcd_io.h>

#include <gtest/gtest.h>

#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <map>
#include <string>
#include <vector>

namespace {

namespace fs = std::filesystem;
using Cloud = pcl::PointCloud<pcl::PointXYZ>;

const fs::path kPsbDir = fs::path(PCL_NCUT_SEG_SHARED_DATA) / "psb-dev";

// ---------------------------------------------------------------------------------------------
// Mesh reading and sampling

/** \brief A file in the temporary directory, removed at the end of the scope. */
class TempFile {
public:
  explicit TempFile(const std::string& contents) {
    const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
    path_ = fs::temp_directory_path() /
            ("pcl_ncut_seg_" + std::string(info->name()) + "_" + std::to_string(::getpid()) + "_" +
             std::to_string(counter_++) + ".txt");
    std::ofstream(path_, std::ios::binary) << contents;
  }
  ~TempFile() { fs::remove(path_); }
  std::string path() const { return path_.string(); }

private:
  fs::path path_;
  static int counter_;
};
int TempFile::counter_ = 0;

TEST(ReadOff, ReadsHeaderVariantsCommentsAndPolygons) {
  // Counts on the header line, comments, blank lines, CRLF, a coloured quad and a triangle.
  const TempFile file("# made by hand\r\nOFF 5 2 0 # counts here\r\n\r\n0 0 0\r\n1 0 0 # c\r\n"
                      "1 1 0\r\n0 1 0\r\n0 0 1\r\n4 0 1 2 3 255 0 0\r\n3 0 1 4\r\n");
  pcl_ncut_seg::TriangleMesh mesh;
  std::string error;
  ASSERT_TRUE(pcl_ncut_seg::readOff(file.path(), mesh, &error)) << error;
  EXPECT_EQ(mesh.numVertices(), 5u);
  EXPECT_EQ(mesh.num_original_faces, 2u);
  EXPECT_EQ(mesh.faces, (std::vector<std::uint32_t>{0, 1, 2, 0, 2, 3, 0, 1, 4}));
  EXPECT_EQ(mesh.original_face, (std::vector<std::uint32_t>{0, 0, 1}));
  EXPECT_EQ(mesh.vertices[3 * 4 + 2], 1.0f);

  // The usual layout: counts on the next line.
  const TempFile plain("OFF\n3 1 0\n0 0 0\n2 0 0\n0 2 0\n3 0 1 2\n");
  ASSERT_TRUE(pcl_ncut_seg::readOff(plain.path(), mesh, &error)) << error;
  EXPECT_EQ(mesh.numTriangles(), 1u);
  EXPECT_EQ(mesh.num_original_faces, 1u);
}

TEST(ReadOff, RejectsMalformedFilesWithAReason) {
  const std::vector<std::string> bad = {
      "",                                           // empty
      "PLY\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n", // not OFF
      "OFF\n3 1 0\n0 0 0\n1 0 0\n",                 // ends before the vertices do
      "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n",          // ends before the faces do
      "OFF\n3 1 0\n0 0 0\n1 x 0\n0 1 0\n3 0 1 2\n", // not a number
      "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 3\n", // index out of range
      "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n2 0 1\n",   // a face of two vertices
      "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n4 0 1 2\n", // fewer indices than announced
  };
  for (const std::string& contents : bad) {
    const TempFile file(contents);
    pcl_ncut_seg::TriangleMesh mesh;
    mesh.vertices = {7, 7, 7};
    std::string error;
    EXPECT_FALSE(pcl_ncut_seg::readOff(file.path(), mesh, &error)) << contents;
    EXPECT_FALSE(error.empty()) << contents;
    EXPECT_EQ(error.find('\n'), std::string::npos) << "one line: " << error;
    EXPECT_EQ(mesh.vertices, (std::vector<float>{7, 7, 7})) << "output untouched on failure";
  }
  std::string error;
  pcl_ncut_seg::TriangleMesh mesh;
  EXPECT_FALSE(pcl_ncut_seg::readOff("/nonexistent/mesh.off", mesh, &error));
  EXPECT_FALSE(error.empty());
}

/** \brief The unit square (as a quad) beside a triangle of area 3 in the plane z = 0. */
pcl_ncut_seg::TriangleMesh squareAndTriangle() {
  const TempFile file("OFF\n7 2 0\n0 0 0\n1 0 0\n1 1 0\n0 1 0\n2 0 0\n5 0 0\n2 2 0\n"
                      "4 0 1 2 3\n3 4 5 6\n");
  pcl_ncut_seg::TriangleMesh mesh;
  EXPECT_TRUE(pcl_ncut_seg::readOff(file.path(), mesh));
  return mesh;
}

TEST(MeshSampling, FaceAreasAndCentroids) {
  const pcl_ncut_seg::TriangleMesh mesh = squareAndTriangle();
  const std::vector<double> areas = pcl_ncut_seg::faceAreas(mesh);
  ASSERT_EQ(areas.size(), 2u);
  EXPECT_DOUBLE_EQ(areas[0], 1.0);
  EXPECT_DOUBLE_EQ(areas[1], 3.0);
  const std::vector<float> centroids = pcl_ncut_seg::faceCentroids(mesh);
  ASSERT_EQ(centroids.size(), 6u);
  EXPECT_FLOAT_EQ(centroids[0], 0.5f);
  EXPECT_FLOAT_EQ(centroids[1], 0.5f);
  EXPECT_FLOAT_EQ(centroids[3], 3.0f);
  EXPECT_FLOAT_EQ(centroids[4], 2.0f / 3.0f);
  EXPECT_FLOAT_EQ(centroids[5], 0.0f);
}

TEST(MeshSampling, IsUniformByAreaAndDeterministic) {
  const pcl_ncut_seg::TriangleMesh mesh = squareAndTriangle();
  const std::size_t n = 40000;
  std::vector<std::uint32_t> face;
  const std::vector<float> xyz = pcl_ncut_seg::sampleSurface(mesh, n, 5, &face);
  ASSERT_EQ(xyz.size(), 3 * n);
  ASSERT_EQ(face.size(), n);
  std::size_t on_square = 0, lower_left_quarter = 0, near_triangle_corner = 0;
  for (std::size_t i = 0; i < n; ++i) {
    const float x = xyz[3 * i], y = xyz[3 * i + 1];
    EXPECT_EQ(xyz[3 * i + 2], 0.0f);
    if (face[i] == 0) {
      ++on_square;
      ASSERT_TRUE(x >= 0 && x <= 1 && y >= 0 && y <= 1) << x << " " << y;
      lower_left_quarter += x < 0.5f && y < 0.5f;
    } else {
      // Inside the triangle (2,0) (5,0) (2,2): y >= 0, x >= 2, 2x + 3y <= 10.
      ASSERT_TRUE(y >= 0 && x >= 2 && 2 * x + 3 * y <= 10 + 1e-4f) << x << " " << y;
      // The half-size copy at corner (2,0) has a quarter of the area.
      near_triangle_corner += 2 * (x - 2) + 3 * y <= 3;
    }
  }
  // Expected fractions 1/4, 1/4 and 1/4; the standard deviations are below 0.005.
  EXPECT_NEAR(double(on_square) / n, 0.25, 0.02);
  EXPECT_NEAR(double(lower_left_quarter) / on_square, 0.25, 0.02);
  EXPECT_NEAR(double(near_triangle_corner) / (n - on_square), 0.25, 0.02);

  EXPECT_EQ(pcl_ncut_seg::sampleSurface(mesh, n, 5), xyz);
  EXPECT_NE(pcl_ncut_seg::sampleSurface(mesh, n, 6), xyz);
  EXPECT_TRUE(pcl_ncut_seg::sampleSurface(pcl_ncut_seg::TriangleMesh(), 10, 5).empty());
}

TEST(ReadSeg, ReadsOneLabelPerLine) {
  std::vector<int> labels;
  const TempFile good("3\n0\r\n12\n\n");
  ASSERT_TRUE(pcl_ncut_seg::readSeg(good.path(), labels));
  EXPECT_EQ(labels, (std::vector<int>{3, 0, 12}));
  const TempFile bad("3\nx\n");
  EXPECT_FALSE(pcl_ncut_seg::readSeg(bad.path(), labels));
  EXPECT_FALSE(pcl_ncut_seg::readSeg("/nonexistent/a.seg", labels));
}

TEST(BundledData, ModelsAreReproducedByTheirDocumentedCommands) {
  // data/README.md says data/<name>.pcd is 8000 samples of cgal-<name>.off with seed 1.
  for (const std::string name : {"armadillo", "hand"}) {
    SCOPED_TRACE(name);
    const fs::path source =
        fs::path(PCL_NCUT_SEG_SHARED_DATA) / "models" / ("cgal-" + name + ".off");
    if (!fs::exists(source))
      GTEST_SKIP() << "shared data absent: no " << source;
    pcl_ncut_seg::TriangleMesh mesh;
    ASSERT_TRUE(pcl_ncut_seg::readOff(source.string(), mesh));
    const std::vector<float> xyz = pcl_ncut_seg::sampleSurface(mesh, 8000, 1);
    pcl::PointCloud<pcl::PointXYZ> bundled;
    ASSERT_EQ(
        pcl::io::loadPCDFile(std::string(PCL_NCUT_SEG_DATA_DIR) + "/" + name + ".pcd", bundled), 0);
    ASSERT_EQ(bundled.size() * 3, xyz.size());
    std::size_t differ = 0;
    for (std::size_t i = 0; i < bundled.size(); ++i)
      differ += bundled[i].x != xyz[3 * i] || bundled[i].y != xyz[3 * i + 1] ||
                bundled[i].z != xyz[3 * i + 2];
    EXPECT_EQ(differ, 0u);
  }
}

// ---------------------------------------------------------------------------------------------
// The benchmark

/** \brief What one model scored: 1 - Rand index per face, averaged over the human
 * segmentations, for the defaults and for what they are measured against. */
struct ModelResult {
  int requested = 0;        ///< the benchmark's segment count for the model
  std::size_t segments = 0; ///< segments produced by the defaults
  double one_minus_ri = 1;  ///< the defaults, with the benchmark's count
  bool has_paper = false;   ///< the next two measured
  std::size_t paper_segments = 0;
  double paper = 1;       ///< the paper's pipeline (Parameters::paper()) with the same count
  double one_segment = 1; ///< every face in one segment
  double k_means = 1;     ///< k-means on the points with the same count
  std::size_t num_human = 0;
  bool partition = false; ///< every point in exactly one segment (the defaults)
};

/** \brief Line `id` (from 1) of nSeg-ByModel.txt, or 0 if missing. */
int benchmarkSegmentCount(int id) {
  std::ifstream in(kPsbDir / "nSeg-ByModel.txt");
  int value = 0;
  for (int line = 1; line <= id; ++line)
    if (!(in >> value))
      return 0;
  return value;
}

/** \brief Every human segmentation of model `id`, in a fixed order, each one label per face;
 * empty, with the test failed, when one is missing or unreadable. */
std::vector<std::vector<int>> humanSegmentations(int id, std::size_t faces) {
  std::vector<fs::path> files;
  for (const auto& entry : fs::directory_iterator(kPsbDir / "seg" / std::to_string(id)))
    if (entry.path().extension() == ".seg")
      files.push_back(entry.path());
  std::sort(files.begin(), files.end());
  std::vector<std::vector<int>> humans;
  for (const auto& file : files) {
    humans.emplace_back();
    if (!pcl_ncut_seg::readSeg(file.string(), humans.back()) || humans.back().size() != faces) {
      ADD_FAILURE() << file << ": unreadable or not one label per face";
      return {};
    }
  }
  if (humans.empty())
    ADD_FAILURE() << "no human segmentations for model " << id;
  return humans;
}

/** \brief 1 - Rand index of labels, averaged over the human segmentations. */
double meanError(const std::vector<int>& labels, const std::vector<std::vector<int>>& humans) {
  double sum = 0;
  for (const std::vector<int>& human : humans)
    sum += 1.0 - pcl_ncut_seg::test::randIndex(labels, human);
  return sum / static_cast<double>(humans.size());
}

/** \brief The segments of cloud with params, asking for `count` segments. */
std::vector<pcl::PointIndices> segmentInto(const Cloud::Ptr& cloud,
                                           const pcl_ncut_seg::Parameters& params, int count) {
  pcl::SupernodeNCutSegmentation<pcl::PointXYZ> seg;
  seg.setInputCloud(cloud);
  EXPECT_TRUE(seg.setParameters(params));
  seg.setNumberOfSegments(count);
  std::vector<pcl::PointIndices> segments;
  seg.extract(segments);
  return segments;
}

/** \brief Every point of the cloud in exactly one segment. */
bool isPartition(const std::vector<pcl::PointIndices>& segments, std::size_t n) {
  std::vector<int> count(n, 0);
  for (const auto& segment : segments)
    for (const auto i : segment.indices)
      if (i >= 0 && static_cast<std::size_t>(i) < n)
        ++count[i];
  return std::all_of(count.begin(), count.end(), [](int c) { return c == 1; });
}

/** \brief Model `id`'s faces, one point at each centroid (xyz and as a cloud). */
bool readModel(int id, std::vector<float>& xyz, Cloud::Ptr& cloud) {
  pcl_ncut_seg::TriangleMesh mesh;
  std::string error;
  const fs::path path = kPsbDir / "off" / (std::to_string(id) + ".off");
  if (!pcl_ncut_seg::readOff(path.string(), mesh, &error)) {
    ADD_FAILURE() << path << ": " << error;
    return false;
  }
  xyz = pcl_ncut_seg::faceCentroids(mesh);
  cloud.reset(new Cloud);
  cloud->resize(xyz.size() / 3);
  for (std::size_t i = 0; i < cloud->size(); ++i)
    (*cloud)[i] = pcl::PointXYZ(xyz[3 * i], xyz[3 * i + 1], xyz[3 * i + 2]);
  return true;
}

void printResult(int id, std::size_t points, const ModelResult& r) {
  std::cout << "[ measured ] model " << id << ": " << points << " points, " << r.segments << " of "
            << r.requested << " segments, 1 - RI " << r.one_minus_ri << " over " << r.num_human
            << " human segmentations; one segment " << r.one_segment << ", k-means " << r.k_means;
  if (r.has_paper)
    std::cout << ", -paper " << r.paper << " (" << r.paper_segments << " segments)";
  std::cout << std::endl;
}

/** \brief Segment model `id` with the defaults (and with -paper when asked), and score them
 * and the baselines; memoised, for the per-model and summary tests. Fails the current test
 * (and returns nullptr) on unreadable data. */
const ModelResult* evaluate(int id, bool with_paper) {
  static std::map<int, ModelResult> cache;
  const auto cached = cache.find(id);
  if (cached != cache.end() && (cached->second.has_paper || !with_paper))
    return &cached->second;

  std::vector<float> xyz;
  Cloud::Ptr cloud;
  if (!readModel(id, xyz, cloud))
    return nullptr;
  ModelResult result;
  result.requested = benchmarkSegmentCount(id);
  if (result.requested <= 0) {
    ADD_FAILURE() << "no segment count for model " << id << " in nSeg-ByModel.txt";
    return nullptr;
  }
  const std::vector<std::vector<int>> humans = humanSegmentations(id, cloud->size());
  if (humans.empty())
    return nullptr;
  result.num_human = humans.size();

  using pcl_ncut_seg::test::segmentsToLabels;
  const auto ours = segmentInto(cloud, pcl_ncut_seg::Parameters(), result.requested);
  result.segments = ours.size();
  result.partition = isPartition(ours, cloud->size());
  result.one_minus_ri = meanError(segmentsToLabels(ours, cloud->size()), humans);
  result.one_segment = meanError(std::vector<int>(cloud->size(), 0), humans);
  result.k_means = meanError(pcl_ncut_seg::test::kMeansLabels(xyz, result.requested), humans);
  if (with_paper) {
    const auto paper = segmentInto(cloud, pcl_ncut_seg::Parameters::paper(), result.requested);
    result.has_paper = true;
    result.paper_segments = paper.size();
    result.paper = meanError(segmentsToLabels(paper, cloud->size()), humans);
  }
  printResult(id, cloud->size(), result);
  return &(cache[id] = result);
}

bool haveData() {
  return fs::is_directory(kPsbDir / "off") && fs::is_directory(kPsbDir / "seg");
}

class PsbModel : public ::testing::TestWithParam<int> {};

TEST_P(PsbModel, SegmentsIntoTheBenchmarkCount) {
  if (!haveData())
    GTEST_SKIP() << "shared data absent: no " << kPsbDir;
  const int id = GetParam();
  const ModelResult* result = evaluate(id, true);
  ASSERT_NE(result, nullptr);
  RecordProperty("one_minus_rand_index", std::to_string(result->one_minus_ri));
  RecordProperty("paper_one_minus_rand_index", std::to_string(result->paper));
  RecordProperty("segments", std::to_string(result->segments));
  EXPECT_TRUE(result->partition) << "a point is in no segment or in several";
  // A hand has at least as many parts as the benchmark's count (five fingers, palm, wrist):
  // all must be found. Elsewhere the count (15 for the human and animal 381, which people cut
  // into limb segments) may exceed the supernodes, and fewer segments come out.
  const bool hand = id >= 181 && id <= 200;
  if (hand)
    EXPECT_EQ(result->segments, static_cast<std::size_t>(result->requested));
  else
    EXPECT_LE(result->segments, static_cast<std::size_t>(result->requested));
  // Its quality: closer to the people's segmentations than no segmentation at all, which a
  // segmenter that gives up (one segment) would not be. -paper and k-means with the same count
  // are printed beside it: the defaults do not beat them on every model (a limitation that
  // results/report.md measures on the whole split), so they are not a bar here.
  EXPECT_LT(result->one_minus_ri, result->one_segment);
}

// 1: human; 181-183: hands; 381-383: four-legged animals.
INSTANTIATE_TEST_SUITE_P(Psb, PsbModel, ::testing::Values(1, 181, 182, 183, 381, 382, 383));

TEST(Psb, LimbCategoriesFollowThePartsBetterThanKMeans) {
  if (!haveData())
    GTEST_SKIP() << "shared data absent: no " << kPsbDir;
  // The goal on these hands and four-legged animals is a mean 1 - Rand index of 0.2 or less.
  // It is not reached: the four-legged animals' heads and tails leak into the body with no
  // saddle between them (docs/limitations.md); pcl_ncut_seg_bench_psb --limbs prints
  // the mean. What the test checks: the segments follow the parts better than the same number
  // of clusters of the points by position alone (k-means, a segmenter that knows nothing of
  // parts and cuts across fingers and legs wherever they are long). The hands carry that; the
  // animals alone are no better than k-means, which is the limitation.
  double sum = 0, sum_k_means = 0;
  int models = 0;
  for (const int id : {181, 182, 183, 381, 382, 383}) {
    const ModelResult* result = evaluate(id, false);
    ASSERT_NE(result, nullptr);
    sum += result->one_minus_ri;
    sum_k_means += result->k_means;
    ++models;
  }
  const double mean = sum / models, mean_k_means = sum_k_means / models;
  std::cout << "[ measured ] mean 1 - RI over hands and four-legged animals: " << mean
            << ", k-means with the same counts " << mean_k_means << std::endl;
  RecordProperty("mean_one_minus_rand_index", std::to_string(mean));
  RecordProperty("k_means_mean_one_minus_rand_index", std::to_string(mean_k_means));
  EXPECT_LT(mean, mean_k_means);
}

} // namespace
