/*
 * pcl_ncut_seg_eval end to end on a tiny benchmark made by hand: a cube whose six faces carry
 * two human segmentations, scored with the baselines whose metrics are known exactly.
 */
#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>
#include <string>
#include <vector>

#include <sys/wait.h>
#include <unistd.h>

namespace {

namespace fs = std::filesystem;

class EvalTool : public ::testing::Test {
protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() / ("pcl_ncut_seg_eval_" + std::to_string(::getpid()));
    fs::remove_all(dir_);
    fs::create_directories(dir_ / "psb" / "off");
    fs::create_directories(dir_ / "psb" / "seg" / "1");
    fs::create_directories(dir_ / "out");
    // The unit cube, six quads: -z, +z, -y, +y, -x, +x.
    std::ofstream(dir_ / "psb" / "off" / "1.off")
        << "OFF\n8 6 0\n0 0 0\n1 0 0\n1 1 0\n0 1 0\n0 0 1\n1 0 1\n1 1 1\n0 1 1\n"
           "4 0 3 2 1\n4 4 5 6 7\n4 0 1 5 4\n4 3 7 6 2\n4 0 4 7 3\n4 1 2 6 5\n";
    // One person: the top against the rest; another: one segment.
    std::ofstream(dir_ / "psb" / "seg" / "1" / "1_0.seg") << "1\n0\n1\n1\n1\n1\n";
    std::ofstream(dir_ / "psb" / "seg" / "1" / "1_1.seg") << "0\n0\n0\n0\n0\n0\n";
    std::ofstream(dir_ / "psb" / "nSeg-ByModel.txt") << "2\n";
  }
  void TearDown() override { fs::remove_all(dir_); }

  int run(const std::string& args) const {
    const std::string cmd = std::string(PCL_NCUT_SEG_EVAL) + " " + args + " > " +
                            (dir_ / "stdout.txt").string() + " 2> " +
                            (dir_ / "stderr.txt").string();
    const int status = std::system(cmd.c_str());
    return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  }
  std::string stderrText() const {
    std::ifstream in(dir_ / "stderr.txt");
    std::stringstream s;
    s << in.rdbuf();
    return s.str();
  }
  /// method,mode -> columns of models.csv
  std::map<std::string, std::vector<std::string>> models() const {
    std::map<std::string, std::vector<std::string>> out;
    std::ifstream in(dir_ / "out" / "models.csv");
    std::string line;
    std::getline(in, line);
    EXPECT_EQ(line, "method,mode,id,category,faces,segments,seconds,one_minus_rand_index,"
                    "hamming,hamming_rm,hamming_rf,gce,lce,human_segmentations,draw");
    while (std::getline(in, line)) {
      std::vector<std::string> cols;
      std::stringstream s(line);
      std::string c;
      while (std::getline(s, c, ','))
        cols.push_back(c);
      out[cols[0] + "," + cols[1]] = cols;
    }
    return out;
  }
  fs::path dir_;
};

TEST_F(EvalTool, ScoresTheBaselinesAsComputedByHand) {
  const std::string args =
      (dir_ / "psb").string() + " " + (dir_ / "out").string() + " -methods one,human -quiet";
  ASSERT_EQ(run(args), 0) << stderrText();
  const auto rows = models();
  ASSERT_EQ(rows.size(), 4u); // two methods, two modes
  // One segment against "top | rest": 1 - RI = 5/15 (the pairs with the top face), Rm = 0,
  // Rf = 1/6; against "one segment": all 0. Averaged over the two people.
  const auto& one = rows.at("\"one\",auto");
  EXPECT_EQ(one[2], "1");
  EXPECT_EQ(one[3], "Human");
  EXPECT_EQ(one[4], "6");
  EXPECT_EQ(one[5], "1");
  EXPECT_NEAR(std::stod(one[7]), 1.0 / 6, 1e-6);
  EXPECT_NEAR(std::stod(one[8]), 1.0 / 24, 1e-6);
  EXPECT_NEAR(std::stod(one[9]), 0.0, 1e-6);
  EXPECT_NEAR(std::stod(one[10]), 1.0 / 12, 1e-6);
  EXPECT_NEAR(std::stod(one[11]), 0.0, 1e-6);
  EXPECT_EQ(one[13], "2");
  // People against each other: 1 - RI 1/3 both ways; 1.5 segments on average.
  const auto& human = rows.at("\"human\",given");
  EXPECT_NEAR(std::stod(human[7]), 1.0 / 3, 1e-6);
  EXPECT_NEAR(std::stod(human[5]), 1.5, 1e-6);
  EXPECT_TRUE(fs::exists(dir_ / "out" / "categories.csv"));
  EXPECT_TRUE(fs::exists(dir_ / "out" / "tables.md"));
}

TEST_F(EvalTool, RunsEveryMethodOnAModel) {
  // Too few faces for a meaningful segmentation, but every method must run and be scored.
  const std::string args = (dir_ / "psb").string() + " " + (dir_ / "out").string() + " -quiet";
  ASSERT_EQ(run(args), 0) << stderrText();
  const auto rows = models();
  for (const char* method : {"ours", "lccp", "cpc", "one", "octants", "human"})
    for (const char* mode : {"auto", "given"})
      EXPECT_EQ(rows.count("\"" + std::string(method) + "\"," + mode), 1u) << method << mode;
}

TEST_F(EvalTool, RunsTheFinestLevelsOraclesOnlyWhenNamedAndSaysTheyReadThePeople) {
  const std::string psb = (dir_ / "psb").string(), out = (dir_ / "out").string();
  ASSERT_EQ(run(psb + " " + out + " -quiet -methods one"), 0) << stderrText();
  EXPECT_EQ(models().size(), 2u); // one, in both modes
  ASSERT_EQ(run(psb + " " + out + " -methods human,finest,oracle,kmeans_oracle -modes auto " +
                "-oracle_segments 4"),
            0)
      << stderrText();
  const auto rows = models();
  ASSERT_EQ(rows.size(), 4u);
  for (const char* method : {"finest", "oracle", "kmeans_oracle"}) {
    const auto& r = rows.at("\"" + std::string(method) + "\",auto");
    for (int col = 7; col <= 12; ++col) {
      EXPECT_GE(std::stod(r[col]), 0.0) << method << col;
      EXPECT_LE(std::stod(r[col]), 1.0) << method << col;
    }
    EXPECT_GE(std::stod(r[5]), 1.0);
    EXPECT_LE(std::stod(r[5]), 4.0);
  }
  // The control has the finest level's count; the oracle is the finest level merged.
  EXPECT_EQ(rows.at("\"kmeans_oracle\",auto")[5], rows.at("\"finest\",auto")[5]);
  EXPECT_EQ(rows.at("\"oracle\",auto")[5], rows.at("\"finest\",auto")[5]);
  std::ifstream tables(dir_ / "out" / "tables.md"), out_text(dir_ / "stdout.txt");
  std::stringstream t, o;
  t << tables.rdbuf();
  o << out_text.rdbuf();
  EXPECT_NE(t.str().find("READ THE PEOPLE'S SEGMENTATIONS"), std::string::npos);
  EXPECT_NE(o.str().find("READ THE PEOPLE'S SEGMENTATIONS"), std::string::npos);
}

TEST_F(EvalTool, WritesTheBuildOfItsBinaryBesideTheReports) {
  ASSERT_EQ(run("-version"), 0);
  std::ifstream version_out(dir_ / "stdout.txt");
  std::string version;
  std::getline(version_out, version);
  const std::string prefix = "pcl_ncut_seg ";
  ASSERT_EQ(version.rfind(prefix, 0), 0u) << version;
  std::string build = version.substr(version.find("(build ") + 7);
  ASSERT_EQ(build.back(), ')');
  build.pop_back();
  const std::string args =
      (dir_ / "psb").string() + " " + (dir_ / "out").string() + " -methods one -modes auto -quiet";
  ASSERT_EQ(run(args), 0) << stderrText();
  std::ifstream in(dir_ / "out" / "build");
  std::string line;
  ASSERT_TRUE(std::getline(in, line));
  EXPECT_EQ(line, build) << "the build file names the binary's own build";
}

TEST_F(EvalTool, PeerSettingsComeFromTheirFile) {
  const fs::path settings = dir_ / "peer_settings.csv";
  const std::string header =
      "peer,kind,voxel,seed,normals,concavity,min_segment,cut_score,max_cuts\n";
  const std::string psb = (dir_ / "psb").string(), out = (dir_ / "out").string();
  std::ofstream(settings) << header << "lccp,whole,0.02,0.1,mesh,10,0,0.16,25\n"
                          << "cpc,views,0.02,0.08,estimated,20,3,0.1,10\n";
  EXPECT_EQ(run(psb + " " + out + " -methods lccp,cpc -modes auto -quiet -peer_settings " +
                settings.string()),
            0)
      << stderrText();
  EXPECT_EQ(models().size(), 2u);
  // A file that is no settings file, a bad row, a voxel not below its seed, and a flag over
  // the file that breaks the same rule: one line, no output.
  for (const std::string& text : {std::string("peer,kind\nlccp,whole\n"),
                                  header + "lccp,whole,0.01,0.05,bogus,10,0,0.16,25\n",
                                  header + "icp,whole,0.01,0.05,mesh,10,0,0.16,25\n",
                                  header + "lccp,whole,0.05,0.05,mesh,10,0,0.16,25\n",
                                  header + "lccp,whole,0.01,0.05,mesh,-1,0,0.16,25\n"}) {
    fs::remove_all(dir_ / "out");
    fs::create_directories(dir_ / "out");
    std::ofstream(settings) << text;
    EXPECT_EQ(run(psb + " " + out + " -methods lccp -peer_settings " + settings.string()), 1)
        << text;
    EXPECT_EQ(stderrText().find('\n'), stderrText().size() - 1) << stderrText();
    EXPECT_TRUE(fs::is_empty(dir_ / "out")) << text;
  }
  std::ofstream(settings) << header << "lccp,whole,0.02,0.1,mesh,10,0,0.16,25\n";
  EXPECT_EQ(run(psb + " " + out + " -methods lccp -peer_settings " + settings.string() +
                " -peer_voxel 0.2"),
            1);
  EXPECT_EQ(run(psb + " " + out + " -methods lccp -peer_settings " + (dir_ / "none").string()), 1);
}

TEST_F(EvalTool, ScoresDepthViewsOnTheFacesTheySee) {
  const std::string args = (dir_ / "psb").string() + " " + (dir_ / "out").string() +
                           " -views 3 -resolution 96x72 -quiet";
  ASSERT_EQ(run(args), 0) << stderrText();
  const auto rows = models();
  ASSERT_EQ(rows.size(), 7u);
  for (const char* method : {"ours", "ours whole", "lccp", "cpc", "one", "octants", "human"}) {
    const auto& r = rows.at("\"" + std::string(method) + "\",view");
    // A camera sees one to three of the cube's six faces.
    EXPECT_GE(std::stod(r[4]), 1) << method;
    EXPECT_LE(std::stod(r[4]), 3) << method;
    for (int c = 7; c <= 12; ++c) {
      EXPECT_GE(std::stod(r[c]), 0) << method;
      EXPECT_LE(std::stod(r[c]), 1) << method;
    }
  }
  // Of two people, one sees a single segment: 'one' agrees with that person, on any faces.
  EXPECT_EQ(rows.at("\"one\",view")[5], "1");
  std::ifstream md(dir_ / "out" / "tables.md");
  std::stringstream text;
  text << md.rdbuf();
  EXPECT_NE(text.str().find("Depth-camera views"), std::string::npos);
  EXPECT_NE(text.str().find("s / view"), std::string::npos);
}

TEST_F(EvalTool, ScoresEveryFormOfAView) {
  const std::string args = (dir_ / "psb").string() + " " + (dir_ / "out").string() +
                           " -views 2 -resolution 96x72 -view_forms view,crop,voxel,laser "
                           "-view_origin unknown -methods ours,whole,lccp,one -quiet";
  ASSERT_EQ(run(args), 0) << stderrText();
  const auto rows = models();
  ASSERT_EQ(rows.size(), 16u); // four methods, four forms
  for (const char* form : {"view", "crop", "voxel", "laser"})
    for (const char* method : {"ours", "ours whole", "lccp", "one"}) {
      const auto& r = rows.at("\"" + std::string(method) + "\"," + form);
      // Every form is scored on the faces the camera sees: one to three of the cube's six.
      EXPECT_EQ(r[4], rows.at("\"one\",view")[4]) << method << " " << form;
      for (int c = 7; c <= 12; ++c) {
        EXPECT_GE(std::stod(r[c]), 0) << method << " " << form;
        EXPECT_LE(std::stod(r[c]), 1) << method << " " << form;
      }
    }
  // A crop holds the frame's valid points: 'one' scores the same on both.
  EXPECT_EQ(rows.at("\"one\",crop")[7], rows.at("\"one\",view")[7]);
  std::ifstream md(dir_ / "out" / "tables.md");
  std::stringstream text;
  text << md.rdbuf();
  for (const char* title : {"Views cropped", "voxel grid", "Laser-like"})
    EXPECT_NE(text.str().find(title), std::string::npos) << title;
}

TEST_F(EvalTool, FailsCleanlyWithoutWritingAnything) {
  const std::string psb = (dir_ / "psb").string(), out = (dir_ / "out").string();
  for (const std::string& args : {psb,
                                  psb + " " + out + " -methods nothing",
                                  psb + " " + out + " -ids 0",
                                  psb + " " + out + " -threshold",
                                  (dir_ / "none").string() + " " + out,
                                  psb + " " + (dir_ / "none").string(),
                                  psb + " " + out + " -k 1",
                                  psb + " " + out + " -thresholds 0.1,x",
                                  psb + " " + out + " -threshold 0.1 -thresholds 0.1,0.2",
                                  psb + " " + out + " -modes ,",
                                  psb + " " + out + " -crease_split 0",
                                  psb + " " + out + " -crease_split 0.1 -crease_split 0.2",
                                  psb + " " + out + " -creasesplit 0.2",
                                  psb + " " + out + " -neck_bound 0",
                                  psb + " " + out + " -segments 3 -thresholds 0.1,0.2",
                                  psb + " " + out + " -bogus",
                                  psb + " " + out + " -views 0",
                                  psb + " " + out + " -views 1 -modes auto",
                                  psb + " " + out + " -views 1 -thresholds 0.1,0.2",
                                  psb + " " + out + " -resolution 64x48",
                                  psb + " " + out + " -views 1 -range_noise -1",
                                  psb + " " + out + " -views 1 -resolution 4x4",
                                  psb + " " + out + " -views 1 -samples 100",
                                  psb + " " + out + " -views 1 -view_forms view,bogus",
                                  psb + " " + out + " -views 1 -view_origin maybe",
                                  psb + " " + out + " -view_forms crop",
                                  psb + " " + out + " -peer_voxel 0.2 -peer_seed 0.1",
                                  psb + " " + out + " -noise 1",
                                  psb + " " + out + " -draws 2",
                                  psb + " " + out + " -samples 10 -permute",
                                  psb + " " + out + " -samples 10 -jitter 0.001",
                                  psb + " " + out + " -samples 10 -draws 2 -jitter 0.1 -permute",
                                  psb + " " + out + " -samples 10 -draws 2 -jitter -1",
                                  psb + " " + out + " -jitter 0.1 -draws 2",
                                  psb + " " + out + " -samples 10 -draws 0",
                                  psb + " " + out + " -samples 10 -density_ratio 0.5",
                                  psb + " " + out + " -samples 10 -noise -1",
                                  psb + " " + out + " -samples x",
                                  psb + " " + out + " -methods oracle,bogus",
                                  psb + " " + out + " -oracle_segments 5",
                                  psb + " " + out + " -methods oracle -oracle_segments 0",
                                  psb + " " + out + " -methods kmeans_oracle -views 1"}) {
    EXPECT_EQ(run(args), 1) << args;
    const std::string err = stderrText();
    EXPECT_FALSE(err.empty()) << args;
    EXPECT_EQ(err.find('\n'), err.size() - 1) << "one line: " << err;
    EXPECT_TRUE(fs::is_empty(dir_ / "out")) << args;
  }
}

TEST_F(EvalTool, SamplesDrawsAndWritesTheSpread) {
  const std::string args = (dir_ / "psb").string() + " " + (dir_ / "out").string() +
                           " -methods one,octants -modes auto -samples 300 -draws 3 -noise 0.5 "
                           "-density_ratio 2 -quiet";
  ASSERT_EQ(run(args), 0) << stderrText();
  std::ifstream in(dir_ / "out" / "models.csv");
  std::string line;
  std::getline(in, line);
  std::map<std::string, int> draws; // method,draw -> rows
  while (std::getline(in, line)) {
    const std::string method = line.substr(0, line.find(','));
    draws[method + "," + line.substr(line.rfind(',') + 1)]++;
    if (method == "\"one\"") { // one segment scores as on the centroids, whatever the samples
      EXPECT_NE(line.find(",6,1,"), std::string::npos) << line;
    }
  }
  for (const char* method : {"\"one\"", "\"octants\""})
    for (const char* d : {"0", "1", "2"})
      EXPECT_EQ(draws[std::string(method) + "," + d], 1) << method << " draw " << d;
  EXPECT_EQ(draws.size(), 6u);
  std::ifstream spread(dir_ / "out" / "spread.csv");
  std::getline(spread, line);
  EXPECT_EQ(line.substr(0, 50), "method,mode,id,category,draws,segments_min,segment");
  std::getline(spread, line);
  EXPECT_EQ(line, "\"one\",auto,1,Human,3,1,1,0.000000,0.000000,0.000000,0.000000,0.000000,"
                  "0.000000,0.000000");
  std::ifstream tables(dir_ / "out" / "tables.md");
  std::stringstream md;
  md << tables.rdbuf();
  EXPECT_NE(md.str().find("spread over 3 draws"), std::string::npos);
}

TEST_F(EvalTool, TakesTheToolsFlags) {
  const std::string args = (dir_ / "psb").string() + " " + (dir_ / "out").string() +
                           " -methods ours -modes auto -quiet ";
  ASSERT_EQ(run(args + "-crease_split 0.5 -neck_bound 0.3 -boundary_band 0.1 -rim_merge 20"), 0)
      << stderrText();
  EXPECT_FALSE(models().empty());
}

} // namespace
