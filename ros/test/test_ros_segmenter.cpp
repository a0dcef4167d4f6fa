// The ROS side without a master: the table's values as ROS holds them, the generated
// dynamic_reconfigure Config against parameterTable(), and the segmenter behind PointCloud2
// (labels in order, layout, indices, bad clouds, re-cuts on the kept analysis).
#include <pcl_ncut_seg_ros/cloud_segmenter.h>
#include <pcl_ncut_seg_ros/ros_parameters.h>

#include <pcl_ncut_seg/parameter_table.h>
#include <shapes/shapes.h>

#include <pcl_conversions/pcl_conversions.h>

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <limits>
#include <set>

using namespace pcl_ncut_seg_ros;
using pcl_ncut_seg::ParameterInfo;
using pcl_ncut_seg::Parameters;

namespace {

const ParameterInfo& row(const std::string& name) {
  const ParameterInfo* r = pcl_ncut_seg::findParameter(name);
  EXPECT_NE(r, nullptr) << name;
  return *r;
}

std::string text(const std::string& name, const Value& v) {
  std::string out, why;
  EXPECT_TRUE(valueText(row(name), v, out, &why)) << why;
  return out;
}

sensor_msgs::PointCloud2 toMsg(const pcl::PointCloud<pcl::PointXYZ>& cloud) {
  sensor_msgs::PointCloud2 msg;
  pcl::toROSMsg(cloud, msg);
  msg.header.frame_id = "sensor";
  msg.header.stamp = ros::Time(1234, 500000000);
  msg.header.seq = 7;
  return msg;
}

/// Labels and x of the labelled cloud, read by field name.
struct Labelled {
  std::vector<std::uint32_t> label;
  std::vector<float> x;
};
Labelled read(const sensor_msgs::PointCloud2& msg) {
  Labelled out;
  std::uint32_t label_at = 0, x_at = 0;
  for (const auto& f : msg.fields) {
    if (f.name == "label")
      label_at = f.offset;
    if (f.name == "x")
      x_at = f.offset;
  }
  for (std::size_t i = 0; i < std::size_t(msg.width) * msg.height; ++i) {
    std::uint32_t l;
    float x;
    std::memcpy(&l, &msg.data[i * msg.point_step + label_at], 4);
    std::memcpy(&x, &msg.data[i * msg.point_step + x_at], 4);
    out.label.push_back(l);
    out.x.push_back(x);
  }
  return out;
}

Parameters segments(int n) {
  Parameters p;
  std::string why;
  EXPECT_TRUE(pcl_ncut_seg::setParameter(p, "segments", std::to_string(n), &why)) << why;
  return p;
}

} // namespace

TEST(RosValues, NumbersBooleansAndOff) {
  EXPECT_EQ(text("k", Value::ofInteger(12)), "12");
  EXPECT_EQ(text("k", Value::ofReal(12.0)), "12");
  EXPECT_EQ(text("threshold", Value::ofReal(0.05)), "0.05");
  EXPECT_EQ(text("threshold", Value::ofInteger(0)), "0"); // 0 is in its range: no off word
  EXPECT_EQ(text("boundary_band", Value::ofText("off")), "off");
  EXPECT_EQ(text("boundary_band", Value::ofBoolean(false)), "off"); // YAML's off
  EXPECT_EQ(text("boundary_band", Value::ofReal(0.0)), "off");      // dynamic_reconfigure's
  // Not reconfigurable: off is off or false, and 0 is a number (out of its range).
  EXPECT_EQ(text("centrality_samples", Value::ofText("auto")), "auto");
  EXPECT_EQ(text("centrality_samples", Value::ofBoolean(false)), "auto");
  EXPECT_EQ(text("centrality_samples", Value::ofInteger(0)), "0");
  EXPECT_EQ(text("crease_split", Value::ofReal(0.0)), "0");
  EXPECT_EQ(text("cad", Value::ofBoolean(true)), "on");
  EXPECT_EQ(text("normalize_width", Value::ofBoolean(false)), "off");
  EXPECT_EQ(text("stopping", Value::ofText("count")), "count");
  std::string out, why;
  EXPECT_FALSE(valueText(row("k"), Value::ofBoolean(true), out, &why));
  EXPECT_NE(why.find("k must be an integer >= 2"), std::string::npos) << why;
  EXPECT_FALSE(valueText(row("cad"), Value::ofInteger(1), out, &why));
  EXPECT_FALSE(valueText(row("boundary_band"), Value::ofBoolean(true), out, &why));
}

TEST(RosValues, SetFromValueRejectsOutOfRangeAndKeepsTheValue) {
  Parameters p;
  std::string why;
  EXPECT_FALSE(setFromValue(p, row("k"), Value::ofInteger(1), &why));
  EXPECT_EQ(why, "k must be an integer >= 2, got '1'");
  EXPECT_EQ(p.graph.k, 10);
  EXPECT_FALSE(setFromValue(p, row("boundary_band"), Value::ofReal(0.7), &why));
  EXPECT_NE(why.find("boundary_band must be a number in (0, 0.5] or off"), std::string::npos);
  ASSERT_TRUE(setFromValue(p, row("boundary_band"), Value::ofReal(0.0), &why));
  EXPECT_FALSE(p.boundary.band.has_value());
  EXPECT_FALSE(setFromValue(p, row("denoise"), Value::ofReal(1.0), &why));
  EXPECT_EQ(why, "denoise must be a number > 1 or off, got '1'");
  EXPECT_EQ(p.graph.denoise, 2.0);
  ASSERT_TRUE(setFromValue(p, row("denoise"), Value::ofBoolean(false), &why));
  EXPECT_FALSE(p.graph.denoise.has_value());
  ASSERT_TRUE(setFromValue(p, row("segments"), Value::ofInteger(4), &why));
  EXPECT_EQ(p.stopping.rule, pcl_ncut_seg::StoppingRule::Count);
}

// The .cfg is written from the table at build time; check what dynamic_reconfigure made of it.
TEST(RosConfig, DescriptionsAreTheTablesCutRows) {
  const Parameters defaults;
  std::set<std::string> described;
  for (const auto& d : Config::__getParamDescriptions__())
    described.insert(d->name);
  const Config min = Config::__getMin__(), max = Config::__getMax__(),
               dflt = Config::__getDefault__();
  const Config from_defaults = toConfig(defaults);
  std::size_t rows = 0;
  for (const ParameterInfo& r : pcl_ncut_seg::parameterTable()) {
    EXPECT_EQ(described.count(r.name) == 1, isReconfigurable(r)) << r.name;
    if (!isReconfigurable(r))
      continue;
    ++rows;
    for (const auto& d : Config::__getParamDescriptions__()) {
      if (d->name != r.name)
        continue;
      boost::any lo, hi, def, mine;
      d->getValue(min, lo);
      d->getValue(max, hi);
      d->getValue(dflt, def);
      d->getValue(from_defaults, mine);
      if (d->type == "double") {
        EXPECT_EQ(r.kind, pcl_ncut_seg::ValueKind::Real) << r.name;
        EXPECT_EQ(boost::any_cast<double>(lo), r.lo) << r.name;
        EXPECT_EQ(boost::any_cast<double>(hi), r.hi) << r.name;
        EXPECT_EQ(boost::any_cast<double>(def), boost::any_cast<double>(mine)) << r.name;
      } else if (d->type == "int") {
        EXPECT_EQ(r.kind, pcl_ncut_seg::ValueKind::Integer) << r.name;
        EXPECT_EQ(boost::any_cast<int>(lo), r.lo) << r.name;
        EXPECT_EQ(boost::any_cast<int>(def), boost::any_cast<int>(mine)) << r.name;
      } else if (d->type == "bool") {
        EXPECT_EQ(boost::any_cast<bool>(def), r.get(defaults) == "on") << r.name;
      } else {
        EXPECT_EQ(r.kind, pcl_ncut_seg::ValueKind::Choice) << r.name;
        EXPECT_EQ(boost::any_cast<std::string>(def), r.get(defaults)) << r.name;
      }
    }
  }
  EXPECT_EQ(rows, described.size());
  // Not vacuous: the cut stages' parameters are there, the analysis' are not.
  for (const char* cut : {"beta", "alpha1", "alpha2", "threshold", "stopping", "boundary_band"})
    EXPECT_EQ(described.count(cut), 1u) << cut;
  EXPECT_EQ(described.count("k"), 0u);
}

TEST(RosConfig, ApplyTakesChangesAndRejectsOutOfRange) {
  Parameters p;
  Config c = toConfig(p);
  c.segments = 4;
  c.boundary_band = 0.0;
  c.beta = 0.0; // out of range (> 0)
  c.adjacency = "saddles";
  const std::vector<std::string> rejected = applyConfig(c, p);
  ASSERT_EQ(rejected.size(), 1u);
  EXPECT_NE(rejected[0].find("beta must be a number > 0"), std::string::npos) << rejected[0];
  EXPECT_EQ(p.similarity.beta, 2.0);
  EXPECT_EQ(p.stopping.segments, 4);
  EXPECT_EQ(p.stopping.rule, pcl_ncut_seg::StoppingRule::Count); // segments chose the count rule
  EXPECT_FALSE(p.boundary.band.has_value());
  EXPECT_EQ(p.similarity.adjacency, pcl_ncut_seg::Adjacency::Saddles);
  const Config back = toConfig(p);
  EXPECT_EQ(back.stopping, "count");
  EXPECT_EQ(back.beta, 2.0);
  // Nothing changed: nothing applied (the count rule stays although stopping was unchanged).
  Parameters q = p;
  EXPECT_TRUE(applyConfig(back, q).empty());
  EXPECT_EQ(q.stopping.rule, pcl_ncut_seg::StoppingRule::Count);
}

TEST(RosSegmenter, LabelsInOrderWithTheHeader) {
  const auto shape = pcl_ncut_seg::test::makeDumbbell(1500, 3);
  CloudSegmenter seg;
  std::string why;
  ASSERT_TRUE(seg.setParameters(segments(3), &why)) << why;
  const sensor_msgs::PointCloud2 in = toMsg(*shape.cloud);
  ASSERT_TRUE(seg.segment(in, nullptr, &why)) << why;
  sensor_msgs::PointCloud2 out;
  seg.labelledCloud(out);
  EXPECT_EQ(out.header.frame_id, "sensor");
  EXPECT_EQ(out.header.stamp, in.header.stamp);
  EXPECT_EQ(out.width, in.width);
  EXPECT_EQ(out.height, in.height);
  std::vector<std::string> names;
  for (const auto& f : out.fields)
    names.push_back(f.name);
  EXPECT_EQ(names, (std::vector<std::string>{"x", "y", "z", "rgb", "label"}));
  const Labelled l = read(out);
  ASSERT_EQ(l.label.size(), shape.cloud->size());
  std::set<std::uint32_t> seen(l.label.begin(), l.label.end());
  EXPECT_EQ(seen, (std::set<std::uint32_t>{1, 2, 3}));
  // In order: each point keeps its coordinates, and the balls' far sides differ in label.
  std::set<std::uint32_t> left, right;
  for (std::size_t i = 0; i < l.label.size(); ++i) {
    EXPECT_EQ(l.x[i], (*shape.cloud)[i].x);
    (l.x[i] < -1.3f ? left : l.x[i] > 1.3f ? right : seen).insert(l.label[i]);
  }
  EXPECT_EQ(left.size(), 1u);
  EXPECT_EQ(right.size(), 1u);
  EXPECT_NE(*left.begin(), *right.begin());
  EXPECT_EQ(seg.stats().segments, 3u);
  EXPECT_TRUE(seg.stats().analysed);
  // PCL reads it back as PointXYZRGBL (rgb as rgba), labels and all.
  pcl::PointCloud<pcl::PointXYZRGBL> back;
  pcl::fromROSMsg(out, back);
  ASSERT_EQ(back.size(), l.label.size());
  EXPECT_EQ(back[10].label, l.label[10]);
}

TEST(RosSegmenter, OrganizedStaysOrganizedAndNanIsLabelZero) {
  const auto shape = pcl_ncut_seg::test::makeDumbbell(1500, 5);
  pcl::PointCloud<pcl::PointXYZ> organized = *shape.cloud;
  organized.width = 50;
  organized.height = 30;
  organized.resize(1500); // keeps width x height
  organized.width = 50;
  organized.height = 30;
  const float nan = std::numeric_limits<float>::quiet_NaN();
  for (std::size_t i = 0; i < organized.size(); i += 7)
    organized[i].x = organized[i].y = organized[i].z = nan;
  organized.is_dense = false;
  CloudSegmenter seg;
  std::string why;
  ASSERT_TRUE(seg.segment(toMsg(organized), nullptr, &why)) << why;
  sensor_msgs::PointCloud2 out;
  seg.labelledCloud(out);
  EXPECT_EQ(out.width, 50u);
  EXPECT_EQ(out.height, 30u);
  EXPECT_FALSE(out.is_dense);
  const Labelled l = read(out);
  for (std::size_t i = 0; i < l.label.size(); ++i)
    EXPECT_EQ(l.label[i] == 0, i % 7 == 0) << i;
}

TEST(RosSegmenter, IndicesRestrictTheSegmentation) {
  const auto shape = pcl_ncut_seg::test::makeDumbbell(1500, 3);
  std::vector<int> indices;
  for (std::size_t i = 0; i < shape.cloud->size(); ++i)
    if ((*shape.cloud)[i].x < 0.4f)
      indices.push_back(static_cast<int>(i));
  CloudSegmenter seg;
  std::string why;
  ASSERT_TRUE(seg.setParameters(segments(2), &why)) << why;
  ASSERT_TRUE(seg.segment(toMsg(*shape.cloud), &indices, &why)) << why;
  const Labelled l = read([&] {
    sensor_msgs::PointCloud2 out;
    seg.labelledCloud(out);
    return out;
  }());
  for (std::size_t i = 0; i < l.label.size(); ++i)
    EXPECT_EQ(l.label[i] != 0, l.x[i] < 0.4f) << i;
  std::size_t listed = 0;
  for (const auto& s : seg.segmentIndices()) {
    EXPECT_EQ(s.header.frame_id, "sensor");
    listed += s.indices.size();
  }
  EXPECT_EQ(listed, indices.size());
  std::vector<int> outside{0, static_cast<int>(shape.cloud->size())};
  EXPECT_FALSE(seg.segment(toMsg(*shape.cloud), &outside, &why));
  const std::string n = std::to_string(shape.cloud->size());
  EXPECT_NE(why.find("index " + n + " is out of range for a cloud of " + n + " points."),
            std::string::npos)
      << why;
}

TEST(RosSegmenter, BadCloudsAreRejectedAndTheKeptOneStays) {
  const auto shape = pcl_ncut_seg::test::makeDumbbell(800, 3);
  CloudSegmenter seg;
  std::string why;
  ASSERT_TRUE(seg.segment(toMsg(*shape.cloud), nullptr, &why)) << why;
  const std::size_t cuts = seg.stats().cuts;

  sensor_msgs::PointCloud2 no_xyz = toMsg(*shape.cloud);
  for (auto& f : no_xyz.fields)
    f.name = "a" + f.name;
  EXPECT_FALSE(seg.segment(no_xyz, nullptr, &why));
  EXPECT_NE(why.find("no field x"), std::string::npos) << why;

  EXPECT_FALSE(seg.segment(toMsg(pcl::PointCloud<pcl::PointXYZ>()), nullptr, &why));
  EXPECT_NE(why.find("empty"), std::string::npos) << why;

  pcl::PointCloud<pcl::PointXYZ> nans(10, 1);
  const float nan = std::numeric_limits<float>::quiet_NaN();
  for (auto& p : nans)
    p.x = p.y = p.z = nan;
  EXPECT_FALSE(seg.segment(toMsg(nans), nullptr, &why));
  EXPECT_NE(why.find("no finite point"), std::string::npos) << why;

  sensor_msgs::PointCloud2 short_data = toMsg(*shape.cloud);
  short_data.data.resize(short_data.data.size() / 2);
  EXPECT_FALSE(seg.segment(short_data, nullptr, &why));
  EXPECT_NE(why.find("does not match its layout"), std::string::npos) << why;

  EXPECT_EQ(seg.stats().cuts, cuts);
  EXPECT_TRUE(seg.hasCloud());
  EXPECT_TRUE(seg.recut(&why)) << why;
}

// What a robot's stream hands over besides objects: too few distinct points, coordinates no
// sensor gives, layouts that do not hold their points.
TEST(RosSegmenter, DegenerateAndMalformedCloudsSayWhy) {
  const auto shape = pcl_ncut_seg::test::makeDumbbell(800, 3);
  CloudSegmenter seg;
  std::string why;
  const auto rejects = [&](const sensor_msgs::PointCloud2& msg, const std::string& words) {
    why.clear();
    EXPECT_FALSE(seg.segment(msg, nullptr, &why)) << words;
    EXPECT_NE(why.find(words), std::string::npos) << why;
  };
  pcl::PointCloud<pcl::PointXYZ> few;
  for (int n = 1; n <= 3; ++n) {
    few.push_back((*shape.cloud)[n]);
    rejects(toMsg(few), "fewer than k + 1 = 11 distinct finite points: only " + std::to_string(n) +
                            " points: using " + std::to_string(n - 1) +
                            " neighbours instead of 10.");
  }
  pcl::PointCloud<pcl::PointXYZ> copies; // 10 distinct points: one short of k + 1
  for (int i = 0; i < 500; ++i)
    copies.push_back((*shape.cloud)[i % 10]);
  rejects(toMsg(copies), "fewer than k + 1 = 11 distinct finite points: only 10 points");
  copies.push_back((*shape.cloud)[10]);
  EXPECT_TRUE(seg.segment(toMsg(copies), nullptr, &why)) << why;

  pcl::PointCloud<pcl::PointXYZ> huge = *shape.cloud;
  huge[5].z = -1e30f;
  rejects(toMsg(huge), "point 5 has a coordinate of 1e+30, beyond +-1000000");

  sensor_msgs::PointCloud2 wrapped = toMsg(*shape.cloud); // offset + 4 wraps round 2^32
  wrapped.fields[0].offset = 0xfffffffeu;
  rejects(wrapped, "field x is not one FLOAT32 within a point");
  sensor_msgs::PointCloud2 doubles = toMsg(*shape.cloud);
  doubles.fields[2].datatype = sensor_msgs::PointField::FLOAT64;
  rejects(doubles, "field z is not one FLOAT32 within a point (datatype 8");
  sensor_msgs::PointCloud2 rows = toMsg(*shape.cloud);
  rows.height = 20;
  rows.width = 40;
  rows.row_step = rows.point_step * rows.width - 4;
  rejects(rows, "does not match its layout");
}

// The sensor's origin as the nodelet hands it over: from TF, none (the points'), or the
// cloud's frame; what was used goes into the stats.
TEST(RosSegmenter, SensorOriginAndWhatTheStatsSay) {
  // A camera's view of a disc, moved into another frame: the camera is then at t.
  const Eigen::Vector3f t(0.5f, -0.25f, 2.0f);
  pcl::PointCloud<pcl::PointXYZ> moved = *pcl_ncut_seg::test::discView(1, 0.03f);
  for (auto& p : moved)
    p.getVector3fMap() += t;
  const sensor_msgs::PointCloud2 msg = toMsg(moved);
  CloudSegmenter seg;
  std::string why;
  SensorOrigin tf;
  tf.source = SensorOrigin::Source::Tf;
  for (int d = 0; d < 3; ++d)
    tf.xyz[d] = t[d];
  ASSERT_TRUE(seg.segment(msg, nullptr, &why, tf)) << why;
  SegmentStats s = seg.stats();
  EXPECT_TRUE(s.view);
  EXPECT_FALSE(s.origin_estimated);
  for (int d = 0; d < 3; ++d)
    EXPECT_NEAR(s.view_origin[d], t[d], 1e-4) << d;
  EXPECT_NE(s.yaml().find("origin: tf, sensor_origin: [0.5, -0.25, 2], view: true, "
                          "origin_estimated: false, view_origin: ["),
            std::string::npos)
      << s.yaml();
  // A re-cut keeps what the cloud came with.
  ASSERT_TRUE(seg.setParameters(segments(2), &why)) << why;
  ASSERT_TRUE(seg.recut(&why)) << why;
  EXPECT_EQ(seg.stats().origin.source, SensorOrigin::Source::Tf);
  EXPECT_FALSE(seg.stats().origin_estimated);

  SensorOrigin none;
  none.source = SensorOrigin::Source::Points;
  ASSERT_TRUE(seg.segment(msg, nullptr, &why, none)) << why;
  s = seg.stats();
  EXPECT_TRUE(s.view);
  EXPECT_TRUE(s.origin_estimated);
  EXPECT_NE(s.yaml().find("origin: points, sensor_origin: null, view: true, "
                          "origin_estimated: true"),
            std::string::npos)
      << s.yaml();

  // The cloud's frame: the camera's own cloud is seen from its origin.
  ASSERT_TRUE(seg.segment(toMsg(*pcl_ncut_seg::test::discView(1, 0.03f)), nullptr, &why)) << why;
  s = seg.stats();
  EXPECT_FALSE(s.origin_estimated);
  EXPECT_NE(s.yaml().find("origin: cloud_frame, sensor_origin: [0, 0, 0], view: true"),
            std::string::npos)
      << s.yaml();
  // Not a view: no view origin.
  ASSERT_TRUE(seg.segment(toMsg(*pcl_ncut_seg::test::makeDumbbell(800, 3).cloud), nullptr, &why));
  EXPECT_NE(seg.stats().yaml().find("view: false, origin_estimated: false, view_origin: null}"),
            std::string::npos)
      << seg.stats().yaml();
}

// The two stages: new cut parameters re-cut the kept analysis (the same object, no new kNN).
TEST(RosSegmenter, RecutKeepsTheAnalysis) {
  const auto shape = pcl_ncut_seg::test::makeDumbbell(1500, 3);
  CloudSegmenter seg;
  std::string why;
  EXPECT_FALSE(seg.recut(&why));
  ASSERT_TRUE(seg.setParameters(segments(2), &why)) << why;
  ASSERT_TRUE(seg.segment(toMsg(*shape.cloud), nullptr, &why)) << why;
  const pcl_ncut_seg::Analysis* analysis = seg.segmentation().getAnalysis();
  ASSERT_NE(analysis, nullptr);
  EXPECT_EQ(seg.stats().segments, 2u);

  Parameters p = seg.parameters();
  Config c = toConfig(p);
  c.segments = 3;
  EXPECT_TRUE(applyConfig(c, p).empty());
  ASSERT_TRUE(seg.setParameters(p, &why)) << why;
  ASSERT_TRUE(seg.recut(&why)) << why;
  EXPECT_EQ(seg.segmentation().getAnalysis(), analysis);
  EXPECT_FALSE(seg.stats().analysed);
  EXPECT_EQ(seg.stats().analyses, 1u);
  EXPECT_EQ(seg.stats().cuts, 2u);
  EXPECT_EQ(seg.stats().segments, 3u);
  EXPECT_NE(seg.stats().yaml().find("analysed: false"), std::string::npos);

  // An analysis parameter is no re-cut: the analysis runs again.
  p.graph.k = 12;
  ASSERT_TRUE(seg.setParameters(p, &why)) << why;
  ASSERT_TRUE(seg.recut(&why)) << why;
  EXPECT_TRUE(seg.stats().analysed);
  EXPECT_EQ(seg.stats().analyses, 2u);
}

// Switching on an extension whose measurement the kept analysis lacks runs the analysis again.
TEST(RosSegmenter, SwitchingOnBoundaryRefinementAnalysesAgain) {
  const auto shape = pcl_ncut_seg::test::makeDumbbell(1500, 3);
  CloudSegmenter seg;
  std::string why;
  Parameters p = segments(3);
  p.boundary.band.reset();
  ASSERT_TRUE(seg.setParameters(p, &why)) << why;
  ASSERT_TRUE(seg.segment(toMsg(*shape.cloud), nullptr, &why)) << why;
  Config c = toConfig(p);
  c.boundary_band = 0.2;
  EXPECT_TRUE(applyConfig(c, p).empty());
  ASSERT_TRUE(seg.setParameters(p, &why)) << why;
  ASSERT_TRUE(seg.recut(&why)) << why;
  EXPECT_TRUE(seg.stats().analysed);
  // Back off: the new analysis serves it, no analysis.
  c.boundary_band = 0.0;
  EXPECT_TRUE(applyConfig(c, p).empty());
  ASSERT_TRUE(seg.setParameters(p, &why)) << why;
  ASSERT_TRUE(seg.recut(&why)) << why;
  EXPECT_FALSE(seg.stats().analysed);
  EXPECT_EQ(seg.stats().analyses, 2u);
}
