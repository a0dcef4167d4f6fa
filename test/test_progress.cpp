/*
 * Progress reports: computeCentrality's fraction of full searches and the class's phases, from
 * the calling thread only, in order, without changing the result.
 */
#include "core/centrality/centrality.h"
#include <pcl_ncut_seg/supernode_ncut_segmentation.h>
#include <shapes/shapes.h>
#include <support/graphs.h>

#include <gtest/gtest.h>

#include <string>
#include <thread>
#include <utility>
#include <vector>

using namespace pcl_ncut_seg;

TEST(Progress, CentralityReportsRisingFractionsFromTheCallingThread) {
  const std::size_t n = 900;
  const auto xyz = test::randomPoints(n, 5);
  const auto knn = test::bruteForceKnn(xyz, 6);
  const CsrGraph g = buildSymmetricKnnGraph(xyz.data(), n, knn.data(), 6);
  const std::thread::id caller = std::this_thread::get_id();
  std::vector<double> fractions;
  bool other_thread = false;
  const Centrality with = computeCentrality(g, 0, 2, nullptr, [&](double f) {
    other_thread = other_thread || std::this_thread::get_id() != caller;
    fractions.push_back(f);
  });
  EXPECT_FALSE(other_thread);
  ASSERT_GE(fractions.size(), 2u);
  EXPECT_GT(fractions.front(), 0.0); // the phase start is the caller's to report
  EXPECT_EQ(fractions.back(), 1.0);
  for (std::size_t i = 1; i < fractions.size(); ++i)
    EXPECT_LE(fractions[i - 1], fractions[i]);
  // The report changes nothing.
  EXPECT_EQ(with.f, computeCentrality(g, 0, 2).f);
}

TEST(Progress, SegmentationReportsEveryPhaseInOrder) {
  const auto shape = test::makeHand(2000, 3);
  pcl::SupernodeNCutSegmentation<pcl::PointXYZ> seg;
  seg.setInputCloud(shape.cloud);
  seg.setNumberOfSegments(4);
  std::vector<std::pair<std::string, double>> reports;
  seg.setProgressCallback(
      [&](const char* phase, double fraction) { reports.emplace_back(phase, fraction); });
  std::vector<pcl::PointIndices> segments;
  seg.extract(segments);
  ASSERT_EQ(segments.size(), 4u);
  // Each phase opens with 0 and closes with 1, one after the other.
  std::vector<std::string> order;
  for (std::size_t i = 0; i < reports.size(); ++i) {
    const auto& [phase, fraction] = reports[i];
    EXPECT_GE(fraction, 0.0);
    EXPECT_LE(fraction, 1.0);
    if (order.empty() || order.back() != phase) {
      EXPECT_EQ(fraction, 0.0) << phase << " does not open with 0";
      if (i > 0) {
        EXPECT_EQ(reports[i - 1].second, 1.0) << reports[i - 1].first << " does not close with 1";
      }
      order.push_back(phase);
    }
  }
  EXPECT_EQ(reports.back().second, 1.0);
  EXPECT_EQ(order, (std::vector<std::string>{"kNN", "Cen", "Snod", "LRef", "HSeg"}));

  // A second cut reuses the expensive stage: only the cut is reported.
  reports.clear();
  seg.setNumberOfSegments(3);
  seg.extract(segments);
  ASSERT_EQ(reports.size(), 2u);
  EXPECT_EQ(reports[0].first, "HSeg");
  EXPECT_EQ(reports[1].first, "HSeg");
}
