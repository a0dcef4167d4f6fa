/*
 * pcl_ncut_seg_eval: score pcl::SupernodeNCutSegmentation and its peers on the Princeton
 * Segmentation Benchmark (Chen et al. 2009) with the benchmark's metrics.
 *
 *   pcl_ncut_seg_eval <psb_dir> <out_dir> [options]
 *
 * For each mesh <psb_dir>/off/<id>.off: one point at each face's centroid (so each point
 * carries its face's human label), or the samples of a sampling condition (-samples, each face
 * then takes its nearest sample's label), a segmentation by each method, and the metrics
 * against every human segmentation <psb_dir>/seg/<id>/<id>_<k>.seg, averaged per model and then
 * over models. Writes <out_dir>/models.csv, categories.csv and tables.md (and spread.csv, the
 * spread over the draws, with -draws).
 */
#include "eval_model.h"
#include "eval_options.h"
#include "eval_oracle.h"
#include "eval_report.h"
#include "eval_sampling.h"
#include "eval_spread.h"
#include "eval_views.h"
#include "psb_metrics.h"
#include "psb_peers.h"
#include <cli/algorithm_flags.h>
#include <cli/build_info.h>
#include <cli/console.h>
#include <cli/flags.h>
#include <cli/output.h>
#include <surfaces/mesh_sampling.h>

#include <pcl/console/print.h>

#include <algorithm>
#include <chrono>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <map>
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
using pcl_ncut_seg::eval::isOracleMethod;
using pcl_ncut_seg::eval::Model;
using pcl_ncut_seg::eval::Report;
using pcl_ncut_seg::eval::Row;
using pcl_ncut_seg::eval::SampledCloud;
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

/** One draw of a model's points, and every method's face labels on each draw so far, by
 * (method, mode), for the disagreement between draws. */
using DrawLabels = std::map<std::pair<std::string, std::string>, std::vector<std::vector<int>>>;
struct Draw {
  SampledCloud cloud;
  int index = 0;
  DrawLabels* labels = nullptr;

  std::size_t points() const { return cloud.xyz.size() / 3; }
  /** The faces' labels from the points' (mapped back to the drawn order). */
  std::vector<int> faces(const std::vector<int>& point_labels) const {
    return pcl_ncut_seg::eval::faceLabels(pcl_ncut_seg::eval::mappedBack(point_labels, cloud.order),
                                          cloud.nearest);
  }
};

/** A row of the model, without its mode. */
Row rowOf(const Model& m) {
  Row r;
  r.id = m.id;
  r.category = m.category;
  r.faces = m.n;
  r.humans = m.humans.size();
  return r;
}

/** A method's face labels scored against the people's. */
Row score(const Model& m, const std::string& method, const std::vector<int>& labels, double seconds,
          int draw = 0) {
  Row r = rowOf(m);
  r.method = method;
  r.draw = draw;
  r.segments = static_cast<double>(countSegments(labels));
  r.seconds = seconds;
  r.scores = againstHumans(labels, m.humans, m.area);
  return r;
}

/** A method's points' labels on a draw, as face labels, scored; kept for the spread. */
Row scoreDraw(const Model& m, const Draw& d, const std::string& method, const std::string& mode,
              const std::vector<int>& point_labels, double seconds) {
  const std::vector<int> faces = d.faces(point_labels);
  Row r = score(m, method, faces, seconds, d.index);
  r.mode = mode;
  if (d.labels)
    (*d.labels)[{method, mode}].push_back(faces);
  return r;
}

/** Methods that do not take a count give the same result in both modes: a row for each. */
void addBothModes(const Options& opt, const Model& m, const Draw& d, const std::string& method,
                  const std::vector<int>& point_labels, double seconds, Report& report) {
  for (const auto& mode : opt.modes)
    report.rows.push_back(scoreDraw(m, d, method, mode, point_labels, seconds));
}

/** A row that is the same in both modes (the human baseline), once per mode. */
void addBothModes(const Options& opt, Row r, Report& report) {
  for (const auto& mode : opt.modes) {
    r.mode = mode;
    report.rows.push_back(r);
  }
}

/** One auto-mode setting of 'ours': a threshold, and its row's method name ("ours", or
 * "ours t=..." in a sweep). */
struct OursSetting {
  double threshold;
  std::string name;

  pcl_ncut_seg::Parameters applied(pcl_ncut_seg::Parameters p) const {
    p.stopping.threshold = threshold;
    return p;
  }
};

/** Every threshold; without a list, the parameters' own. */
std::vector<OursSetting> oursSettings(const Options& opt) {
  std::vector<double> thresholds = opt.thresholds;
  if (thresholds.empty())
    thresholds.push_back(opt.params.stopping.threshold);
  std::vector<OursSetting> settings;
  for (double t : thresholds)
    settings.push_back({t, thresholds.size() > 1 ? "ours t=" + fixed(t, 4) : "ours"});
  return settings;
}

/** A method of the finest level's diagnostic, in both modes: "finest" scored as it is, an
 * oracle merged onto each person first (eval_oracle.h). Not kept for the spread. */
void addFinestRow(const Options& opt, const Model& m, const Draw& d, const std::string& method,
                  const std::vector<int>& point_labels, double segments, double seconds,
                  Report& report) {
  const std::vector<int> faces = d.faces(point_labels);
  Row r = score(m, method, faces, seconds, d.index);
  if (isOracleMethod(method))
    r.scores = pcl_ncut_seg::eval::oracleAgainstHumans(faces, m.humans, m.area);
  r.segments = segments; // the finest level's (or k-means') count, before any merge
  addBothModes(opt, r, report);
}

/** The finest level (ours asked for -oracle_segments parts, on the analysis seg holds or
 * makes), scored as it is and as the oracle; k-means with its count per model, as the
 * control. The oracles read the people's answers: a diagnostic, no method. */
void scoreFinest(const Model& m, const Draw& d, const Options& opt, Segmenter& seg,
                 Report& report) {
  pcl_ncut_seg::Parameters finest = opt.params;
  finest.stopping.rule = pcl_ncut_seg::StoppingRule::Count;
  finest.stopping.segments = opt.oracle_segments;
  configure(seg, finest);
  std::vector<pcl::PointIndices> segments;
  auto start = std::chrono::steady_clock::now();
  seg.extract(segments);
  const double secs = secondsSince(start);
  const std::vector<int> labels = segmentsToLabels(segments, d.points());
  const double count = static_cast<double>(countSegments(labels));
  if (opt.has("finest"))
    addFinestRow(opt, m, d, "finest", labels, count, secs, report);
  if (opt.has("oracle"))
    addFinestRow(opt, m, d, "oracle", labels, count, secs, report);
  if (!opt.has("kmeans_oracle"))
    return;
  start = std::chrono::steady_clock::now(); // k-means with the count of finest, seeded
  const std::uint64_t seed = 1000003ull * static_cast<std::uint64_t>(m.id) + d.index;
  const std::vector<int> kmeans = pcl_ncut_seg::eval::kmeansLabels(
      d.cloud.xyz, std::max<std::size_t>(segments.size(), 1), seed);
  addFinestRow(opt, m, d, "kmeans_oracle", kmeans, static_cast<double>(countSegments(kmeans)),
               secondsSince(start), report);
}

/** 'ours' on a model: a row per auto setting (the first extract() runs both stages, the later
 * ones reuse the analysis), and the given-count row. */
void scoreOursRows(const Model& m, const Draw& d, const Options& opt,
                   const std::vector<OursSetting>& settings, Segmenter& seg, Report& report) {
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
    report.rows.push_back(scoreDraw(m, d, settings[t].name, "auto",
                                    segmentsToLabels(segments, d.points()),
                                    t == 0 ? secs : analysis_seconds + secs));
  }
  if (opt.hasMode("given")) {
    pcl_ncut_seg::Parameters given = opt.params;
    given.stopping.rule = pcl_ncut_seg::StoppingRule::Count;
    given.stopping.segments = m.given;
    configure(seg, given);
    const auto start = std::chrono::steady_clock::now();
    seg.extract(segments);
    report.rows.push_back(scoreDraw(m, d, "ours", "given", segmentsToLabels(segments, d.points()),
                                    analysis_seconds + secondsSince(start)));
  }
}

/** 'ours' (scoreOursRows), then the finest level's rows on the same analysis (scoreFinest:
 * their time is the cut's alone when ours ran first). */
void scoreOurs(const Model& m, const Draw& d, const Options& opt,
               const std::vector<OursSetting>& settings, Report& report) {
  const std::vector<float>& xyz = d.cloud.xyz;
  pcl::PointCloud<pcl::PointXYZ>::Ptr cloud(new pcl::PointCloud<pcl::PointXYZ>);
  cloud->resize(d.points());
  for (std::size_t i = 0; i < d.points(); ++i)
    (*cloud)[i] = pcl::PointXYZ(xyz[3 * i], xyz[3 * i + 1], xyz[3 * i + 2]);
  Segmenter seg;
  seg.setInputCloud(cloud);
  if (opt.has("ours"))
    scoreOursRows(m, d, opt, settings, seg, report);
  if (opt.hasFinest())
    scoreFinest(m, d, opt, seg, report);
}

/** PCL's LCCP and CPC on a model, with the mesh's outward normals to orient theirs by (or to
 * take as theirs), as a user who holds the mesh would. */
void scorePeers(const Model& m, const Draw& d, const Options& opt, Report& report) {
  std::vector<float> outward;
  for (const char* peer : {"lccp", "cpc"}) {
    if (!opt.has(peer))
      continue;
    if (outward.empty()) {
      const std::vector<float> faces = pcl_ncut_seg::eval::outwardFaceNormals(m.mesh);
      outward = d.cloud.nearest.empty()
                    ? faces
                    : pcl_ncut_seg::eval::nearestFaceNormals(d.cloud.xyz, m.xyz, faces);
    }
    std::vector<int> labels;
    std::string error;
    const auto start = std::chrono::steady_clock::now();
    // CPC reports every failed RANSAC draw as an error; they are part of how it works.
    pcl::console::setVerbosityLevel(pcl::console::L_ALWAYS);
    const bool cpc = std::string(peer) == "cpc";
    const bool ok = pcl_ncut_seg::segmentWithPclPeer(d.cloud.xyz, cpc, opt.peerParams(cpc, false),
                                                     labels, &error, &outward);
    pcl::console::setVerbosityLevel(pcl::console::L_WARN);
    if (!ok)
      throw Failure(std::string(peer) + " on model " + m.name + ": " + error);
    addBothModes(opt, m, d, peer, labels, secondsSince(start), report);
  }
}

/** The baselines: one segment, the octants, and each person against the others. */
void scoreBaselines(const Model& m, const Draw& d, const Options& opt, Report& report) {
  if (opt.has("one"))
    addBothModes(opt, m, d, "one", std::vector<int>(d.points(), 0), 0, report);
  if (opt.has("octants")) {
    const auto start = std::chrono::steady_clock::now();
    const std::vector<int> labels = pcl_ncut_seg::segmentOctants(d.cloud.xyz);
    addBothModes(opt, m, d, "octants", labels, secondsSince(start), report);
  }
  if (!opt.has("human") || m.humans.size() < 2 || d.index > 0)
    return;
  Row r = rowOf(m); // the benchmark's human baseline
  r.method = "human";
  r.scores = pcl_ncut_seg::eval::humansAgainstEachOther(m.humans, m.area, &r.segments);
  addBothModes(opt, r, report);
}

// ---------------------------------------------------------------------------------- reports

/** The reports (spread.csv too with draws) and the build that made them, each written whole and
 * named only once all are. */
void writeReports(const Options& opt, const Report& report) {
  const fs::path dir(opt.out_dir);
  const bool spread = report.draws > 1;
  std::vector<std::pair<const char*, std::string>> files = {
      {"models.csv", pcl_ncut_seg::eval::modelsCsv(report)},
      {"categories.csv", pcl_ncut_seg::eval::categoriesCsv(report)},
      {"tables.md", pcl_ncut_seg::eval::tablesMarkdown(report) +
                        (spread ? pcl_ncut_seg::eval::spreadMarkdown(report) : "")},
      // The binary's own build, so that a results file names what made its figures.
      {"build", std::string(pcl_ncut_seg::buildDescription()) + "\n"}};
  if (spread)
    files.emplace_back("spread.csv", pcl_ncut_seg::eval::spreadCsv(report));
  std::vector<AtomicFile> out(files.size());
  for (std::size_t i = 0; i < files.size(); ++i)
    if (!out[i].open((dir / files[i].first).string()) || !writeText(out[i], files[i].second))
      throw Failure("");
  for (AtomicFile& file : out)
    if (!file.commit())
      throw Failure("");
}

/** Draw d of a model's points under the sampling condition (the centroids without one). */
Draw makeDraw(const Model& m, const Options& opt, int index, DrawLabels& labels) {
  Draw d;
  d.index = index;
  d.labels = &labels;
  try {
    d.cloud = pcl_ncut_seg::eval::makeCloud(m.mesh, m.xyz, opt.sampling, m.id, index);
  } catch (const std::exception& e) {
    throw Failure("model " + m.name + ": " + e.what());
  }
  return d;
}

/** Per (method, mode): 1 - RI between the face labels of every two draws, their mean. */
void addBetweenDraws(const Model& m, const DrawLabels& labels, Report& report) {
  for (const auto& [key, draws] : labels) {
    double sum = 0;
    std::size_t pairs = 0;
    for (std::size_t a = 0; a < draws.size(); ++a)
      for (std::size_t b = a + 1; b < draws.size(); ++b, ++pairs)
        sum += pcl_ncut_seg::compareSegmentations(draws[a], draws[b], {}).rand_index_error;
    if (pairs > 0)
      report.between_draws[{key.first, key.second, m.id}] = sum / static_cast<double>(pairs);
  }
}

/** Every method on every draw of a model. */
void scoreModel(const Model& m, const Options& opt, const std::vector<OursSetting>& settings,
                Report& report) {
  DrawLabels labels;
  for (int index = 0; index < opt.sampling.draws; ++index) {
    const Draw d = makeDraw(m, opt, index, labels);
    if (opt.has("ours") || opt.hasFinest())
      scoreOurs(m, d, opt, settings, report);
    scorePeers(m, d, opt, report);
    scoreBaselines(m, d, opt, report);
  }
  addBetweenDraws(m, labels, report);
}

/** Score every method on every model, print a line per model, write the reports. */
void evaluate(const Options& opt) {
  const Benchmark bench = openBenchmark(opt);
  const std::vector<OursSetting> settings = oursSettings(opt);
  Report report;
  report.modes = opt.modes;
  report.ids = bench.ids;
  report.draws = opt.sampling.draws;
  for (const int id : bench.ids) {
    const Model m = loadModel(bench, id, opt.hasMode("given") && opt.has("ours"));
    std::string points; // in view mode, the valid points per view
    if (opt.views > 0) {
      points = ", " + fixed(pcl_ncut_seg::eval::scoreViews(m, opt, report), 0) + " points per view";
    } else {
      scoreModel(m, opt, settings, report);
    }
    if (!opt.quiet)
      std::cout << "model " << id << " (" << m.category << ", " << m.n << " faces, "
                << m.humans.size() << " human segmentations" << points
                << "):" << pcl_ncut_seg::eval::modelResults(report, id) << std::endl;
  }
  writeReports(opt, report);
  if (!opt.quiet)
    std::cout << pcl_ncut_seg::eval::summary(report)
              << (report.draws > 1 ? pcl_ncut_seg::eval::spreadSummary(report) : "") << "Wrote "
              << (fs::path(opt.out_dir) / "models.csv").string() << ", categories.csv, tables.md"
              << (report.draws > 1 ? ", spread.csv" : "") << std::endl;
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
  if (flags.has("-version")) {
    printVersion();
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
