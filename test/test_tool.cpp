/*
 * The pcl_ncut_seg command, driven as a user would: run it in a scratch directory, read what it
 * wrote, and check that every kind of bad input fails with one line on stderr, a non-zero exit
 * status and no file left behind. Its reports and output formats: test_tool_output.cpp.
 */
#include "tool_fixture.h"

using namespace pcl_ncut_seg::test;

namespace {

TEST_F(ToolTest, HelpListsEveryOptionWithItsDefault) {
  const ToolRun r = run("-h");
  EXPECT_EQ(r.status, 0);
  // Every parameter of the table, then the tool's own flags.
  std::vector<std::string> options;
  for (const pcl_ncut_seg::ParameterInfo& row : pcl_ncut_seg::parameterTable())
    options.push_back("-" + row.name);
  for (const char* option :
       {"-paper", "-exact", "-samples", "-seed", "-add", "-ascii", "-binary", "-split", "-quiet"})
    options.push_back(option);
  for (const std::string& option : options) {
    bool found = false;
    for (const std::string& line : lines(r.out))
      if (line.find(option + " ") != std::string::npos && line.find("default") != std::string::npos)
        found = true;
    EXPECT_TRUE(found) << option << " missing from the help, or without a default:\n" << r.out;
  }
  const ToolRun long_form = run("--help");
  EXPECT_EQ(long_form.status, 0);
  EXPECT_EQ(long_form.out, r.out);
  EXPECT_TRUE(listDir(dir_).empty());
}

TEST_F(ToolTest, DefaultRunSegmentsTheBundledModel) {
  if (!fs::exists(fs::path(kDataDir) / "armadillo.pcd"))
    GTEST_SKIP() << "no bundled model in " << kDataDir;
  const ToolRun r = run("");
  ASSERT_EQ(r.status, 0) << r.out << r.err;
  EXPECT_EQ(listDir(dir_), std::set<std::string>{"armadillo_segments.pcd"});

  for (const char* phase : {"kNN", "Cen", "Snod", "LRef", "HSeg", "PSeg"}) {
    const std::regex phase_line(std::string("^") + phase + "\\s*:\\s*[0-9.]+ s$");
    bool found = false;
    for (const std::string& line : lines(r.out))
      found = found || std::regex_match(line, phase_line);
    EXPECT_TRUE(found) << "no time for " << phase << " in:\n" << r.out;
  }
  for (const char* count : {"n", "m", "l"}) {
    const std::regex count_line(std::string("^") + count + "\\s*:\\s*[0-9]+ .*");
    bool found = false;
    for (const std::string& line : lines(r.out))
      found = found || std::regex_match(line, count_line);
    EXPECT_TRUE(found) << "no " << count << " in:\n" << r.out;
  }
  const long t = printedSegments(r.out);
  // At least its arms, legs and tail apart from the body (results/pcl_clouds.md gives the count).
  ASSERT_GE(t, 6) << r.out;

  Output output;
  ASSERT_TRUE(readOutput(dir_ / "armadillo_segments.pcd", output));
  for (const char* field : {"x", "y", "z", "rgb", "label"})
    EXPECT_NE(std::find(output.fields.begin(), output.fields.end(), field), output.fields.end())
        << "no field " << field;

  pcl::PointCloud<pcl::PointXYZ> input;
  ASSERT_EQ(pcl::io::loadPCDFile(kDataDir + "/armadillo.pcd", input), 0);
  ASSERT_EQ(output.cloud.size(), input.size());

  // Labels 1..t, all used; one colour per label, different labels in different colours.
  std::map<std::uint32_t, std::uint32_t> colour_of;
  std::set<std::uint32_t> colours;
  for (std::size_t i = 0; i < output.cloud.size(); ++i) {
    const auto& p = output.cloud[i];
    EXPECT_EQ(p.x, input[i].x);
    ASSERT_GE(p.label, 1u);
    ASSERT_LE(p.label, static_cast<std::uint32_t>(t));
    const std::uint32_t rgb = p.rgba & 0xFFFFFFu;
    const auto it = colour_of.emplace(p.label, rgb).first;
    ASSERT_EQ(it->second, rgb) << "label " << p.label << " has two colours";
  }
  EXPECT_EQ(static_cast<long>(colour_of.size()), t);
  for (const auto& lc : colour_of)
    colours.insert(lc.second);
  EXPECT_EQ(colours.size(), colour_of.size()) << "two segments share a colour";
}

TEST_F(ToolTest, SegmentsAGeneratedShapeIntoTheRequestedNumberOfSegments) {
  auto cloud = makeShape();
  // One point with no coordinates: kept in the output, in no segment.
  pcl::PointXYZ nan_point;
  nan_point.x = nan_point.y = nan_point.z = std::numeric_limits<float>::quiet_NaN();
  cloud->push_back(nan_point);
  cloud->is_dense = false;
  ASSERT_EQ(pcl::io::savePCDFileBinary((dir_ / "shape.pcd").string(), *cloud), 0);

  const ToolRun r = run("shape.pcd out.pcd -segments 2 -k 10 -threads 2");
  ASSERT_EQ(r.status, 0) << r.out << r.err;
  EXPECT_EQ(printedSegments(r.out), 2) << r.out;
  EXPECT_EQ(listDir(dir_), (std::set<std::string>{"shape.pcd", "out.pcd"}));

  Output output;
  ASSERT_TRUE(readOutput(dir_ / "out.pcd", output));
  ASSERT_EQ(output.cloud.size(), cloud->size());
  std::set<std::uint32_t> labels;
  for (std::size_t i = 0; i + 1 < output.cloud.size(); ++i) {
    EXPECT_EQ(output.cloud[i].x, (*cloud)[i].x);
    EXPECT_EQ(output.cloud[i].z, (*cloud)[i].z);
    labels.insert(output.cloud[i].label);
  }
  EXPECT_EQ(labels, (std::set<std::uint32_t>{1, 2}));
  EXPECT_EQ(output.cloud.back().label, 0u) << "a NaN point must be in no segment";
  EXPECT_EQ(output.cloud.back().rgba & 0xFFFFFFu, 0u) << "a point in no segment is black";
}

TEST_F(ToolTest, ReadsPlyAndNamesTheOutputAfterTheInput) {
  ASSERT_EQ(pcl::io::savePLYFileBinary((dir_ / "spheres.ply").string(), *makeTwoSpheres()), 0);
  const ToolRun r = run("spheres.ply -quiet");
  ASSERT_EQ(r.status, 0) << r.out << r.err;
  EXPECT_TRUE(lines(r.out).empty()) << "-quiet printed:\n" << r.out;
  EXPECT_EQ(listDir(dir_), (std::set<std::string>{"spheres.ply", "spheres_segments.pcd"}));
  Output output;
  ASSERT_TRUE(readOutput(dir_ / "spheres_segments.pcd", output));
  ASSERT_EQ(output.cloud.size(), 1200u);
  // The two spheres never share a segment.
  std::set<std::uint32_t> left, right;
  for (std::size_t i = 0; i < output.cloud.size(); ++i)
    (i < 600 ? left : right).insert(output.cloud[i].label);
  for (std::uint32_t label : left)
    EXPECT_EQ(right.count(label), 0u) << "label " << label << " on both spheres";
}

TEST_F(ToolTest, AcceptsEveryOption) {
  ASSERT_EQ(pcl::io::savePCDFileBinary((dir_ / "shape.pcd").string(), *makeShape()), 0);
  const ToolRun r = run("shape.pcd out.pcd -k 12 -centrality_samples 30 -crossing_fraction 0.3 "
                        "-area_fraction 0.01 -height_fraction 0.01 -beta 2 -alpha1 2 -alpha2 0.5 "
                        "-threshold 0.05 -threads 1 -paper");
  ASSERT_EQ(r.status, 0) << r.out << r.err;
  EXPECT_GE(printedSegments(r.out), 1) << r.out;
  EXPECT_TRUE(fs::exists(dir_ / "out.pcd"));
}

TEST_F(ToolTest, PaperIsAPresetTheFlagsApplyOnTop) {
  ASSERT_EQ(pcl::io::savePCDFileBinary((dir_ / "shape.pcd").string(), *makeShape()), 0);
  // -paper is every parameter at its value in Parameters::paper(), spelt out...
  const pcl_ncut_seg::Parameters paper = pcl_ncut_seg::Parameters::paper();
  std::string spelt;
  for (const pcl_ncut_seg::ParameterInfo& row : pcl_ncut_seg::parameterTable())
    if (row.kind != pcl_ncut_seg::ValueKind::Switch && row.name != "segments")
      spelt += " -" + row.name + " " + row.get(paper);
  ASSERT_EQ(run("shape.pcd paper.pcd -paper").status, 0);
  ASSERT_EQ(run("shape.pcd spelt.pcd" + spelt).status, 0);
  EXPECT_EQ(readText(dir_ / "paper.pcd"), readText(dir_ / "spelt.pcd"));
  ASSERT_EQ(run("shape.pcd spelt.pcd -threshold 0.05" + spelt).status, 1) << "given twice";
  // ... and a flag given with it changes its parameter only, wherever it stands.
  ASSERT_EQ(run("shape.pcd paper_k.pcd -paper -k 14 -concavity 3").status, 0);
  ASSERT_EQ(run("shape.pcd k_paper.pcd -k 14 -concavity 3 -paper").status, 0);
  EXPECT_EQ(readText(dir_ / "paper_k.pcd"), readText(dir_ / "k_paper.pcd"));
  std::string spelt_k = spelt;
  for (const auto& [from, to] : {std::pair<std::string, std::string>{" -k 10", " -k 14"},
                                 {" -concavity off", " -concavity 3"}}) {
    ASSERT_NE(spelt_k.find(from), std::string::npos) << spelt_k;
    spelt_k.replace(spelt_k.find(from), from.size(), to);
  }
  ASSERT_EQ(run("shape.pcd spelt_k.pcd" + spelt_k).status, 0);
  EXPECT_EQ(readText(dir_ / "paper_k.pcd"), readText(dir_ / "spelt_k.pcd"));
  EXPECT_NE(readText(dir_ / "paper_k.pcd"), readText(dir_ / "spelt.pcd"));
}

TEST_F(ToolTest, OldSpellingsAreUnknownOptions) {
  // One name per parameter: the spellings of older releases fail as any unknown option.
  ASSERT_EQ(pcl::io::savePCDFileBinary((dir_ / "shape.pcd").string(), *makeShape()), 0);
  for (const char* old :
       {"-crossing 0.25", "-crease 0.5", "-flat 0.2", "-neck 2", "-band 0.1", "-cen_samples 40"}) {
    const std::string flag = std::string(old).substr(0, std::string(old).find(' '));
    expectCleanFailure(std::string("shape.pcd old.pcd ") + old, "unknown option " + flag);
  }
  const ToolRun help = run("-h");
  EXPECT_EQ(help.out.find("[also"), std::string::npos) << help.out;
}

TEST_F(ToolTest, OverwritesAnExistingOutput) {
  ASSERT_EQ(pcl::io::savePCDFileBinary((dir_ / "shape.pcd").string(), *makeShape()), 0);
  writeFile("out.pcd", "old contents\n");
  const ToolRun r = run("shape.pcd out.pcd -segments 3");
  ASSERT_EQ(r.status, 0) << r.out << r.err;
  Output output;
  ASSERT_TRUE(readOutput(dir_ / "out.pcd", output));
  EXPECT_EQ(listDir(dir_), (std::set<std::string>{"shape.pcd", "out.pcd"}));
}

TEST_F(ToolTest, BadInputFilesFailCleanly) {
  ASSERT_EQ(pcl::io::savePCDFileBinary((dir_ / "shape.pcd").string(), *makeShape()), 0);
  expectCleanFailure("missing.pcd out.pcd", "missing.pcd");
  expectCleanFailure("missing.ply out.pcd", "missing.ply");

  writeFile("zero_bytes.pcd", "");
  expectCleanFailure("zero_bytes.pcd out.pcd", "zero_bytes.pcd");
  writeFile("garbage.ply", "this is not a ply file\n");
  expectCleanFailure("garbage.ply out.pcd", "garbage.ply");

  writeFile("empty_cloud.pcd", "# .PCD v0.7 - Point Cloud Data file format\n"
                               "VERSION 0.7\nFIELDS x y z\nSIZE 4 4 4\nTYPE F F F\nCOUNT 1 1 1\n"
                               "WIDTH 0\nHEIGHT 1\nVIEWPOINT 0 0 0 1 0 0 0\nPOINTS 0\n"
                               "DATA ascii\n");
  expectCleanFailure("empty_cloud.pcd out.pcd", "empty_cloud.pcd");

  pcl::PointCloud<pcl::Intensity> intensity;
  for (int i = 0; i < 50; ++i) {
    pcl::Intensity p;
    p.intensity = static_cast<float>(i);
    intensity.push_back(p);
  }
  ASSERT_EQ(pcl::io::savePCDFileASCII((dir_ / "intensity.pcd").string(), intensity), 0);
  expectCleanFailure("intensity.pcd out.pcd", "intensity.pcd");

  pcl::PointCloud<pcl::PointXYZ> nans;
  nans.push_back(pcl::PointXYZ(std::nanf(""), 0, 0));
  nans.push_back(pcl::PointXYZ(0, std::nanf(""), 0));
  nans.is_dense = false;
  ASSERT_EQ(pcl::io::savePCDFileBinary((dir_ / "nans.pcd").string(), nans), 0);
  expectCleanFailure("nans.pcd out.pcd", "nans.pcd");

  fs::create_directory(dir_ / "a_directory.pcd");
  expectCleanFailure("a_directory.pcd out.pcd", "a_directory.pcd");
  expectCleanFailure("shape.xyz out.pcd", "shape.xyz");
  expectCleanFailure("shape.pcd out.pcd extra.pcd");
}

TEST_F(ToolTest, UnknownFlagsFailCleanly) {
  ASSERT_EQ(pcl::io::savePCDFileBinary((dir_ / "shape.pcd").string(), *makeShape()), 0);
  expectCleanFailure("shape.pcd out.pcd -bogus", "-bogus");
  expectCleanFailure("shape.pcd out.pcd -bogus 3", "-bogus");
  expectCleanFailure("-K 10 shape.pcd out.pcd", "-K");
  expectCleanFailure("shape.pcd out.pcd --k 10", "--k");
}

TEST_F(ToolTest, BadParameterValuesFailCleanly) {
  ASSERT_EQ(pcl::io::savePCDFileBinary((dir_ / "shape.pcd").string(), *makeShape()), 0);
  const std::vector<std::pair<std::string, std::string>> bad = {{"-k", "1"},
                                                                {"-k", "abc"},
                                                                {"-k", "2.5"},
                                                                {"-k", "10x"},
                                                                {"-k", "''"},
                                                                {"-centrality_samples", "-1"},
                                                                {"-centrality_samples", "0"},
                                                                {"-crossing_fraction", "1.5"},
                                                                {"-crossing_fraction", "-0.1"},
                                                                {"-area_fraction", "2"},
                                                                {"-height_fraction", "nan"},
                                                                {"-beta", "0"},
                                                                {"-beta", "-1"},
                                                                {"-alpha1", "inf"},
                                                                {"-alpha2", "0"},
                                                                {"-threshold", "-0.1"},
                                                                {"-threshold", "nan"},
                                                                {"-segments", "0"},
                                                                {"-threads", "-1"},
                                                                {"-k", "99999999999999"},
                                                                {"-boundary_band", "0"},
                                                                {"-rim_merge", "0"}};
  for (const auto& option_value : bad)
    expectCleanFailure("shape.pcd out.pcd " + option_value.first + " " + option_value.second,
                       option_value.first);
  expectCleanFailure("shape.pcd out.pcd -k", "-k");        // no value
  expectCleanFailure("shape.pcd out.pcd -k 8 -k 9", "-k"); // given twice
  expectCleanFailure("shape.pcd out.pcd -threshold 0.1 -segments 3");
}

TEST_F(ToolTest, UnwritableOutputFailsCleanly) {
  ASSERT_EQ(pcl::io::savePCDFileBinary((dir_ / "shape.pcd").string(), *makeShape()), 0);
  expectCleanFailure("shape.pcd no_such_dir/out.pcd", "no_such_dir/out.pcd");
  expectCleanFailure("shape.pcd out.txt", "out.txt");
  expectCleanFailure("shape.pcd /proc/out.pcd", "/proc/out.pcd");

  // A read-only directory (root writes anywhere, so only as another user).
  if (::geteuid() != 0) {
    fs::create_directory(dir_ / "read_only");
    fs::permissions(dir_ / "read_only", fs::perms::owner_read | fs::perms::owner_exec);
    expectCleanFailure("shape.pcd read_only/out.pcd", "read_only/out.pcd");
    EXPECT_TRUE(fs::is_empty(dir_ / "read_only"));
  }

  // A failed run leaves an existing output as it was.
  writeFile("out.pcd", "old contents\n");
  expectCleanFailure("missing.pcd out.pcd");
  EXPECT_EQ(readText(dir_ / "out.pcd"), "old contents\n");
}

} // namespace
