/*
 * pcl_ncut_seg_eval: score pcl::SupernodeNCutSegmentation and its peers on the Princeton
 * Segmentation Benchmark (Chen et al. 2009) with the benchmark's metrics.
 *
 *   pcl_ncut_seg_eval <psb_dir> <out_dir> [options]
 *
 * For each mesh <psb_dir>/off/<id>.off: one point at each face's centroid (so each point
 * carries its face's human label), a segmentation by each method, and the metrics against every
 * human segmentation <psb_dir>/seg/<id>/<id>_<k>.seg, averaged per model and then over models.
 * Writes <out_dir>/models.csv, categories.csv and tables.md.
 */
#include "cli/algorithm_flags.h"
#include "cli/console.h"
#include "cli/flags.h"
#include "cli/output.h"
#include "eval_model.h"
#include "eval_options.h"
#include "eval_report.h"
#include "eval_views.h"
#include "mesh_sampling.h"
#include "psb_metrics.h"
#include "psb_peers.h"

#include <pcl/console/print.h>

#include <algorithm>
#include <chrono>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <set>
#include <string>
#include <utility>
#include <vector>

namespace fs = std::filesystem;
using namespace pcl_ncut_seg::tool;
using pcl_ncut_seg::SegmentationScores;
using pcl_ncut_seg::eval::evalFlags;
using pcl_ncut_seg::eval::Failure;
using pcl_ncut_seg::eval::Options;
using pcl_ncut_seg::eval::printHelp;
using pcl_ncut_seg::eval::readOptions;

namespace {

using pcl_ncut_seg::eval::againstHumans;
using pcl_ncut_seg::eval::countSegments;
using pcl_ncut_seg::eval::fixed;
using pcl_ncut_seg::eval::Model;
using pcl_ncut_seg::eval::Report;
using pcl_ncut_seg::eval::Row;
using pcl_ncut_seg::eval::secondsSince;
using pcl_ncut_seg::eval::segmentsToLabels;

/** The segmenter set to these parameters (valid: the flag table checked them). */
void configure(Segmenter& seg, const pcl_ncut_seg::Parameters& params) {
  if (!seg.setParameters(params))
    throw Failure("the segmenter refused the parameters");
}

// -------------------------------------------------------------------------------- benchmark

/** The benchmark's folder: the models to score and the counts of the given mode. */
struct Benchmark {
  fs::path dir;
  std::vector<int> ids;
  std::vector<int> given_counts; ///< nSeg-ByModel.txt, by id - 1
};

Benchmark openBenchmark(const Options& opt) {
  Benchmark b;
  b.dir = opt.psb_dir;
  if (!fs::is_directory(b.dir / "off") || !fs::is_directory(b.dir / "seg"))
    throw Failure(opt.psb_dir + " has no off/ and seg/ directories");
  if (!fs::is_directory(opt.out_dir))
    throw Failure("output directory " + opt.out_dir + " does not exist");
  AtomicFile probe; // removed at once: the reports can be written there
  if (!probe.open((fs::path(opt.out_dir) / "models.csv").string()))
    throw Failure(""); // probe.open printed why
  b.ids = opt.ids;
  if (b.ids.empty()) {
    for (const auto& e : fs::directory_iterator(b.dir / "off")) {
      const std::string stem = e.path().stem().string();
      if (e.path().extension() == ".off" && !stem.empty() &&
          stem.find_first_not_of("0123456789") == std::string::npos)
        b.ids.push_back(std::stoi(stem));
    }
    std::sort(b.ids.begin(), b.ids.end());
  }
  if (b.ids.empty())
    throw Failure("no models in " + (b.dir / "off").string());
  std::ifstream in(b.dir / "nSeg-ByModel.txt");
  for (int v = 0; in >> v;)
    b.given_counts.push_back(v);
  return b;
}

Model loadModel(const Benchmark& b, int id, bool need_count) {
  Model m;
  m.id = id;
  m.name = std::to_string(id);
  m.category = pcl_ncut_seg::psbCategory(id);
  std::string error;
  if (!pcl_ncut_seg::readOff((b.dir / "off" / (m.name + ".off")).string(), m.mesh, &error))
    throw Failure(error);
  m.xyz = pcl_ncut_seg::faceCentroids(m.mesh);
  m.area = pcl_ncut_seg::faceAreas(m.mesh);
  m.n = m.xyz.size() / 3;
  std::vector<fs::path> files;
  if (fs::is_directory(b.dir / "seg" / m.name))
    for (const auto& e : fs::directory_iterator(b.dir / "seg" / m.name))
      if (e.path().extension() == ".seg")
        files.push_back(e.path());
  std::sort(files.begin(), files.end());
  if (files.empty())
    throw Failure("no human segmentations of model " + m.name);
  for (const auto& f : files) {
    m.humans.emplace_back();
    if (!pcl_ncut_seg::readSeg(f.string(), m.humans.back()) || m.humans.back().size() != m.n)
      throw Failure(f.string() + ": unreadable or not one label per face");
  }
  m.given = id <= static_cast<int>(b.given_counts.size()) ? b.given_counts[id - 1] : 0;
  if (need_count && m.given <= 0)
    throw Failure("no segment count for model " + m.name + " in nSeg-ByModel.txt");
  return m;
}

// ---------------------------------------------------------------------------------- scoring

/** A row of the model, without its mode. */
Row rowOf(const Model& m) {
  Row r;
  r.id = m.id;
  r.category = m.category;
  r.faces = m.n;
  r.humans = m.humans.size();
  return r;
}

/** A method's labels scored against the people's. */
Row score(const Model& m, const std::string& method, const std::vector<int>& labels,
          double seconds) {
  Row r = rowOf(m);
  r.method = method;
  r.segments = static_cast<double>(countSegments(labels));
  r.seconds = seconds;
  r.scores = againstHumans(labels, m.humans, m.area);
  return r;
}

/** Methods that do not take a count give the same result in both modes: a row for each. */
void addBothModes(const Options& opt, Row r, Report& report) {
  for (const auto& mode : opt.modes) {
    r.mode = mode;
    report.rows.push_back(r);
  }
}

/** One auto-mode setting of 'ours': a threshold and a minimum segment fraction (0: off),
 * and its row's method name ("ours", or "ours t=... f=..." in a sweep). */
struct OursSetting {
  double threshold, fraction;
  std::string name;

  pcl_ncut_seg::Parameters applied(pcl_ncut_seg::Parameters p) const {
    p.stopping.threshold = threshold;
    p.stopping.min_segment_fraction.reset();
    if (fraction > 0)
      p.stopping.min_segment_fraction = fraction;
    return p;
  }
};

/** Every threshold with every fraction; without a list, the parameters' own value. */
std::vector<OursSetting> oursSettings(const Options& opt) {
  std::vector<double> thresholds = opt.thresholds, fractions = opt.fractions;
  if (thresholds.empty())
    thresholds.push_back(opt.params.stopping.threshold);
  if (fractions.empty())
    fractions.push_back(opt.params.stopping.min_segment_fraction.value_or(0.0));
  std::vector<OursSetting> settings;
  for (double t : thresholds)
    for (double f : fractions) {
      std::string name = "ours";
      if (thresholds.size() > 1)
        name += " t=" + fixed(t, 4);
      if (fractions.size() > 1)
        name += " f=" + fixed(f, 3);
      settings.push_back({t, f, name});
    }
  return settings;
}

/** 'ours' on a model: a row per auto setting (the first extract() runs both stages, the later
 * ones reuse the analysis), and the given-count row. */
void scoreOurs(const Model& m, const Options& opt, const std::vector<OursSetting>& settings,
               Report& report) {
  pcl::PointCloud<pcl::PointXYZ>::Ptr cloud(new pcl::PointCloud<pcl::PointXYZ>);
  cloud->resize(m.n);
  for (std::size_t i = 0; i < m.n; ++i)
    (*cloud)[i] = pcl::PointXYZ(m.xyz[3 * i], m.xyz[3 * i + 1], m.xyz[3 * i + 2]);
  Segmenter seg;
  seg.setInputCloud(cloud);
  std::vector<pcl::PointIndices> segments;
  double analysis_seconds = -1;
  for (std::size_t t = 0; t < settings.size() && (opt.hasMode("auto") || t == 0); ++t) {
    configure(seg, settings[t].applied(opt.params));
    const auto start = std::chrono::steady_clock::now();
    seg.extract(segments);
    const double secs = secondsSince(start);
    if (analysis_seconds < 0) {
      const auto& times = seg.getPhaseTimes();
      analysis_seconds = std::max(0.0, secs - times.hierarchy - times.points);
    }
    if (!opt.hasMode("auto"))
      break;
    Row r = score(m, settings[t].name, segmentsToLabels(segments, m.n),
                  t == 0 ? secs : analysis_seconds + secs);
    r.mode = "auto";
    report.rows.push_back(r);
  }
  if (opt.hasMode("given")) {
    pcl_ncut_seg::Parameters given = opt.params;
    given.stopping.rule = pcl_ncut_seg::StoppingRule::Count;
    given.stopping.segments = m.given;
    configure(seg, given);
    const auto start = std::chrono::steady_clock::now();
    seg.extract(segments);
    Row r =
        score(m, "ours", segmentsToLabels(segments, m.n), analysis_seconds + secondsSince(start));
    r.mode = "given";
    report.rows.push_back(r);
  }
}

/** PCL's LCCP and CPC on a model. */
void scorePeers(const Model& m, const Options& opt, Report& report) {
  for (const char* peer : {"lccp", "cpc"}) {
    if (!opt.has(peer))
      continue;
    std::vector<int> labels;
    std::string error;
    const auto start = std::chrono::steady_clock::now();
    // CPC reports every failed RANSAC draw as an error; they are part of how it works.
    pcl::console::setVerbosityLevel(pcl::console::L_ALWAYS);
    const bool ok = pcl_ncut_seg::segmentWithPclPeer(m.xyz, std::string(peer) == "cpc",
                                                     pcl_ncut_seg::PeerParams(), labels, &error);
    pcl::console::setVerbosityLevel(pcl::console::L_WARN);
    if (!ok)
      throw Failure(std::string(peer) + " on model " + m.name + ": " + error);
    addBothModes(opt, score(m, peer, labels, secondsSince(start)), report);
  }
}

/** The baselines: one segment, the octants, and each person against the others. */
void scoreBaselines(const Model& m, const Options& opt, Report& report) {
  if (opt.has("one"))
    addBothModes(opt, score(m, "one", std::vector<int>(m.n, 0), 0), report);
  if (opt.has("octants")) {
    const auto start = std::chrono::steady_clock::now();
    const std::vector<int> labels = pcl_ncut_seg::segmentOctants(m.xyz);
    addBothModes(opt, score(m, "octants", labels, secondsSince(start)), report);
  }
  if (!opt.has("human") || m.humans.size() < 2)
    return;
  Row r = rowOf(m); // the benchmark's human baseline
  r.method = "human";
  r.scores = pcl_ncut_seg::eval::humansAgainstEachOther(m.humans, m.area, &r.segments);
  addBothModes(opt, r, report);
}

// ---------------------------------------------------------------------------------- reports

/** The three reports, each written whole and named only once all three are. */
void writeReports(const Options& opt, const Report& report) {
  const fs::path dir(opt.out_dir);
  const std::pair<const char*, std::string> files[] = {
      {"models.csv", pcl_ncut_seg::eval::modelsCsv(report)},
      {"categories.csv", pcl_ncut_seg::eval::categoriesCsv(report)},
      {"tables.md", pcl_ncut_seg::eval::tablesMarkdown(report)}};
  AtomicFile out[3];
  for (int i = 0; i < 3; ++i)
    if (!out[i].open((dir / files[i].first).string()) || !writeText(out[i], files[i].second))
      throw Failure("");
  for (AtomicFile& file : out)
    if (!file.commit())
      throw Failure("");
}

/** Score every method on every model, print a line per model, write the reports. */
void evaluate(const Options& opt) {
  const Benchmark bench = openBenchmark(opt);
  const std::vector<OursSetting> settings = oursSettings(opt);
  Report report;
  report.modes = opt.modes;
  report.ids = bench.ids;
  for (const int id : bench.ids) {
    const Model m = loadModel(bench, id, opt.hasMode("given") && opt.has("ours"));
    std::string points; // in view mode, the valid points per view
    if (opt.views > 0) {
      points = ", " + fixed(pcl_ncut_seg::eval::scoreViews(m, opt, report), 0) + " points per view";
    } else {
      if (opt.has("ours"))
        scoreOurs(m, opt, settings, report);
      scorePeers(m, opt, report);
      scoreBaselines(m, opt, report);
    }
    if (!opt.quiet)
      std::cout << "model " << id << " (" << m.category << ", " << m.n << " faces, "
                << m.humans.size() << " human segmentations" << points
                << "):" << pcl_ncut_seg::eval::modelResults(report, id) << std::endl;
  }
  writeReports(opt, report);
  if (!opt.quiet)
    std::cout << pcl_ncut_seg::eval::summary(report) << "Wrote "
              << (fs::path(opt.out_dir) / "models.csv").string() << ", categories.csv, tables.md"
              << std::endl;
}

} // namespace

int main(int argc, char** argv) {
  Flags flags;
  if (!parseFlags(argc, argv, evalFlags(), flags))
    return 1;
  if (flags.has("-h")) {
    printHelp();
    return 0;
  }
  // PCL's segmenters report progress at the info level; keep the output to our summary lines.
  pcl::console::setVerbosityLevel(pcl::console::L_WARN);
  try {
    evaluate(readOptions(flags));
  } catch (const Failure& e) {
    if (*e.what())
      fail(e.what());
    return 1;
  }
  return 0;
}
