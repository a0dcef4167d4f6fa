// The parameter model: the table's ranges (every row at its edges and just past them), the
// presets, which changes invalidate the expensive stage, the README's table, and the core run
// alone giving the labels of the PCL class.
#include "core/pipeline/pipeline.h"
#include <pcl_ncut_seg/parameter_table.h>
#include <pcl_ncut_seg/supernode_ncut_segmentation.h>

#include "support/text_files.h"
#include <shapes/shapes.h>

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <limits>
#include <set>

using namespace pcl_ncut_seg;

namespace {

/// The next value after x towards y in single precision, so that it is a value of float
/// fields as well as of double ones.
double nextTowards(double x, double y) {
  return static_cast<double>(std::nextafter(static_cast<float>(x), static_cast<float>(y)));
}

/// Values of a numeric row inside its range (its edges where they are in it).
std::vector<double> inside(const ParameterInfo& r) {
  std::vector<double> v;
  v.push_back(r.lo_open ? nextTowards(r.lo, r.hi) : r.lo);
  if (std::isfinite(r.hi))
    v.push_back(r.hi_open ? nextTowards(r.hi, r.lo) : r.hi);
  else
    v.push_back(r.kind == ValueKind::Integer ? r.lo + 1000 : r.lo + 1e6);
  return v;
}

/// Values of a numeric row just past its range, and values no number range holds.
std::vector<double> outside(const ParameterInfo& r) {
  const double inf = std::numeric_limits<double>::infinity();
  const bool integer = r.kind == ValueKind::Integer;
  std::vector<double> v{std::numeric_limits<double>::quiet_NaN(), inf, -inf};
  v.push_back(integer ? r.lo - 1 : r.lo_open ? r.lo : nextTowards(r.lo, -inf));
  if (std::isfinite(r.hi))
    v.push_back(integer ? r.hi + 1 : r.hi_open ? r.hi : nextTowards(r.hi, inf));
  if (integer)
    v.push_back(r.lo + 0.5); // not a whole number
  return v;
}

std::string text(double v) {
  return formatNumber(v);
}

bool numeric(const ParameterInfo& r) {
  return r.kind == ValueKind::Integer || r.kind == ValueKind::Real;
}

} // namespace

TEST(ParameterTable, NamesAreUniqueAndEveryRowIsComplete) {
  std::set<std::string> names;
  for (const ParameterInfo& r : parameterTable()) {
    EXPECT_TRUE(names.insert(r.name).second) << r.name;
    EXPECT_FALSE(r.help.empty()) << r.name;
    EXPECT_FALSE(r.range.empty()) << r.name;
    EXPECT_FALSE(r.field.empty()) << r.name;
    EXPECT_EQ(findParameter(r.name), &r);
  }
  for (const Shorthand& s : parameterShorthands()) {
    EXPECT_TRUE(names.insert(s.name).second) << s.name;
    Parameters p;
    EXPECT_TRUE(setParameter(p, s.parameter, s.value)) << s.name;
  }
}

TEST(ParameterTable, DefaultsAndPaperAreValidAndReadBackExactly) {
  for (const Parameters& preset : {Parameters(), Parameters::paper()}) {
    std::string why;
    EXPECT_TRUE(validate(preset, &why)) << why;
    for (const ParameterInfo& r : parameterTable()) {
      Parameters copy; // set each field from its text
      ASSERT_TRUE(r.set(copy, r.get(preset), &why)) << r.name << ": " << why;
      EXPECT_EQ(r.get(copy), r.get(preset)) << r.name;
    }
  }
}

TEST(ParameterTable, EveryNumberAtTheEdgesOfItsRangeIsTaken) {
  for (const ParameterInfo& r : parameterTable()) {
    if (!numeric(r))
      continue;
    for (double v : inside(r)) {
      Parameters p;
      std::string why;
      EXPECT_TRUE(r.set(p, text(v), &why)) << r.name << " " << text(v) << ": " << why;
      EXPECT_TRUE(validate(p, &why)) << r.name << " " << text(v) << ": " << why;
      // Read back as the field's own precision prints it, and read again to the same value.
      EXPECT_NEAR(std::strtod(r.get(p).c_str(), nullptr), v, 1e-6 * std::max(1.0, std::fabs(v)));
      Parameters again;
      EXPECT_TRUE(r.set(again, r.get(p), nullptr)) << r.name << " " << r.get(p);
      EXPECT_EQ(r.get(again), r.get(p)) << r.name;
    }
  }
}

TEST(ParameterTable, EveryNumberPastItsRangeIsRejectedWithItsRange) {
  for (const ParameterInfo& r : parameterTable()) {
    if (!numeric(r))
      continue;
    for (double v : outside(r)) {
      Parameters p;
      const std::string before = r.get(p);
      std::string why;
      EXPECT_FALSE(r.set(p, text(v), &why)) << r.name << " took " << text(v);
      EXPECT_EQ(r.get(p), before) << r.name << ": a rejected value changed the field";
      EXPECT_NE(why.find(r.name + " must be " + r.range), std::string::npos) << why;
    }
    Parameters p;
    EXPECT_FALSE(r.set(p, "", nullptr)) << r.name;
    EXPECT_FALSE(r.set(p, "1x", nullptr)) << r.name;
    for (const char* bad : {" 1", "1 ", "0x10", "inf", "nan"}) {
      EXPECT_FALSE(r.set(p, bad, nullptr)) << r.name << " took '" << bad << "'";
    }
    if (r.kind == ValueKind::Integer) {
      for (const char* bad : {"10.0", "1e3", "4294967296", "-2147483649", "1e300"}) {
        EXPECT_FALSE(r.set(p, bad, nullptr)) << r.name << " took '" << bad << "'";
      }
    }
    EXPECT_EQ(r.set(p, "off", nullptr), r.off_word == "off") << r.name;
  }
}

TEST(ParameterTable, ValidateFindsAFieldSetPastItsRangeInCode) {
  Parameters p;
  p.similarity.beta = 0.0;
  std::string why;
  EXPECT_FALSE(validate(p, &why));
  EXPECT_EQ(why, "beta must be a number > 0, got 0");
  p = Parameters();
  p.stopping.rule = static_cast<StoppingRule>(9);
  EXPECT_FALSE(validate(p, &why));
  EXPECT_NE(why.find("stopping must be one of threshold"), std::string::npos) << why;
}

TEST(ParameterTable, ChoicesAndSwitchesReadTheirWords) {
  Parameters p;
  EXPECT_TRUE(setParameter(p, "stopping", "threshold"));
  EXPECT_EQ(p.stopping.rule, StoppingRule::Threshold);
  EXPECT_TRUE(setParameter(p, "segments", "5"));
  EXPECT_EQ(p.stopping.rule, StoppingRule::Count) << "asking for segments is the count rule";
  EXPECT_EQ(p.stopping.segments, 5);
  EXPECT_TRUE(setParameter(p, "cad", ""));
  EXPECT_TRUE(p.cad.enabled);
  EXPECT_TRUE(setParameter(p, "normalize_width", "off"));
  EXPECT_FALSE(p.similarity.normalize_width);
  EXPECT_FALSE(setParameter(p, "adjacency", "some"));
  std::string why;
  EXPECT_FALSE(setParameter(p, "no_such_thing", "1", &why));
  EXPECT_EQ(why, "unknown parameter 'no_such_thing'");
}

TEST(ParameterTable, OneNamePerParameter) {
  // The spellings of older releases are no names: each is an unknown parameter.
  for (const char* old :
       {"bridge", "cen_samples", "crossing", "area", "height", "crease", "share",
        "concavity_weight", "flat", "maxseg", "neck", "neckbound", "band", "bandcrease"}) {
    Parameters p;
    std::string why;
    EXPECT_EQ(findParameter(old), nullptr) << old;
    EXPECT_FALSE(setParameter(p, old, "0.5", &why)) << old;
    EXPECT_EQ(why, std::string("unknown parameter '") + old + "'");
    EXPECT_EQ(parameterValue(p, old), "") << old;
  }
}

TEST(ParameterTable, ThePaperPresetTurnsEveryExtensionOff) {
  const Parameters paper = Parameters::paper(), defaults;
  for (const ParameterInfo& r : parameterTable()) {
    if (r.paper || r.stage == Stage::Execution || r.name == "segments")
      continue; // the paper's own parameters keep their values
    const bool off = r.get(paper) == "off" || r.get(paper) == "saddles" ||
                     r.get(paper) == "threshold" || r.get(paper) == "exact" ||
                     (r.name == "starts" && r.get(paper) == "1"); // step 4's one start
    EXPECT_TRUE(off || r.get(paper) == r.get(defaults)) << r.name << " = " << r.get(paper);
  }
  EXPECT_EQ(paper.stopping.rule, StoppingRule::Threshold);
  EXPECT_FALSE(paper.similarity.normalize_width);
}

TEST(ParameterTable, OnlyAnalysisStagesInvalidateTheAnalysis) {
  for (const ParameterInfo& r : parameterTable()) {
    Parameters changed;
    const std::string now = r.get(changed);
    std::string other;
    if (numeric(r))
      other = text(inside(r)[0]) != now ? text(inside(r)[0]) : text(inside(r)[1]);
    else if (r.kind == ValueKind::Choice)
      other = r.choices[0] != now ? r.choices[0] : r.choices[1];
    else
      other = now == "on" ? "off" : "on";
    ASSERT_TRUE(r.set(changed, other, nullptr)) << r.name << " " << other;
    EXPECT_EQ(analysisDiffers(Parameters(), changed), isAnalysisStage(r.stage)) << r.name;
  }
}

TEST(ParameterTable, TheReadmeHoldsTheGeneratedTable) {
  const std::string readme = test::readText(std::string(PCL_NCUT_SEG_SOURCE_DIR) + "/README.md");
  const std::string begin = "<!-- parameter table: begin -->\n",
                    end = "<!-- parameter table: end -->";
  const std::size_t a = readme.find(begin), b = readme.find(end);
  ASSERT_NE(a, std::string::npos) << "README.md has no " << begin;
  ASSERT_NE(b, std::string::npos);
  const std::string table = parameterMarkdown();
  if (readme.substr(a + begin.size(), b - a - begin.size()) != table) {
    std::ofstream("parameter_table.md") << table;
    ADD_FAILURE() << "README.md's parameter table is not the table's: the generated one is in "
                     "parameter_table.md in the test's working directory";
  }
}

TEST(CorePipeline, AloneGivesTheLabelsOfThePclClass) {
  const test::LabeledShape shape = test::makeHand(4000, 3);
  std::vector<float> xyz;
  for (const auto& p : *shape.cloud)
    xyz.insert(xyz.end(), {p.x, p.y, p.z});
  for (const Parameters& params : {Parameters(), Parameters::paper()}) {
    const std::vector<std::uint32_t> core = segmentPoints(xyz.data(), shape.cloud->size(), params);
    pcl::SupernodeNCutSegmentation<pcl::PointXYZ> seg;
    seg.setInputCloud(shape.cloud);
    ASSERT_TRUE(seg.setParameters(params));
    std::vector<pcl::PointIndices> segments;
    seg.extract(segments);
    ASSERT_GT(segments.size(), 1u);
    ASSERT_EQ(core.size(), shape.cloud->size());
    for (std::size_t s = 0; s < segments.size(); ++s)
      for (int i : segments[s].indices)
        ASSERT_EQ(core[static_cast<std::size_t>(i)], s) << "point " << i;
  }
}

TEST(CorePipeline, AnalysisServesACutOnlyWithWhatItMeasured) {
  Parameters p;
  p.similarity.concavity.reset();
  p.boundary.band.reset();
  p.boundary.rim_merge.reset();
  p.similarity.thickness = false;
  EXPECT_FALSE(cutNeeds(p).concavity);
  EXPECT_FALSE(cutNeeds(p).crease);
  EXPECT_FALSE(cutNeeds(p).rim);
  EXPECT_FALSE(cutNeeds(p).thickness);
  Parameters merge_only = p;
  merge_only.boundary.rim_merge = 10.0;
  EXPECT_TRUE(cutNeeds(merge_only).rim) << "the rim merge fits planes to the rim's sides";
  Analysis a;
  EXPECT_TRUE(serves(a, p));
  EXPECT_FALSE(serves(a, Parameters())) << "the defaults' cut needs the contact concavity";
  a.measured.concavity = a.measured.crease = true;
  EXPECT_FALSE(serves(a, Parameters())) << "the defaults' cut needs the rim's bends";
  a.measured.rim = true;
  EXPECT_FALSE(serves(a, Parameters())) << "the defaults' cut needs the supernodes' thickness";
  a.measured.thickness = true;
  EXPECT_TRUE(serves(a, Parameters()));
  Parameters cad;
  cad.cad.enabled = true;
  EXPECT_FALSE(serves(a, cad)) << "a surface analysis does not serve CAD mode";
}
