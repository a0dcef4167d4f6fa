/*
 * The Princeton Segmentation Benchmark's development split (shared data): hands, four-legged
 * animals and a human, one point per face at its centroid, segmented into the benchmark's
 * number of segments and scored as the benchmark does (1 - Rand index per face, averaged over
 * every human segmentation of the model). Skipped when the shared data is absent.
 */
#include <pcl_ncut_seg/supernode_ncut_segmentation.h>

#include "mesh_sampling.h"
#include "support/metrics.h"

#include <gtest/gtest.h>

#include <algorithm>
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

/** \brief What one model scored. */
struct ModelResult {
  int requested = 0;        ///< the benchmark's segment count for the model
  std::size_t segments = 0; ///< segments produced
  double one_minus_ri = 1;  ///< 1 - Rand index, averaged over the human segmentations
  std::size_t num_human = 0;
  bool partition = false; ///< every point in exactly one segment
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

/** \brief Segment model `id` and score it; memoised, for the per-model and summary tests.
 * Fails the current test (and returns nullptr) on unreadable data. */
const ModelResult* evaluate(int id) {
  static std::map<int, ModelResult> cache;
  const auto cached = cache.find(id);
  if (cached != cache.end())
    return &cached->second;

  const std::string name = std::to_string(id);
  pcl_ncut_seg::TriangleMesh mesh;
  std::string error;
  if (!pcl_ncut_seg::readOff((kPsbDir / "off" / (name + ".off")).string(), mesh, &error)) {
    ADD_FAILURE() << error;
    return nullptr;
  }
  ModelResult result;
  result.requested = benchmarkSegmentCount(id);
  if (result.requested <= 0) {
    ADD_FAILURE() << "no segment count for model " << id << " in nSeg-ByModel.txt";
    return nullptr;
  }

  const std::vector<float> xyz = pcl_ncut_seg::faceCentroids(mesh);
  Cloud::Ptr cloud(new Cloud);
  cloud->resize(xyz.size() / 3);
  for (std::size_t i = 0; i < cloud->size(); ++i)
    (*cloud)[i] = pcl::PointXYZ(xyz[3 * i], xyz[3 * i + 1], xyz[3 * i + 2]);

  pcl::SupernodeNCutSegmentation<pcl::PointXYZ> seg;
  seg.setInputCloud(cloud);
  seg.setNumberOfSegments(result.requested);
  std::vector<pcl::PointIndices> segments;
  seg.extract(segments);
  result.segments = segments.size();

  std::vector<int> count(cloud->size(), 0);
  for (const auto& segment : segments)
    for (const auto i : segment.indices)
      if (i >= 0 && static_cast<std::size_t>(i) < count.size())
        ++count[i];
  result.partition = std::all_of(count.begin(), count.end(), [](int c) { return c == 1; });
  const std::vector<int> labels = pcl_ncut_seg::test::segmentsToLabels(segments, cloud->size());

  // Every human segmentation of the model, in a fixed order.
  std::vector<fs::path> seg_files;
  for (const auto& entry : fs::directory_iterator(kPsbDir / "seg" / name))
    if (entry.path().extension() == ".seg")
      seg_files.push_back(entry.path());
  std::sort(seg_files.begin(), seg_files.end());
  if (seg_files.empty()) {
    ADD_FAILURE() << "no human segmentations for model " << id;
    return nullptr;
  }
  double sum = 0;
  for (const auto& file : seg_files) {
    std::vector<int> human;
    if (!pcl_ncut_seg::readSeg(file.string(), human) || human.size() != labels.size()) {
      ADD_FAILURE() << file << ": unreadable or not one label per face";
      return nullptr;
    }
    sum += 1.0 - pcl_ncut_seg::test::randIndex(labels, human);
  }
  result.num_human = seg_files.size();
  result.one_minus_ri = sum / seg_files.size();
  std::cout << "[ measured ] model " << id << ": " << cloud->size() << " points, "
            << result.segments << " of " << result.requested << " segments, 1 - RI "
            << result.one_minus_ri << " over " << result.num_human << " human segmentations"
            << std::endl;
  return &cache.emplace(id, result).first->second;
}

bool haveData() {
  return fs::is_directory(kPsbDir / "off") && fs::is_directory(kPsbDir / "seg");
}

class PsbModel : public ::testing::TestWithParam<int> {};

TEST_P(PsbModel, SegmentsIntoTheBenchmarkCount) {
  if (!haveData())
    GTEST_SKIP() << "shared data not found at " << kPsbDir;
  const ModelResult* result = evaluate(GetParam());
  ASSERT_NE(result, nullptr);
  RecordProperty("one_minus_rand_index", std::to_string(result->one_minus_ri));
  RecordProperty("segments", std::to_string(result->segments));
  EXPECT_TRUE(result->partition) << "a point is in no segment or in several";
  // A hand has at least as many parts as the benchmark's count (five fingers, palm, wrist):
  // all must be found. Elsewhere the count (15 for the human and animal 381, which people cut
  // into limb segments) may exceed the supernodes, and fewer segments come out.
  const bool hand = GetParam() >= 181 && GetParam() <= 200;
  if (hand)
    EXPECT_EQ(result->segments, static_cast<std::size_t>(result->requested));
  else
    EXPECT_LE(result->segments, static_cast<std::size_t>(result->requested));
}

// 1: human; 181-183: hands; 381-383: four-legged animals.
INSTANTIATE_TEST_SUITE_P(Psb, PsbModel, ::testing::Values(1, 181, 182, 183, 381, 382, 383));

TEST(Psb, LimbCategoriesScoreLikeThePaper) {
  if (!haveData())
    GTEST_SKIP() << "shared data not found at " << kPsbDir;
  // A quick prototype of the paper reached 0.13 on limb categories and people score about
  // 0.10 on the whole benchmark; 0.2 leaves room, and fails a method that misses the limbs.
  double sum = 0;
  int models = 0;
  for (const int id : {181, 182, 183, 381, 382, 383}) {
    const ModelResult* result = evaluate(id);
    ASSERT_NE(result, nullptr);
    sum += result->one_minus_ri;
    ++models;
  }
  const double mean = sum / models;
  std::cout << "[ measured ] mean 1 - RI over hands and four-legged animals: " << mean << std::endl;
  RecordProperty("mean_one_minus_rand_index", std::to_string(mean));
  EXPECT_LE(mean, 0.2);
}

} // namespace
