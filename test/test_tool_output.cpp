/*
 * The pcl_ncut_seg command's reports and outputs: phases, counts and peak memory, the progress
 * bar, PCD encodings, added and split outputs, and meshes as input.
 */
#include "tool_fixture.h"

using namespace pcl_ncut_seg::test;

namespace {

/** The DATA line of a PCD file. */
std::string pcdDataType(const fs::path& path) {
  std::ifstream in(path);
  std::string line;
  while (std::getline(in, line))
    if (line.rfind("DATA ", 0) == 0)
      return line.substr(5);
  return "";
}

TEST_F(ToolTest, ReportsPhasesCountsAndPeakMemory) {
  ASSERT_EQ(pcl::io::savePCDFileBinary((dir_ / "shape.pcd").string(), *makeShape()), 0);
  const ToolRun r = run("shape.pcd out.pcd -segments 3");
  ASSERT_EQ(r.status, 0) << r.out << r.err;
  EXPECT_TRUE(r.err.empty()) << "stderr is not a terminal: no progress bar expected\n" << r.err;
  const std::vector<std::string> out = lines(r.out);
  for (const char* phase : {"kNN", "Cen", "Snod", "LRef", "HSeg", "PSeg", "total"}) {
    const std::regex phase_line(std::string("^") + phase + "\\s*:\\s*[0-9.]+ s$");
    EXPECT_TRUE(std::any_of(out.begin(), out.end(),
                            [&](const std::string& l) { return std::regex_match(l, phase_line); }))
        << phase << " missing:\n"
        << r.out;
  }
  for (const char* count : {"n", "m", "l", "t"}) {
    const std::regex count_line(std::string("^") + count + "\\s*:\\s*[0-9]+ .*");
    EXPECT_TRUE(std::any_of(out.begin(), out.end(),
                            [&](const std::string& l) { return std::regex_match(l, count_line); }))
        << count << " missing:\n"
        << r.out;
  }
  const std::regex mem_line("^mem\\s*:\\s*([0-9.]+) MiB peak resident memory$");
  double mib = -1;
  for (const std::string& l : out) {
    std::smatch m;
    if (std::regex_match(l, m, mem_line))
      mib = std::stod(m[1]);
  }
  EXPECT_GT(mib, 1.0) << r.out; // a process with PCL loaded uses more than 1 MiB
  EXPECT_LT(mib, 4096.0) << r.out;
}

TEST_F(ToolTest, ProgressBarOnATerminalOnly) {
  if (std::system("command -v script >/dev/null 2>&1") != 0)
    GTEST_SKIP() << "no 'script' command (util-linux) to run the tool on a terminal";
  ASSERT_EQ(pcl::io::savePCDFileBinary((dir_ / "shape.pcd").string(), *makeShape()), 0);
  // On a pseudo-terminal, with the bar's delay at 0 s instead of 1 s so that every phase shows.
  auto onTerminal = [&](const std::string& args) {
    const fs::path typescript = root_ / "typescript.txt";
    const std::string cmd = "cd " + quote(dir_.string()) +
                            " && PCL_NCUT_SEG_PROGRESS_DELAY=0 script -qec " +
                            quote(quote(kTool) + " " + args) + " /dev/null >" +
                            quote(typescript.string()) + " 2>&1 </dev/null";
    EXPECT_EQ(std::system(cmd.c_str()), 0);
    return readText(typescript);
  };
  const std::string shown = onTerminal("shape.pcd out.pcd -segments 3 -centrality_samples 200");
  EXPECT_NE(shown.find("Cen   ["), std::string::npos) << shown;
  EXPECT_NE(shown.find("%"), std::string::npos) << shown;
  EXPECT_NE(shown.find("\r\x1b[K"), std::string::npos) << "the bar is not cleared";
  const std::string quiet = onTerminal("shape.pcd out2.pcd -segments 3 -quiet");
  EXPECT_EQ(quiet.find("Cen   ["), std::string::npos) << quiet;
  EXPECT_TRUE(fs::exists(dir_ / "out.pcd"));
  EXPECT_TRUE(fs::exists(dir_ / "out2.pcd"));
}

TEST_F(ToolTest, BinaryByDefaultAsciiOnRequest) {
  ASSERT_EQ(pcl::io::savePCDFileBinary((dir_ / "shape.pcd").string(), *makeShape()), 0);
  ASSERT_EQ(run("shape.pcd binary.pcd -segments 3 -quiet").status, 0);
  ASSERT_EQ(run("shape.pcd ascii.pcd -segments 3 -quiet -ascii").status, 0);
  ASSERT_EQ(run("shape.pcd old.pcd -segments 3 -quiet -binary").status, 0); // older scripts
  EXPECT_EQ(pcdDataType(dir_ / "binary.pcd"), "binary");
  EXPECT_EQ(pcdDataType(dir_ / "ascii.pcd"), "ascii");
  EXPECT_EQ(readText(dir_ / "old.pcd"), readText(dir_ / "binary.pcd"));
  Output a, b;
  ASSERT_TRUE(readOutput(dir_ / "ascii.pcd", a));
  ASSERT_TRUE(readOutput(dir_ / "binary.pcd", b));
  ASSERT_EQ(a.cloud.size(), b.cloud.size());
  for (std::size_t i = 0; i < a.cloud.size(); ++i) { // ASCII keeps every float exactly
    ASSERT_EQ(a.cloud[i].x, b.cloud[i].x);
    ASSERT_EQ(a.cloud[i].y, b.cloud[i].y);
    ASSERT_EQ(a.cloud[i].label, b.cloud[i].label);
    ASSERT_EQ(a.cloud[i].rgba & 0xFFFFFFu, b.cloud[i].rgba & 0xFFFFFFu);
  }
  expectCleanFailure("shape.pcd both.pcd -segments 3 -ascii -binary", "-ascii");
}

TEST_F(ToolTest, AddKeepsEveryInputFieldAndAddsLabel) {
  pcl::PointCloud<pcl::PointXYZI> input;
  const auto shape = makeShape(); // kept alive: a range-for does not extend a temporary's owner
  for (const auto& p : *shape) {
    pcl::PointXYZI q;
    q.x = p.x, q.y = p.y, q.z = p.z;
    q.intensity = static_cast<float>(input.size()) * 0.5f;
    input.push_back(q);
  }
  ASSERT_EQ(pcl::io::savePCDFileBinary((dir_ / "intensity.pcd").string(), input), 0);
  const ToolRun r = run("intensity.pcd out.pcd -segments 3 -add");
  ASSERT_EQ(r.status, 0) << r.out << r.err;
  EXPECT_TRUE(r.err.empty()) << r.err;
  pcl::PCLPointCloud2 blob;
  ASSERT_EQ(pcl::io::loadPCDFile((dir_ / "out.pcd").string(), blob), 0);
  std::vector<std::string> fields;
  for (const auto& f : blob.fields)
    fields.push_back(f.name);
  EXPECT_EQ(fields, (std::vector<std::string>{"x", "y", "z", "intensity", "label"}));
  struct XYZIL {
    float x, y, z, intensity;
    std::uint32_t label;
  };
  ASSERT_EQ(blob.point_step, sizeof(XYZIL));
  ASSERT_EQ(blob.width * blob.height, input.size());
  std::set<std::uint32_t> labels;
  for (std::size_t i = 0; i < input.size(); ++i) {
    XYZIL p;
    std::memcpy(&p, &blob.data[i * blob.point_step], sizeof(p));
    ASSERT_EQ(p.x, input[i].x);
    ASSERT_EQ(p.intensity, input[i].intensity);
    labels.insert(p.label);
  }
  EXPECT_EQ(labels, (std::set<std::uint32_t>{1, 2, 3}));

  // An input that has a label already: a warning, and the label is replaced.
  pcl::PointCloud<pcl::PointXYZL> labelled;
  for (const auto& p : *shape) {
    pcl::PointXYZL q;
    q.x = p.x, q.y = p.y, q.z = p.z;
    q.label = 77;
    labelled.push_back(q);
  }
  ASSERT_EQ(pcl::io::savePCDFileBinary((dir_ / "labelled.pcd").string(), labelled), 0);
  const ToolRun w = run("labelled.pcd out2.pcd -segments 2 -add");
  ASSERT_EQ(w.status, 0) << w.out << w.err;
  ASSERT_EQ(lines(w.err).size(), 1u) << w.err;
  EXPECT_NE(lines(w.err)[0].find("label"), std::string::npos) << w.err;
  pcl::PointCloud<pcl::PointXYZL> relabelled;
  ASSERT_EQ(pcl::io::loadPCDFile((dir_ / "out2.pcd").string(), relabelled), 0);
  std::set<std::uint32_t> new_labels;
  for (const auto& p : relabelled)
    new_labels.insert(p.label);
  EXPECT_EQ(new_labels, (std::set<std::uint32_t>{1, 2}));
}

TEST_F(ToolTest, SplitWritesOneFilePerSegment) {
  ASSERT_EQ(pcl::io::savePCDFileBinary((dir_ / "shape.pcd").string(), *makeShape()), 0);
  const ToolRun r = run("shape.pcd out.pcd -segments 3 -split part");
  ASSERT_EQ(r.status, 0) << r.out << r.err;
  EXPECT_EQ(listDir(dir_), (std::set<std::string>{"shape.pcd", "out.pcd", "part_1.pcd",
                                                  "part_2.pcd", "part_3.pcd"}));
  Output all;
  ASSERT_TRUE(readOutput(dir_ / "out.pcd", all));
  std::size_t total = 0;
  for (std::uint32_t label = 1; label <= 3; ++label) {
    Output part;
    ASSERT_TRUE(readOutput(dir_ / ("part_" + std::to_string(label) + ".pcd"), part));
    EXPECT_EQ(part.fields, all.fields);
    std::size_t expected = 0;
    for (const auto& p : all.cloud)
      expected += p.label == label;
    EXPECT_EQ(part.cloud.size(), expected);
    for (const auto& p : part.cloud)
      EXPECT_EQ(p.label, label);
    total += part.cloud.size();
  }
  EXPECT_EQ(total, all.cloud.size());
  // An unwritable prefix fails before any work, and leaves nothing.
  expectCleanFailure("shape.pcd out3.pcd -segments 3 -split no_such_dir/part", "no_such_dir");
}

TEST_F(ToolTest, ReadsMeshesAsFaceCentroidsOrAreaSamples) {
  const TestMesh triangles = makeCigar(24, 32, false), quads = makeCigar(24, 32, true);
  writeFile("cigar.off", toOff(triangles));
  writeFile("cigar.obj", toObj(triangles));
  writeFile("quads.obj", toObj(quads));
  ASSERT_EQ(pcl::io::savePLYFileBinary((dir_ / "cigar.ply").string(), toPolygonMesh(triangles)), 0);

  // One point per face: as many points as faces, the same from every format.
  std::vector<Output> outputs;
  for (const char* name : {"cigar.off", "cigar.obj", "cigar.ply"}) {
    SCOPED_TRACE(name);
    const std::string out = std::string(name) + ".pcd";
    const ToolRun r = run(std::string(name) + " " + out + " -segments 2");
    ASSERT_EQ(r.status, 0) << r.out << r.err;
    EXPECT_NE(r.out.find("one point per face"), std::string::npos) << r.out;
    outputs.emplace_back();
    ASSERT_TRUE(readOutput(dir_ / out, outputs.back()));
    ASSERT_EQ(outputs.back().cloud.size(), triangles.faces.size());
  }
  for (std::size_t i = 0; i < triangles.faces.size(); ++i) {
    EXPECT_NEAR(outputs[0].cloud[i].x, outputs[1].cloud[i].x, 1e-5f);
    EXPECT_NEAR(outputs[0].cloud[i].x, outputs[2].cloud[i].x, 1e-5f);
    // The centroid of a face of the cigar lies inside its bounding box.
    EXPECT_LE(std::abs(outputs[0].cloud[i].x), 3.0f);
  }
  // Quads: one point per polygon, not per triangle.
  Output q;
  ASSERT_EQ(run("quads.obj quads.pcd -segments 2 -quiet").status, 0);
  ASSERT_TRUE(readOutput(dir_ / "quads.pcd", q));
  EXPECT_EQ(q.cloud.size(), quads.faces.size());

  // N area-uniform samples: N points on the surface, the same for the same seed.
  ASSERT_EQ(run("cigar.off s1.pcd -samples 3000 -seed 5 -segments 2 -quiet").status, 0);
  ASSERT_EQ(run("cigar.off s2.pcd -samples 3000 -seed 5 -segments 2 -quiet").status, 0);
  ASSERT_EQ(run("cigar.off s3.pcd -samples 3000 -seed 6 -segments 2 -quiet").status, 0);
  EXPECT_EQ(readText(dir_ / "s1.pcd"), readText(dir_ / "s2.pcd"));
  EXPECT_NE(readText(dir_ / "s1.pcd"), readText(dir_ / "s3.pcd"));
  Output s;
  ASSERT_TRUE(readOutput(dir_ / "s1.pcd", s));
  ASSERT_EQ(s.cloud.size(), 3000u);
  for (const auto& p : s.cloud) { // on the (flat-faceted) ellipsoid x^2/9 + y^2 + z^2 = 1
    const float e = p.x * p.x / 9 + p.y * p.y + p.z * p.z;
    ASSERT_GT(e, 0.95f);
    ASSERT_LT(e, 1.0001f);
  }
  // Equal areas get equal shares: as many samples at x < 0 as at x > 0, within 5 sigma.
  std::size_t left = 0;
  for (const auto& p : s.cloud)
    left += p.x < 0;
  EXPECT_NEAR(static_cast<double>(left), 1500.0, 5 * std::sqrt(3000 * 0.25));
}

TEST_F(ToolTest, BadMeshesAndMeshFlagsFailCleanly) {
  ASSERT_EQ(pcl::io::savePCDFileBinary((dir_ / "shape.pcd").string(), *makeShape()), 0);
  expectCleanFailure("shape.pcd out.pcd -samples 100", "-samples");
  expectCleanFailure("shape.pcd out.pcd -seed 3", "-seed");
  writeFile("no_faces.off", "OFF\n3 0 0\n0 0 0\n1 0 0\n0 1 0\n");
  expectCleanFailure("no_faces.off out.pcd", "no_faces.off");
  writeFile("bad_index.off", "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 7\n");
  expectCleanFailure("bad_index.off out.pcd", "bad_index.off");
  writeFile("flat.obj", "v 0 0 0\nv 1 0 0\nv 2 0 0\nf 1 2 3\n");
  expectCleanFailure("flat.obj out.pcd -samples 10", "flat.obj");
  writeFile("garbage.obj", "this is not a mesh\n");
  expectCleanFailure("garbage.obj out.pcd", "garbage.obj");
  writeFile("bad_face.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 9\n");
  expectCleanFailure("bad_face.obj out.pcd", "bad_face.obj");
  expectCleanFailure("missing.off out.pcd", "missing.off");
  expectCleanFailure("shape.pcd out.pcd -samples 0", "-samples");
}

} // namespace
