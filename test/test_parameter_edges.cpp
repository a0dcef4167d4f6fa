/*
 * Every parameter at the edges of its valid range (accepted, and extract() gives a partition)
 * and just past them (rejected with a PCL_ERROR naming the setter, the old value kept), through
 * its setter and through setParameter() and setParameters() for every row of the parameter
 * table; and determinism: bit-identical output across runs and thread counts.
 */
#include "core/model/model.h" // what getAnalysis() points to
#include <pcl_ncut_seg/parameter_table.h>
#include <pcl_ncut_seg/supernode_ncut_segmentation.h>
#include <shapes/metrics.h>
#include <shapes/shapes.h>
#include <support/extract_capturing.h>
#include <support/graphs.h>
#include <support/parameter_values.h>
#include <support/partition.h>

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

using pcl_ncut_seg::Adjacency;
using pcl_ncut_seg::CentralityMode;
using pcl_ncut_seg::ParameterInfo;
using pcl_ncut_seg::StoppingRule;
using std::nullopt;
using OptD = std::optional<double>;
using OptI = std::optional<int>;

const float kNaN = std::numeric_limits<float>::quiet_NaN();
const float kInf = std::numeric_limits<float>::infinity();
const double kDMin = std::numeric_limits<double>::denorm_min();
const double kDMax = std::numeric_limits<double>::max();
const double kDInf = std::numeric_limits<double>::infinity();
const double kDNaN = std::numeric_limits<double>::quiet_NaN();

/** One call of a single-parameter setter of the PCL class. */
struct ParamCase {
  std::string row; ///< the parameter table's row it sets
  const char* setter;
  std::function<void(Seg&)> set;
  std::function<bool(const Seg&)> took; ///< the getter shows the value set
};

/** Cases that set each value, which the getter must then show. */
template <typename T>
void addValid(std::vector<ParamCase>& v, const char* row, const char* setter, void (Seg::*set)(T),
              T (Seg::*get)() const, std::vector<T> values) {
  for (const T& x : values)
    v.push_back({row, setter, [set, x](Seg& s) { (s.*set)(x); },
                 [get, x](const Seg& s) { return (s.*get)() == x; }});
}

/** Cases that set each (bad) value; the setter took it when the getter no longer shows the
 * default (a NaN taken shows as a change too). */
template <typename T>
void addBad(std::vector<ParamCase>& v, const char* row, const char* setter, void (Seg::*set)(T),
            T (Seg::*get)() const, std::vector<T> values) {
  for (const T& x : values)
    v.push_back({row, setter, [set, x](Seg& s) { (s.*set)(x); },
                 [get](const Seg& s) { return !((s.*get)() == (Seg().*get)()); }});
}

#define SETTER(row, name, get) row, #name, &Seg::name, &Seg::get

/** Every setter at the ends of its field's range (the parameter table's), its off value and
 * each of its words. */
std::vector<ParamCase> validEdges() {
  std::vector<ParamCase> v;
  addValid<int>(v, SETTER("k", setNumberOfNeighbours, getNumberOfNeighbours), {2, INT_MAX});
  addValid<OptD>(v, SETTER("bridge_gap", setBridgeGap, getBridgeGap), {nullopt, kDMin, kDMax});
  addValid<OptD>(v, SETTER("denoise", setDenoise, getDenoise),
                 {nullopt, std::nextafter(1.0, 2.0), kDMax});
  addValid<OptD>(v, SETTER("irregular_sampling", setIrregularSampling, getIrregularSampling),
                 {nullopt, kDMin, kDMax});
  addValid<OptI>(v, SETTER("max_points", setMaxPoints, getMaxPoints), {nullopt, 100, INT_MAX});
  addValid<OptI>(v, SETTER("centrality_samples", setNumberOfSamples, getNumberOfSamples),
                 {nullopt, 1, INT_MAX});
  addValid<CentralityMode>(v, SETTER("centrality", setCentralityMode, getCentralityMode),
                           {CentralityMode::Exact, CentralityMode::Fast});
  addValid<int>(v, SETTER("starts", setStarts, getStarts), {1, 16});
  addValid<float>(v, SETTER("crossing_fraction", setCrossingFraction, getCrossingFraction),
                  {0.0f, 1.0f});
  addValid<float>(v, SETTER("area_fraction", setAreaFraction, getAreaFraction), {0.0f, 1.0f});
  addValid<float>(v, SETTER("height_fraction", setHeightFraction, getHeightFraction), {0.0f, 1.0f});
  addValid<OptD>(v, SETTER("crease_split", setCreaseSplit, getCreaseSplit),
                 {nullopt, kDMin, kDMax});
  addValid<bool>(v, SETTER("cad", setCadMode, getCadMode), {true, false});
  const std::vector<double> positive = {kDMin, 1e-300, 1e300, kDMax}; // for ranges (0, inf)
  addValid<double>(v, SETTER("beta", setBeta, getBeta), positive);
  addValid<double>(v, SETTER("alpha1", setAlpha1, getAlpha1), positive);
  addValid<double>(v, SETTER("alpha2", setAlpha2, getAlpha2), positive);
  addValid<bool>(v, SETTER("normalize_width", setNormalizeWidth, getNormalizeWidth), {true, false});
  addValid<Adjacency>(v, SETTER("adjacency", setAdjacency, getAdjacency),
                      {Adjacency::Saddles, Adjacency::Trees, Adjacency::All});
  addValid<OptD>(v, SETTER("concavity", setConcavityWeight, getConcavityWeight),
                 {nullopt, kDMin, kDMax});
  addValid<bool>(v, SETTER("thickness", setThickness, getThickness), {true, false});
  addValid<OptD>(v, SETTER("flat_elongation", setFlatElongation, getFlatElongation),
                 {nullopt, kDMin, kDMax});
  addValid<StoppingRule>(v, SETTER("stopping", setStoppingRule, getStoppingRule),
                         {StoppingRule::Threshold, StoppingRule::ShortCut, StoppingRule::Count});
  addValid<double>(v, SETTER("threshold", setThreshold, getThreshold), {0.0, kDMax});
  for (int n : {1, INT_MAX}) // asking for segments is choosing the count rule
    v.push_back({"segments", "setNumberOfSegments", [n](Seg& s) { s.setNumberOfSegments(n); },
                 [n](const Seg& s) {
                   return s.getNumberOfSegments() == n &&
                          s.getStoppingRule() == StoppingRule::Count;
                 }});
  addValid<int>(v, SETTER("max_segments", setMaxSegments, getMaxSegments), {1, INT_MAX});
  addValid<double>(v, SETTER("neck_bound", setNeckBound, getNeckBound), {kDMin, kDMax});
  addValid<OptD>(v, SETTER("boundary_band", setBoundaryBand, getBoundaryBand),
                 {nullopt, kDMin, 0.5});
  addValid<OptD>(v, SETTER("rim_merge", setRimMerge, getRimMerge), {nullopt, kDMin, 180.0});
  addValid<unsigned>(v, SETTER("threads", setNumberOfThreads, getNumberOfThreads),
                     {0u, 1u, 64u, UINT_MAX});
  return v;
}

/** Every setter just past the ends of its field's range, and with values no range holds. */
std::vector<ParamCase> justPast() {
  const std::vector<double> positive = {0.0, -0.0, -kDMin, kDInf, kDNaN}; // for ranges (0, inf)
  const std::vector<OptD> positive_or_off(positive.begin(), positive.end());
  const std::vector<float> fraction = {std::nextafter(0.0f, -1.0f), std::nextafter(1.0f, 2.0f),
                                       kNaN, kInf}; // for [0, 1]
  std::vector<ParamCase> v;
  addBad<int>(v, SETTER("k", setNumberOfNeighbours, getNumberOfNeighbours), {1, 0, -1, INT_MIN});
  addBad<OptD>(v, SETTER("bridge_gap", setBridgeGap, getBridgeGap), positive_or_off);
  addBad<OptD>(v, SETTER("denoise", setDenoise, getDenoise), {1.0, 0.0, kDInf, kDNaN});
  addBad<OptD>(v, SETTER("irregular_sampling", setIrregularSampling, getIrregularSampling),
               positive_or_off);
  addBad<OptI>(v, SETTER("max_points", setMaxPoints, getMaxPoints), {99, 0, -1, INT_MIN});
  addBad<OptI>(v, SETTER("centrality_samples", setNumberOfSamples, getNumberOfSamples),
               {0, -1, INT_MIN});
  addBad<CentralityMode>(v, SETTER("centrality", setCentralityMode, getCentralityMode),
                         {static_cast<CentralityMode>(7)});
  addBad<int>(v, SETTER("starts", setStarts, getStarts), {0, 17, -1, INT_MIN, INT_MAX});
  addBad<float>(v, SETTER("crossing_fraction", setCrossingFraction, getCrossingFraction), fraction);
  addBad<float>(v, SETTER("area_fraction", setAreaFraction, getAreaFraction), fraction);
  addBad<float>(v, SETTER("height_fraction", setHeightFraction, getHeightFraction), fraction);
  addBad<OptD>(v, SETTER("crease_split", setCreaseSplit, getCreaseSplit), positive_or_off);
  addBad<double>(v, SETTER("beta", setBeta, getBeta), positive);
  addBad<double>(v, SETTER("alpha1", setAlpha1, getAlpha1), positive);
  addBad<double>(v, SETTER("alpha2", setAlpha2, getAlpha2), positive);
  addBad<Adjacency>(v, SETTER("adjacency", setAdjacency, getAdjacency),
                    {static_cast<Adjacency>(7)});
  addBad<OptD>(v, SETTER("concavity", setConcavityWeight, getConcavityWeight), positive_or_off);
  addBad<OptD>(v, SETTER("flat_elongation", setFlatElongation, getFlatElongation), positive_or_off);
  addBad<StoppingRule>(v, SETTER("stopping", setStoppingRule, getStoppingRule),
                       {static_cast<StoppingRule>(7)});
  addBad<double>(v, SETTER("threshold", setThreshold, getThreshold), {-kDMin, kDInf, kDNaN});
  for (int n : {0, -1, INT_MIN})
    v.push_back({"segments", "setNumberOfSegments", [n](Seg& s) { s.setNumberOfSegments(n); },
                 [](const Seg& s) {
                   return s.getNumberOfSegments() != Seg().getNumberOfSegments() ||
                          s.getStoppingRule() != Seg().getStoppingRule();
                 }});
  addBad<int>(v, SETTER("max_segments", setMaxSegments, getMaxSegments), {0, -1, INT_MIN});
  addBad<double>(v, SETTER("neck_bound", setNeckBound, getNeckBound), {0.0, -kDMin, kDInf, kDNaN});
  addBad<OptD>(v, SETTER("boundary_band", setBoundaryBand, getBoundaryBand),
               {0.0, -kDMin, std::nextafter(0.5, 1.0), kDInf, kDNaN});
  addBad<OptD>(v, SETTER("rim_merge", setRimMerge, getRimMerge),
               {0.0, -kDMin, std::nextafter(180.0, 181.0), kDInf, kDNaN});
  return v;
}

#undef SETTER

/// Rows the PCL class has no setter of their own for: setParameters() sets them (and the
/// table-driven tests below cover them through it).
const std::map<std::string, std::string> kOnlyThroughSetParameters = {
    {"single_view", "no setter in the PCL class: the open-view test is on unless setParameters "
                    "turns it off"},
    {"ridge_angle", "no setter in the PCL class: CAD mode's angle is set with setParameters"}};

/// Rows whose setter takes a type with no value outside the range.
const std::map<std::string, std::string> kNoValuePastTheRange = {
    {"cad", "setCadMode takes a bool"},
    {"normalize_width", "setNormalizeWidth takes a bool"},
    {"thickness", "setThickness takes a bool"},
    {"threads", "setNumberOfThreads takes an unsigned, and every unsigned is valid"}};

/// The table's rows that neither the cases nor the lists name.
std::vector<std::string> rowsLeftOut(const std::vector<ParamCase>& cases,
                                     const std::map<std::string, std::string>& listed) {
  std::set<std::string> covered;
  for (const ParamCase& c : cases)
    covered.insert(c.row);
  for (const auto& entry : listed)
    covered.insert(entry.first);
  std::vector<std::string> left;
  for (const ParameterInfo& row : pcl_ncut_seg::parameterTable())
    if (!covered.count(row.name))
      left.push_back(row.name);
  return left;
}

} // namespace

TEST(Robustness, EveryRowOfTheTableHasSetterCasesOrIsListed) {
  EXPECT_EQ(rowsLeftOut(validEdges(), kOnlyThroughSetParameters), std::vector<std::string>{})
      << "add the setter's cases to validEdges(), or the row to kOnlyThroughSetParameters";
  std::map<std::string, std::string> no_past = kOnlyThroughSetParameters;
  no_past.insert(kNoValuePastTheRange.begin(), kNoValuePastTheRange.end());
  EXPECT_EQ(rowsLeftOut(justPast(), no_past), std::vector<std::string>{})
      << "add the setter's cases to justPast(), or the row to kNoValuePastTheRange";
  for (const ParamCase& c : validEdges())
    EXPECT_NE(pcl_ncut_seg::findParameter(c.row), nullptr) << c.setter << ": no row " << c.row;
  for (const auto& [name, why] : no_past)
    EXPECT_NE(pcl_ncut_seg::findParameter(name), nullptr) << "listed, but no row: " << name;
}

TEST(Robustness, ParametersAtTheEdgesOfTheirRangeAreAcceptedAndWork) {
  Cloud::Ptr c = makeDumbbell(500, 4).cloud; // few points: k = INT_MAX joins every pair
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
// Every row of the parameter table through setParameter() and setParameters(), with values
// generated from the table (support/parameter_values.h): a new row is covered as it is added.

namespace {

/** Default parameters with the row set to value by setParameter(), in CAD mode for a row that
 * only CAD mode reads. */
pcl_ncut_seg::Parameters withValue(const ParameterInfo& row, const std::string& value) {
  pcl_ncut_seg::Parameters p;
  p.cad.enabled = row.stage == pcl_ncut_seg::Stage::Cad;
  std::string why;
  EXPECT_TRUE(pcl_ncut_seg::setParameter(p, row.name, value, &why)) << why;
  return p;
}

/** Every row's value as text. */
std::vector<std::string> allValues(const pcl_ncut_seg::Parameters& p) {
  std::vector<std::string> values;
  for (const ParameterInfo& row : pcl_ncut_seg::parameterTable())
    values.push_back(row.get(p));
  return values;
}

/** A depth camera's view of a disc with a bump, every third pixel (about 500 points): the
 * open-view stages act on it, not on a whole surface. */
Cloud::Ptr smallView() {
  const Cloud::Ptr full = discView(11, 0.02f);
  Cloud::Ptr view(new Cloud(full->width / 3, full->height / 3));
  for (std::uint32_t row = 0; row < view->height; ++row)
    for (std::uint32_t col = 0; col < view->width; ++col)
      (*view)(col, row) = (*full)(3 * col, 3 * row);
  view->is_dense = false;
  return view;
}

} // namespace

TEST(Robustness, EveryRowAtTheEdgesOfItsRangeWorksThroughSetParameters) {
  const Cloud::Ptr whole = makeDumbbell(500, 4).cloud, view = smallView();
  for (const ParameterInfo& row : pcl_ncut_seg::parameterTable())
    for (const std::string& value : valuesAtTheEdges(row)) {
      SCOPED_TRACE(row.name + " " + value);
      const pcl_ncut_seg::Parameters p = withValue(row, value);
      for (const Cloud::Ptr& cloud : {whole, view}) {
        Seg seg;
        seg.setInputCloud(cloud);
        ::testing::internal::CaptureStderr();
        const bool taken = seg.setParameters(p);
        const std::string err = ::testing::internal::GetCapturedStderr();
        ASSERT_TRUE(taken) << err;
        EXPECT_EQ(allValues(seg.getParameters()), allValues(p));
        const Extracted r = extractCapturing(seg);
        ASSERT_FALSE(r.segments.empty()) << r.err;
        expectPartition(r.segments, *cloud);
      }
    }
}

TEST(Robustness, EveryRowJustPastItsRangeIsRejectedBySetParameter) {
  const std::vector<std::string> defaults = allValues(pcl_ncut_seg::Parameters());
  for (const ParameterInfo& row : pcl_ncut_seg::parameterTable())
    for (const std::string& value : valuesJustPast(row)) {
      SCOPED_TRACE(row.name + " " + value);
      pcl_ncut_seg::Parameters p;
      std::string why;
      EXPECT_FALSE(pcl_ncut_seg::setParameter(p, row.name, value, &why));
      EXPECT_EQ(why.rfind(row.name + " must be ", 0), 0u) << why;
      EXPECT_EQ(allValues(p), defaults) << "a rejected value changed the parameters";
    }
}

TEST(Robustness, TheSmallViewIsAViewAndTheDumbbellIsNot) {
  // The open-view rows above act only on a view: the test relies on these two clouds.
  for (const bool is_view : {true, false}) {
    Seg seg;
    seg.setInputCloud(is_view ? smallView() : makeDumbbell(500, 4).cloud);
    Segments out;
    seg.extract(out);
    EXPECT_EQ(seg.getViewTest().view, is_view);
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
