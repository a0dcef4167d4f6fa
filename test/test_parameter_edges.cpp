/*
 * Every parameter at the edges of its valid range (accepted, and extract() gives a partition)
 * and just past them (rejected with a PCL_ERROR naming the setter, the old value kept); and
 * determinism: bit-identical output across runs and thread counts.
 */
#include <pcl_ncut_seg/supernode_ncut_segmentation.h>
#include <support/extract_capturing.h>
#include <support/graphs.h>
#include <support/metrics.h>
#include <support/partition.h>
#include <support/shapes.h>

#include <pcl/common/point_tests.h>

#include <gtest/gtest.h>

#include <algorithm>
#include <climits>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <functional>
#include <limits>
#include <map>
#include <numeric>
#include <optional>
#include <random>
#include <set>
#include <string>
#include <vector>

using Seg = pcl::SupernodeNCutSegmentation<pcl::PointXYZ>;
using Cloud = pcl::PointCloud<pcl::PointXYZ>;
using Segments = std::vector<pcl::PointIndices>;
using namespace pcl_ncut_seg::test;

namespace {

const float kNaN = std::numeric_limits<float>::quiet_NaN();
const float kInf = std::numeric_limits<float>::infinity();

struct ParamCase {
  const char* setter;
  std::function<void(Seg&)> set;
  std::function<bool(const Seg&)> took; ///< the getter shows the new value
};

std::vector<ParamCase> validEdges() {
  const double dmin = std::numeric_limits<double>::denorm_min();
  const double dmax = std::numeric_limits<double>::max();
  std::vector<ParamCase> v;
  v.push_back({"setNumberOfNeighbours", [](Seg& s) { s.setNumberOfNeighbours(2); },
               [](const Seg& s) { return s.getNumberOfNeighbours() == 2; }});
  v.push_back({"setNumberOfNeighbours", [](Seg& s) { s.setNumberOfNeighbours(INT_MAX); },
               [](const Seg& s) { return s.getNumberOfNeighbours() == INT_MAX; }});
  for (std::optional<int> n :
       {std::optional<int>(), std::optional<int>(1), std::optional<int>(INT_MAX)})
    v.push_back({"setNumberOfSamples", [n](Seg& s) { s.setNumberOfSamples(n); },
                 [n](const Seg& s) { return s.getNumberOfSamples() == n; }});
  for (float f : {0.0f, 1.0f}) {
    v.push_back({"setCrossingFraction", [f](Seg& s) { s.setCrossingFraction(f); },
                 [f](const Seg& s) { return s.getCrossingFraction() == f; }});
    v.push_back({"setAreaFraction", [f](Seg& s) { s.setAreaFraction(f); },
                 [f](const Seg& s) { return s.getAreaFraction() == f; }});
    v.push_back({"setHeightFraction", [f](Seg& s) { s.setHeightFraction(f); },
                 [f](const Seg& s) { return s.getHeightFraction() == f; }});
  }
  for (double x : {dmin, 1e-300, 1e300, dmax}) {
    v.push_back(
        {"setBeta", [x](Seg& s) { s.setBeta(x); }, [x](const Seg& s) { return s.getBeta() == x; }});
    v.push_back({"setAlpha1", [x](Seg& s) { s.setAlpha1(x); },
                 [x](const Seg& s) { return s.getAlpha1() == x; }});
    v.push_back({"setAlpha2", [x](Seg& s) { s.setAlpha2(x); },
                 [x](const Seg& s) { return s.getAlpha2() == x; }});
  }
  for (double x : {0.0, dmax})
    v.push_back({"setThreshold", [x](Seg& s) { s.setThreshold(x); },
                 [x](const Seg& s) { return s.getThreshold() == x; }});
  for (int n : {1, INT_MAX})
    v.push_back({"setNumberOfSegments", [n](Seg& s) { s.setNumberOfSegments(n); },
                 [n](const Seg& s) {
                   return s.getNumberOfSegments() == n &&
                          s.getStoppingRule() == pcl_ncut_seg::StoppingRule::Count;
                 }});
  for (unsigned n : {0u, 1u, 64u, UINT_MAX})
    v.push_back({"setNumberOfThreads", [n](Seg& s) { s.setNumberOfThreads(n); },
                 [n](const Seg& s) { return s.getNumberOfThreads() == n; }});
  for (int n : {1, INT_MAX})
    v.push_back({"setMaxSegments", [n](Seg& s) { s.setMaxSegments(n); },
                 [n](const Seg& s) { return s.getMaxSegments() == n; }});
  for (double x : {dmin, dmax})
    v.push_back({"setNeckBound", [x](Seg& s) { s.setNeckBound(x); },
                 [x](const Seg& s) { return s.getNeckBound() == x; }});
  v.push_back(
      {"setCentralityMode",
       [](Seg& s) { s.setCentralityMode(pcl_ncut_seg::CentralityMode::Exact); },
       [](const Seg& s) { return s.getCentralityMode() == pcl_ncut_seg::CentralityMode::Exact; }});
  return v;
}

std::vector<ParamCase> justPast() {
  const double dmin = std::numeric_limits<double>::denorm_min();
  const double dinf = std::numeric_limits<double>::infinity();
  const double dnan = std::numeric_limits<double>::quiet_NaN();
  std::vector<ParamCase> v;
  for (int k : {1, 0, -1, INT_MIN})
    v.push_back({"setNumberOfNeighbours", [k](Seg& s) { s.setNumberOfNeighbours(k); },
                 [](const Seg& s) { return s.getNumberOfNeighbours() != 10; }});
  for (int n : {0, -1, INT_MIN})
    v.push_back({"setNumberOfSamples", [n](Seg& s) { s.setNumberOfSamples(n); },
                 [](const Seg& s) { return s.getNumberOfSamples() != std::nullopt; }});
  for (float f : {std::nextafter(0.0f, -1.0f), std::nextafter(1.0f, 2.0f), kNaN, kInf}) {
    v.push_back({"setCrossingFraction", [f](Seg& s) { s.setCrossingFraction(f); },
                 [](const Seg& s) { return s.getCrossingFraction() != 0.3f; }});
    v.push_back({"setAreaFraction", [f](Seg& s) { s.setAreaFraction(f); },
                 [](const Seg& s) { return s.getAreaFraction() != 0.01f; }});
    v.push_back({"setHeightFraction", [f](Seg& s) { s.setHeightFraction(f); },
                 [](const Seg& s) { return s.getHeightFraction() != 0.01f; }});
  }
  for (double x : {0.0, -0.0, -dmin, dinf, dnan}) {
    v.push_back({"setBeta", [x](Seg& s) { s.setBeta(x); },
                 [](const Seg& s) { return s.getBeta() != 2.0; }});
    v.push_back({"setAlpha1", [x](Seg& s) { s.setAlpha1(x); },
                 [](const Seg& s) { return s.getAlpha1() != 2.0; }});
    v.push_back({"setAlpha2", [x](Seg& s) { s.setAlpha2(x); },
                 [](const Seg& s) { return s.getAlpha2() != 0.5; }});
  }
  for (double x : {-dmin, dinf, dnan})
    v.push_back({"setThreshold", [x](Seg& s) { s.setThreshold(x); },
                 [](const Seg& s) { return s.getThreshold() != Seg().getThreshold(); }});
  for (int n : {0, -1, INT_MIN})
    v.push_back({"setNumberOfSegments", [n](Seg& s) { s.setNumberOfSegments(n); },
                 [](const Seg& s) {
                   return s.getNumberOfSegments() != Seg().getNumberOfSegments() ||
                          s.getStoppingRule() != Seg().getStoppingRule();
                 }});
  for (int n : {0, -1, INT_MIN})
    v.push_back({"setMaxSegments", [n](Seg& s) { s.setMaxSegments(n); },
                 [](const Seg& s) { return s.getMaxSegments() != Seg().getMaxSegments(); }});
  for (double x : {0.0, -dmin, dinf, dnan})
    v.push_back({"setNeckBound", [x](Seg& s) { s.setNeckBound(x); },
                 [](const Seg& s) { return s.getNeckBound() != Seg().getNeckBound(); }});
  v.push_back({"setCentralityMode",
               [](Seg& s) { s.setCentralityMode(static_cast<pcl_ncut_seg::CentralityMode>(7)); },
               [](const Seg& s) { return s.getCentralityMode() != Seg().getCentralityMode(); }});
  return v;
}

} // namespace

TEST(Robustness, ParametersAtTheEdgesOfTheirRangeAreAcceptedAndWork) {
  Cloud::Ptr c = makeDumbbell(800, 4).cloud;
  for (const ParamCase& p : validEdges()) {
    Seg seg;
    seg.setInputCloud(c);
    ::testing::internal::CaptureStderr();
    p.set(seg);
    const std::string err = ::testing::internal::GetCapturedStderr();
    SCOPED_TRACE(std::string(p.setter));
    EXPECT_TRUE(p.took(seg));
    EXPECT_EQ(err.find(p.setter), std::string::npos) << err;
    const Extracted r = extractCapturing(seg);
    ASSERT_FALSE(r.segments.empty()) << r.err;
    expectPartition(r.segments, *c);
  }
}

TEST(Robustness, ParametersJustPastTheirRangeAreRejected) {
  for (const ParamCase& p : justPast()) {
    Seg seg;
    ::testing::internal::CaptureStderr();
    p.set(seg);
    const std::string err = ::testing::internal::GetCapturedStderr();
    SCOPED_TRACE(std::string(p.setter));
    EXPECT_FALSE(p.took(seg)) << "a value past the range was taken";
    EXPECT_NE(err.find(std::string("[pcl::SupernodeNCutSegmentation::") + p.setter + "]"),
              std::string::npos)
        << err;
  }
}

// ---------------------------------------------------------------------------------------------
// Determinism: bit-identical output across runs and thread counts.

namespace {
struct Fingerprint {
  std::vector<std::uint32_t> labels;
  std::vector<float> centrality;
  std::vector<int> supernodes, refined;
  std::vector<double> ncuts;
};

Fingerprint fingerprint(const Cloud::Ptr& cloud, unsigned threads, int segments) {
  Seg seg;
  seg.setInputCloud(cloud);
  seg.setNumberOfThreads(threads);
  if (segments > 0)
    seg.setNumberOfSegments(segments);
  Segments out;
  seg.extract(out);
  Fingerprint f;
  const auto labeled = seg.getLabeledCloud(); // keep the cloud alive through the loop
  for (const auto& p : *labeled)
    f.labels.push_back(p.label);
  f.centrality = seg.getCentrality();
  f.supernodes = seg.getSupernodeLabels(false);
  f.refined = seg.getSupernodeLabels(true);
  for (const auto& node : seg.getHierarchy().nodes)
    f.ncuts.push_back(node.ncut);
  return f;
}

template <typename T> bool bitIdentical(const std::vector<T>& a, const std::vector<T>& b) {
  return a.size() == b.size() && std::memcmp(a.data(), b.data(), a.size() * sizeof(T)) == 0;
}
/// Shapes with many components, with ties (a regular grid), and with duplicates; each with the
/// default rule (0) or a count.
struct DeterminismCase {
  const char* name;
  Cloud::Ptr cloud;
  int segments;
};

std::vector<DeterminismCase> determinismCases() {
  Cloud::Ptr grid(new Cloud);
  for (int i = 0; i < 30; ++i)
    for (int j = 0; j < 30; ++j)
      grid->push_back(
          pcl::PointXYZ(static_cast<float>(i), static_cast<float>(j), (i - 15) * (i - 15) * 0.05f));
  Cloud::Ptr dup(new Cloud(*makeDumbbell(1000, 5).cloud));
  *dup += *dup;
  return {{"hand", makeHand(3000, 12).cloud, 0},
          {"quadruped", makeQuadruped(3000, 13).cloud, 7},
          {"two objects", makeTwoObjects(2000, 14).cloud, 0},
          {"grid", grid, 4},
          {"duplicated dumbbell", dup, 3}};
}

/// The same partition of the points, whatever the segments' numbers.
bool samePartition(const std::vector<std::uint32_t>& a, const std::vector<std::uint32_t>& b) {
  if (a.size() != b.size())
    return false;
  std::map<std::uint32_t, std::uint32_t> ab, ba;
  for (std::size_t i = 0; i < a.size(); ++i)
    if (ab.emplace(a[i], b[i]).first->second != b[i] ||
        ba.emplace(b[i], a[i]).first->second != a[i])
      return false;
  return true;
}
} // namespace

TEST(Determinism, BitIdenticalAcrossRunsAndThreadCounts) {
  for (const DeterminismCase& cs : determinismCases()) {
    SCOPED_TRACE(cs.name);
    const Fingerprint ref = fingerprint(cs.cloud, 1, cs.segments);
    ASSERT_EQ(ref.labels.size(), cs.cloud->size());
    for (unsigned threads : {1u, 2u, 4u})
      for (int run = 0; run < 2; ++run) {
        const Fingerprint f = fingerprint(cs.cloud, threads, cs.segments);
        EXPECT_TRUE(bitIdentical(ref.labels, f.labels)) << threads << " threads, run " << run;
        EXPECT_TRUE(bitIdentical(ref.centrality, f.centrality)) << threads << " threads";
        EXPECT_TRUE(bitIdentical(ref.supernodes, f.supernodes)) << threads << " threads";
        EXPECT_TRUE(bitIdentical(ref.refined, f.refined)) << threads << " threads";
        EXPECT_TRUE(bitIdentical(ref.ncuts, f.ncuts)) << threads << " threads";
      }
  }
}

TEST(Determinism, BitIdenticalForAnyOrderOfThePoints) {
  // The same points reversed and shuffled: per point (mapped back to the first order) the same
  // segments, centrality and supernodes, and the same hierarchy, with five starts (the default)
  // and the default rule or a count.
  for (const DeterminismCase& cs : determinismCases()) {
    SCOPED_TRACE(cs.name);
    const std::size_t n = cs.cloud->size();
    const Fingerprint ref = fingerprint(cs.cloud, 2, cs.segments);
    ASSERT_EQ(ref.labels.size(), n);
    std::vector<std::size_t> perm(n); // perm[i]: the point at position i of the new order
    std::iota(perm.begin(), perm.end(), std::size_t(0));
    std::reverse(perm.begin(), perm.end());
    for (int round = 0; round < 3; ++round) {
      Cloud::Ptr moved(new Cloud);
      for (std::size_t i : perm)
        moved->push_back((*cs.cloud)[i]);
      const Fingerprint f = fingerprint(moved, 2, cs.segments);
      Fingerprint back = f; // mapped back to the first order
      for (std::size_t i = 0; i < n; ++i) {
        back.labels[perm[i]] = f.labels[i];
        back.centrality[perm[i]] = f.centrality[i];
        back.supernodes[perm[i]] = f.supernodes[i];
        back.refined[perm[i]] = f.refined[i];
      }
      // Segments are numbered by their smallest index (the API's order): the same segments.
      EXPECT_TRUE(samePartition(ref.labels, back.labels)) << "order " << round;
      EXPECT_TRUE(bitIdentical(ref.centrality, back.centrality)) << "order " << round;
      EXPECT_TRUE(bitIdentical(ref.supernodes, back.supernodes)) << "order " << round;
      EXPECT_TRUE(bitIdentical(ref.refined, back.refined)) << "order " << round;
      EXPECT_TRUE(bitIdentical(ref.ncuts, back.ncuts)) << "order " << round;
      std::shuffle(perm.begin(), perm.end(), std::mt19937(static_cast<unsigned>(round + 1)));
    }
  }
}
