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
#include <pcl_ncut_seg/supernode_ncut_segmentation.h>

#include "mesh_sampling.h"
#include "psb_metrics.h"
#include "psb_peers.h"

#include <pcl/console/print.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <iostream>
#include <map>
#include <set>
#include <sstream>
#include <string>
#include <vector>

namespace fs = std::filesystem;
using pcl_ncut_seg::SegmentationScores;

namespace {

using Segmenter = pcl::SupernodeNCutSegmentation<pcl::PointXYZ>;

const std::vector<std::string> kAllMethods = {"ours", "lccp", "cpc", "one", "octants", "human"};

struct Options {
  std::string psb_dir, out_dir;
  std::vector<std::string> methods = kAllMethods;
  std::vector<std::string> modes = {"auto", "given"};
  std::vector<int> ids;           ///< empty: every off/<id>.off
  std::vector<double> thresholds; ///< auto mode; empty: the segmenter's default
  std::vector<double> fractions;  ///< auto mode, min segment fractions; empty: the default
  unsigned threads = 1;
  bool quiet = false;
  // Segmenter settings; negative / empty = the library's default.
  int k = -1;
  double crossing = -1, area = -1, height = -1, beta = -1, alpha1 = -1, alpha2 = -1;
  bool paper = false;
  bool exact = false;
  int adjacent = -1; ///< -1: default; 0/1: setConnectAllAdjacent
  int gap = -1;      ///< -1: default; 0/1: setLargestGapStopping
  int max_segments = -1;
  double gap_floor = -1;
  double adjacent_share = -1;
  double bridge_gap = -1;
  double concavity = -1;
  double flat = -1;
  double neck = -1;       ///< setNeckExponent
  double neck_bound = -1; ///< setNeckBound
  double band = -1, band_crease = -1; ///< setBoundaryBand, setBoundaryCreaseWeight
  double crease = -1;       ///< setCreaseSplit
  double crease_cut = -1;   ///< setCreaseCut
};

[[noreturn]] void fail(const std::string& reason) {
  std::cerr << "pcl_ncut_seg_eval: " << reason << std::endl;
  std::exit(1);
}

void printHelp() {
  std::cout
      << "Syntax: pcl_ncut_seg_eval <psb_dir> <out_dir> [options]\n"
         "Scores segmenters on the Princeton Segmentation Benchmark (points at face centroids)\n"
         "and writes out_dir/models.csv, categories.csv and tables.md.\n"
         "  -methods LIST     of ours,lccp,cpc,one,octants,human (default: all)\n"
         "  -modes LIST       of auto,given: the segmenter chooses the number of segments,\n"
         "                    or gets nSeg-ByModel.txt's (default: auto,given)\n"
         "  -ids LIST         model ids and ranges, e.g. 1-3,181 (default: every off/<id>.off)\n"
         "  -thresholds LIST  NCut thresholds for 'ours' in auto mode, each its own row\n"
         "                    (default: the library's default)\n"
         "  -fractions LIST   minimum segment fractions for 'ours' in auto mode, each its own\n"
         "                    row (with every threshold; default: the library's default)\n"
         "  -threads N        threads for the centrality phase (default 1)\n"
         "  -k K -crossing F -area F -height F -beta B -alpha1 A -alpha2 A\n"
         "                    segmenter settings (default: the library's defaults)\n"
         "  -adjacent 0|1     setConnectAllAdjacent (default: the library's default)\n"
         "  -share F          setAdjacentShare (default: the library's default)\n"
         "  -gap 0|1          setLargestGapStopping (default: the library's default)\n"
         "  -maxseg N         setMaxSegments (default: the library's default)\n"
         "  -gapfloor F       setGapFloor (default: the library's default)\n"
         "  -bridge F         setBridgeGap (default: the library's default)\n"
         "  -concavity W      setConcavityWeight (default: the library's default)\n"
         "  -flat E           setFlatElongation (default: the library's default)\n"
         "  -neck W           setNeckExponent, 0 = largest jump (default: the library's)\n"
         "  -neckbound K      setNeckBound (default: the library's default)\n"
         "  -band F           setBoundaryBand (default: the library's default)\n"
         "  -bandcrease W     setBoundaryCreaseWeight (default: the library's default)\n"
         "  -crease C         setCreaseSplit (default: the library's default)\n"
         "  -creasecut S      setCreaseCut (default: the library's default)\n"
         "  -exact            exact centrality (as pcl_ncut_seg -exact)\n"
         "  -paper            the paper to the letter (as pcl_ncut_seg -paper)\n"
         "  -quiet            print errors only\n";
}

std::vector<std::string> splitList(const std::string& s) {
  std::vector<std::string> out;
  std::stringstream in(s);
  std::string item;
  while (std::getline(in, item, ','))
    if (!item.empty())
      out.push_back(item);
  return out;
}

double parseNumber(const std::string& option, const std::string& value) {
  char* end = nullptr;
  const double v = std::strtod(value.c_str(), &end);
  if (value.empty() || *end != '\0' || !std::isfinite(v) || v < 0)
    fail(option + " needs a non-negative number, got '" + value + "'");
  return v;
}

Options parseOptions(int argc, char** argv) {
  Options o;
  std::vector<std::string> positional;
  std::set<std::string> seen;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    if (a == "-h" || a == "--help") {
      printHelp();
      std::exit(0);
    }
    if (a.size() < 2 || a[0] != '-') {
      positional.push_back(a);
      continue;
    }
    if (!seen.insert(a).second)
      fail("option " + a + " given twice");
    if (a == "-quiet") {
      o.quiet = true;
      continue;
    }
    if (a == "-paper") {
      o.paper = true;
      continue;
    }
    if (a == "-exact") {
      o.exact = true;
      continue;
    }
    if (i + 1 >= argc)
      fail("option " + a + " needs a value");
    const std::string v = argv[++i];
    if (a == "-methods") {
      o.methods = splitList(v);
      for (const auto& m : o.methods)
        if (std::find(kAllMethods.begin(), kAllMethods.end(), m) == kAllMethods.end())
          fail("unknown method '" + m + "'");
    } else if (a == "-modes") {
      o.modes = splitList(v);
      for (const auto& m : o.modes)
        if (m != "auto" && m != "given")
          fail("unknown mode '" + m + "'");
    } else if (a == "-ids") {
      for (const auto& item : splitList(v)) {
        int lo = 0, hi = 0;
        char dash = 0;
        std::stringstream in(item);
        if (!(in >> lo))
          fail("bad id list '" + v + "'");
        hi = lo;
        if (in >> dash && !(dash == '-' && in >> hi))
          fail("bad id list '" + v + "'");
        if (lo < 1 || hi < lo)
          fail("bad id range '" + item + "'");
        for (int id = lo; id <= hi; ++id)
          o.ids.push_back(id);
      }
    } else if (a == "-thresholds") {
      for (const auto& item : splitList(v))
        o.thresholds.push_back(parseNumber(a, item));
    } else if (a == "-fractions") {
      for (const auto& item : splitList(v))
        o.fractions.push_back(parseNumber(a, item));
    } else if (a == "-adjacent") {
      const double b = parseNumber(a, v);
      if (b != 0 && b != 1)
        fail("-adjacent needs 0 or 1");
      o.adjacent = static_cast<int>(b);
    } else if (a == "-gap") {
      const double b = parseNumber(a, v);
      if (b != 0 && b != 1)
        fail("-gap needs 0 or 1");
      o.gap = static_cast<int>(b);
    } else if (a == "-share") {
      o.adjacent_share = parseNumber(a, v);
    } else if (a == "-concavity") {
      o.concavity = parseNumber(a, v);
    } else if (a == "-flat") {
      o.flat = parseNumber(a, v);
    } else if (a == "-band") {
      o.band = parseNumber(a, v);
    } else if (a == "-bandcrease") {
      o.band_crease = parseNumber(a, v);
    } else if (a == "-crease") {
      o.crease = parseNumber(a, v);
    } else if (a == "-creasecut") {
      o.crease_cut = parseNumber(a, v);
    } else if (a == "-bridge") {
      o.bridge_gap = parseNumber(a, v);
    } else if (a == "-neck") {
      o.neck = parseNumber(a, v);
    } else if (a == "-neckbound") {
      o.neck_bound = parseNumber(a, v);
    } else if (a == "-gapfloor") {
      o.gap_floor = parseNumber(a, v);
    } else if (a == "-maxseg") {
      o.max_segments = static_cast<int>(parseNumber(a, v));
      if (o.max_segments < 1)
        fail("-maxseg needs a count >= 1");
    } else if (a == "-threads") {
      o.threads = static_cast<unsigned>(parseNumber(a, v));
    } else if (a == "-k") {
      o.k = static_cast<int>(parseNumber(a, v));
    } else if (a == "-crossing") {
      o.crossing = parseNumber(a, v);
    } else if (a == "-area") {
      o.area = parseNumber(a, v);
    } else if (a == "-height") {
      o.height = parseNumber(a, v);
    } else if (a == "-beta") {
      o.beta = parseNumber(a, v);
    } else if (a == "-alpha1") {
      o.alpha1 = parseNumber(a, v);
    } else if (a == "-alpha2") {
      o.alpha2 = parseNumber(a, v);
    } else {
      fail("unknown option " + a);
    }
  }
  if (positional.size() != 2)
    fail("expected <psb_dir> <out_dir> (see -h)");
  o.psb_dir = positional[0];
  o.out_dir = positional[1];
  if (o.methods.empty() || o.modes.empty())
    fail("no method or no mode to run");
  return o;
}

/** \brief Apply the options to a segmenter; fails on a value the segmenter rejects. */
void configure(Segmenter& seg, const Options& o) {
  seg.setNumberOfThreads(o.threads);
  if (o.k >= 0)
    seg.setNumberOfNeighbours(o.k);
  if (o.crossing >= 0)
    seg.setCrossingFraction(static_cast<float>(o.crossing));
  if (o.area >= 0)
    seg.setAreaFraction(static_cast<float>(o.area));
  if (o.height >= 0)
    seg.setHeightFraction(static_cast<float>(o.height));
  if (o.beta >= 0)
    seg.setBeta(o.beta);
  if (o.alpha1 >= 0)
    seg.setAlpha1(o.alpha1);
  if (o.alpha2 >= 0)
    seg.setAlpha2(o.alpha2);
  if (o.adjacent >= 0)
    seg.setConnectAllAdjacent(o.adjacent == 1);
  if (o.adjacent_share >= 0)
    seg.setAdjacentShare(o.adjacent_share);
  if (o.adjacent_share >= 0 && seg.getAdjacentShare() != o.adjacent_share)
    fail("-share needs a value in [0, 1]");
  if (o.gap >= 0)
    seg.setLargestGapStopping(o.gap == 1);
  if (o.max_segments >= 1)
    seg.setMaxSegments(o.max_segments);
  if (o.gap_floor >= 0)
    seg.setGapFloor(o.gap_floor);
  if (o.gap_floor >= 0 && seg.getGapFloor() != o.gap_floor)
    fail("-gapfloor needs a value > 0");
  if (o.neck >= 0)
    seg.setNeckExponent(o.neck);
  if (o.neck_bound >= 0)
    seg.setNeckBound(o.neck_bound);
  if ((o.neck >= 0 && seg.getNeckExponent() != o.neck) ||
      (o.neck_bound >= 0 && seg.getNeckBound() != o.neck_bound))
    fail("-neck needs a value >= 0, -neckbound a value > 0");
  if (o.bridge_gap >= 0)
    seg.setBridgeGap(o.bridge_gap);
  if (o.concavity >= 0)
    seg.setConcavityWeight(o.concavity);
  if (o.flat >= 0)
    seg.setFlatElongation(o.flat);
  if (o.band >= 0)
    seg.setBoundaryBand(o.band);
  if (o.band >= 0 && seg.getBoundaryBand() != o.band)
    fail("-band needs a value in [0, 0.5]");
  if (o.band_crease >= 0)
    seg.setBoundaryCreaseWeight(o.band_crease);
  if (o.crease >= 0)
    seg.setCreaseSplit(o.crease);
  if (o.crease_cut >= 0)
    seg.setCreaseCut(o.crease_cut);
  if (o.crease_cut >= 0 && seg.getCreaseCut() != o.crease_cut)
    fail("-creasecut needs a value in [0, 1]");
  if (o.paper) {
    seg.setBridgeGap(0.0);
    seg.setConcavityWeight(0.0);
    seg.setFlatElongation(0.0);
    seg.setBoundaryBand(0.0);
    seg.setCreaseSplit(0.0);
    seg.setCreaseCut(0.0);
    seg.setNormalizeWidth(false);
    seg.setConnectAdjacentTrees(false);
    seg.setConnectAllAdjacent(false);
    seg.setLargestGapStopping(false);
    seg.setNeckExponent(0.0);
    seg.setMinSegmentFraction(0.0);
  }
  if (o.paper || o.exact)
    seg.setCentralityMode(pcl_ncut_seg::CentralityMode::Exact);
  if ((o.k >= 0 && seg.getNumberOfNeighbours() != o.k) ||
      (o.beta >= 0 && seg.getBeta() != o.beta) || (o.alpha1 >= 0 && seg.getAlpha1() != o.alpha1) ||
      (o.alpha2 >= 0 && seg.getAlpha2() != o.alpha2) ||
      (o.crossing >= 0 && seg.getCrossingFraction() != static_cast<float>(o.crossing)) ||
      (o.area >= 0 && seg.getAreaFraction() != static_cast<float>(o.area)) ||
      (o.height >= 0 && seg.getHeightFraction() != static_cast<float>(o.height)))
    fail("a segmenter setting is out of range (see pcl_ncut_seg -h)");
}

/** \brief One method's result on one model in one mode. */
struct Row {
  std::string method, mode, category;
  int id = 0;
  std::size_t faces = 0;
  double segments = 0, seconds = 0;
  SegmentationScores scores;
  std::size_t humans = 0;
};

/** \brief Mean of the scores against every human segmentation. */
SegmentationScores againstHumans(const std::vector<int>& labels,
                                 const std::vector<std::vector<int>>& humans,
                                 const std::vector<double>& area) {
  SegmentationScores sum;
  for (const auto& h : humans)
    sum += pcl_ncut_seg::compareSegmentations(labels, h, area);
  return sum / static_cast<double>(humans.size());
}

std::size_t countSegments(const std::vector<int>& labels) {
  std::set<int> s;
  for (int l : labels)
    s.insert(l < 0 ? -1 : l);
  return s.size();
}

double seconds(std::chrono::steady_clock::time_point since) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - since).count();
}

std::vector<int> segmentsToLabels(const std::vector<pcl::PointIndices>& segments, std::size_t n) {
  std::vector<int> labels(n, -1);
  for (std::size_t s = 0; s < segments.size(); ++s)
    for (const auto i : segments[s].indices)
      labels[static_cast<std::size_t>(i)] = static_cast<int>(s);
  return labels;
}

/** \brief Write a file in one step: to a temporary name, then renamed over the target. */
void writeAtomically(const fs::path& path, const std::string& contents) {
  const fs::path tmp = path.string() + ".tmp";
  {
    std::ofstream out(tmp, std::ios::binary);
    out << contents;
    if (!out.flush()) {
      std::error_code ec;
      fs::remove(tmp, ec);
      fail("cannot write " + tmp.string());
    }
  }
  std::error_code ec;
  fs::rename(tmp, path, ec);
  if (ec) {
    fs::remove(tmp, ec);
    fail("cannot write " + path.string());
  }
}

std::string fmt(double v, int digits = 3) {
  std::ostringstream s;
  s << std::fixed << std::setprecision(digits) << v;
  return s.str();
}

const char* kMetricNames[] = {"1 - RI", "Hamming", "Rm", "Rf", "GCE", "LCE"};
double metric(const SegmentationScores& s, int m) {
  const double v[] = {s.rand_index_error, s.hamming, s.hamming_rm, s.hamming_rf, s.gce, s.lce};
  return v[m];
}

struct Mean {
  SegmentationScores scores;
  double segments = 0, seconds = 0;
  std::size_t models = 0;
  void add(const Row& r) {
    scores += r.scores;
    segments += r.segments;
    seconds += r.seconds;
    ++models;
  }
  Mean result() const {
    Mean m = *this;
    const double d = std::max<std::size_t>(models, 1);
    m.scores = scores / d;
    m.segments = segments / d;
    m.seconds = seconds / d;
    return m;
  }
};

} // namespace

int main(int argc, char** argv) {
  const Options opt = parseOptions(argc, argv);
  // PCL's segmenters report progress at the info level; keep the output to our summary lines.
  pcl::console::setVerbosityLevel(pcl::console::L_WARN);
  {
    // Check the segmenter settings once, up front: one line of ours, not the setters' errors.
    pcl::console::setVerbosityLevel(pcl::console::L_ALWAYS);
    Segmenter check;
    configure(check, opt);
    pcl::console::setVerbosityLevel(pcl::console::L_WARN);
  }
  const fs::path psb(opt.psb_dir), out_dir(opt.out_dir);
  if (!fs::is_directory(psb / "off") || !fs::is_directory(psb / "seg"))
    fail(opt.psb_dir + " has no off/ and seg/ directories");
  if (!fs::is_directory(out_dir))
    fail("output directory " + opt.out_dir + " does not exist");

  std::vector<int> ids = opt.ids;
  if (ids.empty()) {
    for (const auto& e : fs::directory_iterator(psb / "off")) {
      const std::string stem = e.path().stem().string();
      if (e.path().extension() == ".off" && !stem.empty() &&
          stem.find_first_not_of("0123456789") == std::string::npos)
        ids.push_back(std::stoi(stem));
    }
    std::sort(ids.begin(), ids.end());
  }
  if (ids.empty())
    fail("no models in " + (psb / "off").string());
  auto has = [&](const std::string& m) {
    return std::find(opt.methods.begin(), opt.methods.end(), m) != opt.methods.end();
  };
  auto hasMode = [&](const std::string& m) {
    return std::find(opt.modes.begin(), opt.modes.end(), m) != opt.modes.end();
  };
  std::vector<int> given_count;
  {
    std::ifstream in(psb / "nSeg-ByModel.txt");
    int v = 0;
    while (in >> v)
      given_count.push_back(v);
  }
  // Auto-mode settings of 'ours': every threshold with every minimum segment fraction.
  std::vector<std::pair<double, double>> settings;
  std::vector<std::string> ours_names;
  {
    std::vector<double> thresholds = opt.thresholds, fractions = opt.fractions;
    if (thresholds.empty())
      thresholds.push_back(Segmenter().getThreshold());
    if (fractions.empty())
      fractions.push_back(Segmenter().getMinSegmentFraction());
    for (double t : thresholds)
      for (double f : fractions) {
        settings.emplace_back(t, f);
        std::string name = "ours";
        if (thresholds.size() > 1)
          name += " t=" + fmt(t, 4);
        if (fractions.size() > 1)
          name += " f=" + fmt(f, 3);
        ours_names.push_back(name);
      }
  }

  std::vector<Row> rows;
  for (const int id : ids) {
    const std::string name = std::to_string(id);
    pcl_ncut_seg::TriangleMesh mesh;
    std::string error;
    if (!pcl_ncut_seg::readOff((psb / "off" / (name + ".off")).string(), mesh, &error))
      fail(error);
    const std::vector<float> xyz = pcl_ncut_seg::faceCentroids(mesh);
    const std::vector<double> area = pcl_ncut_seg::faceAreas(mesh);
    const std::size_t n = xyz.size() / 3;

    std::vector<fs::path> files;
    if (fs::is_directory(psb / "seg" / name))
      for (const auto& e : fs::directory_iterator(psb / "seg" / name))
        if (e.path().extension() == ".seg")
          files.push_back(e.path());
    std::sort(files.begin(), files.end());
    if (files.empty())
      fail("no human segmentations of model " + name);
    std::vector<std::vector<int>> humans;
    for (const auto& f : files) {
      humans.emplace_back();
      if (!pcl_ncut_seg::readSeg(f.string(), humans.back()) || humans.back().size() != n)
        fail(f.string() + ": unreadable or not one label per face");
    }
    const int given = id <= static_cast<int>(given_count.size()) ? given_count[id - 1] : 0;
    if (hasMode("given") && has("ours") && given <= 0)
      fail("no segment count for model " + name + " in nSeg-ByModel.txt");

    Row base;
    base.id = id;
    base.category = pcl_ncut_seg::psbCategory(id);
    base.faces = n;
    base.humans = humans.size();
    // Methods that do not take a count give the same result in both modes.
    auto addBoth = [&](Row r) {
      for (const auto& mode : opt.modes) {
        r.mode = mode;
        rows.push_back(r);
      }
    };
    auto score = [&](const std::string& method, const std::vector<int>& labels, double secs) {
      Row r = base;
      r.method = method;
      r.segments = static_cast<double>(countSegments(labels));
      r.seconds = secs;
      r.scores = againstHumans(labels, humans, area);
      return r;
    };

    if (has("ours")) {
      pcl::PointCloud<pcl::PointXYZ>::Ptr cloud(new pcl::PointCloud<pcl::PointXYZ>);
      cloud->resize(n);
      for (std::size_t i = 0; i < n; ++i)
        (*cloud)[i] = pcl::PointXYZ(xyz[3 * i], xyz[3 * i + 1], xyz[3 * i + 2]);
      Segmenter seg;
      configure(seg, opt);
      seg.setInputCloud(cloud);
      std::vector<pcl::PointIndices> segments;
      double analysis_seconds = -1;
      for (std::size_t t = 0; t < settings.size() && (hasMode("auto") || t == 0); ++t) {
        seg.setThreshold(settings[t].first);
        seg.setMinSegmentFraction(settings[t].second);
        if (seg.getMinSegmentFraction() != settings[t].second)
          fail("-fractions: a fraction is outside [0, 0.5]");
        const auto start = std::chrono::steady_clock::now();
        seg.extract(segments);
        const double secs = seconds(start);
        if (analysis_seconds < 0) {
          const auto& times = seg.getPhaseTimes();
          analysis_seconds = std::max(0.0, secs - times.hierarchy - times.points);
        }
        if (!hasMode("auto"))
          break;
        // The first extract() runs both stages; later thresholds reuse the analysis.
        Row r = score(ours_names[t], segmentsToLabels(segments, n),
                      t == 0 ? secs : analysis_seconds + secs);
        r.mode = "auto";
        rows.push_back(r);
      }
      if (hasMode("given")) {
        seg.setNumberOfSegments(given);
        const auto start = std::chrono::steady_clock::now();
        seg.extract(segments);
        Row r = score("ours", segmentsToLabels(segments, n), analysis_seconds + seconds(start));
        r.mode = "given";
        rows.push_back(r);
      }
    }
    for (const char* peer : {"lccp", "cpc"}) {
      if (!has(peer))
        continue;
      std::vector<int> labels;
      const auto start = std::chrono::steady_clock::now();
      // CPC reports every failed RANSAC draw as an error; they are part of how it works.
      pcl::console::setVerbosityLevel(pcl::console::L_ALWAYS);
      const bool ok = pcl_ncut_seg::segmentWithPclPeer(xyz, std::string(peer) == "cpc",
                                                       pcl_ncut_seg::PeerParams(), labels, &error);
      pcl::console::setVerbosityLevel(pcl::console::L_WARN);
      if (!ok)
        fail(std::string(peer) + " on model " + name + ": " + error);
      addBoth(score(peer, labels, seconds(start)));
    }
    if (has("one"))
      addBoth(score("one", std::vector<int>(n, 0), 0));
    if (has("octants")) {
      const auto start = std::chrono::steady_clock::now();
      const std::vector<int> labels = pcl_ncut_seg::segmentOctants(xyz);
      addBoth(score("octants", labels, seconds(start)));
    }
    if (has("human") && humans.size() >= 2) {
      // Each human segmentation against the others: the benchmark's human baseline.
      Row r = base;
      r.method = "human";
      SegmentationScores sum;
      double segs = 0;
      for (std::size_t i = 0; i < humans.size(); ++i) {
        std::vector<std::vector<int>> others;
        for (std::size_t j = 0; j < humans.size(); ++j)
          if (j != i)
            others.push_back(humans[j]);
        sum += againstHumans(humans[i], others, area);
        segs += static_cast<double>(countSegments(humans[i]));
      }
      r.scores = sum / static_cast<double>(humans.size());
      r.segments = segs / static_cast<double>(humans.size());
      addBoth(r);
    }
    if (!opt.quiet) {
      std::cout << "model " << id << " (" << base.category << ", " << n << " faces, "
                << humans.size() << " human segmentations):";
      for (const Row& r : rows)
        if (r.id == id)
          std::cout << " " << r.method << "/" << r.mode << " " << fmt(r.scores.rand_index_error)
                    << "/" << fmt(r.scores.hamming) << " (" << r.segments << " seg, "
                    << fmt(r.seconds, 2) << " s);";
      std::cout << std::endl;
    }
  }

  // Method order in the tables: ours first, then peers in the order given.
  std::vector<std::string> methods;
  for (const Row& r : rows)
    if (std::find(methods.begin(), methods.end(), r.method) == methods.end())
      methods.push_back(r.method);
  std::vector<std::string> categories;
  for (const int id : ids) {
    const std::string c = pcl_ncut_seg::psbCategory(id);
    if (std::find(categories.begin(), categories.end(), c) == categories.end())
      categories.push_back(c);
  }

  std::ostringstream models_csv;
  models_csv << "method,mode,id,category,faces,segments,seconds,one_minus_rand_index,hamming,"
                "hamming_rm,hamming_rf,gce,lce,human_segmentations\n";
  for (const Row& r : rows)
    models_csv << '"' << r.method << "\"," << r.mode << ',' << r.id << ',' << r.category << ','
               << r.faces << ',' << r.segments << ',' << fmt(r.seconds, 4) << ','
               << fmt(r.scores.rand_index_error, 6) << ',' << fmt(r.scores.hamming, 6) << ','
               << fmt(r.scores.hamming_rm, 6) << ',' << fmt(r.scores.hamming_rf, 6) << ','
               << fmt(r.scores.gce, 6) << ',' << fmt(r.scores.lce, 6) << ',' << r.humans << '\n';

  // Means per (mode, method, category); "Overall" = over every model.
  std::map<std::tuple<std::string, std::string, std::string>, Mean> means;
  for (const Row& r : rows) {
    means[{r.mode, r.method, r.category}].add(r);
    means[{r.mode, r.method, "Overall"}].add(r);
  }
  std::vector<std::string> with_overall = categories;
  with_overall.push_back("Overall");
  std::ostringstream cat_csv;
  cat_csv << "method,mode,category,models,segments,seconds,one_minus_rand_index,hamming,"
             "hamming_rm,hamming_rf,gce,lce\n";
  for (const auto& mode : opt.modes)
    for (const auto& method : methods)
      for (const auto& c : with_overall) {
        const auto it = means.find({mode, method, c});
        if (it == means.end())
          continue;
        const Mean m = it->second.result();
        cat_csv << '"' << method << "\"," << mode << ',' << c << ',' << m.models << ','
                << fmt(m.segments, 2) << ',' << fmt(m.seconds, 4);
        for (int k = 0; k < 6; ++k)
          cat_csv << ',' << fmt(metric(m.scores, k), 6);
        cat_csv << '\n';
      }

  std::ostringstream md;
  md << "<!-- written by pcl_ncut_seg_eval -->\n";
  for (const auto& mode : opt.modes) {
    md << "\n### " << (mode == "auto" ? "Automatic mode" : "Given number of segments")
       << ": overall (" << ids.size() << " models)\n\n";
    md << "| method | 1 - RI | Hamming | Rm | Rf | GCE | LCE | segments | s / model |\n";
    md << "|---|---|---|---|---|---|---|---|---|\n";
    for (const auto& method : methods) {
      const auto it = means.find({mode, method, "Overall"});
      if (it == means.end())
        continue;
      const Mean m = it->second.result();
      md << "| " << method;
      for (int k = 0; k < 6; ++k)
        md << " | " << fmt(metric(m.scores, k));
      md << " | " << fmt(m.segments, 1) << " | " << fmt(m.seconds, 2) << " |\n";
    }
    for (int k = 0; k < 6; ++k) {
      md << "\n#### " << (mode == "auto" ? "Automatic" : "Given count") << ": " << kMetricNames[k]
         << " per category\n\n| category |";
      for (const auto& method : methods)
        md << ' ' << method << " |";
      md << "\n|---|";
      for (std::size_t i = 0; i < methods.size(); ++i)
        md << "---|";
      md << '\n';
      for (const auto& c : with_overall) {
        md << "| " << (c == "Overall" ? "**Overall**" : c) << " |";
        for (const auto& method : methods) {
          const auto it = means.find({mode, method, c});
          md << ' ' << (it == means.end() ? "" : fmt(metric(it->second.result().scores, k)))
             << " |";
        }
        md << '\n';
      }
    }
  }
  writeAtomically(out_dir / "models.csv", models_csv.str());
  writeAtomically(out_dir / "categories.csv", cat_csv.str());
  writeAtomically(out_dir / "tables.md", md.str());
  if (!opt.quiet) {
    for (const auto& mode : opt.modes)
      for (const auto& method : methods) {
        const auto it = means.find({mode, method, "Overall"});
        if (it == means.end())
          continue;
        const Mean m = it->second.result();
        std::cout << mode << " " << method << ": 1-RI " << fmt(m.scores.rand_index_error)
                  << " Hamming " << fmt(m.scores.hamming) << " GCE " << fmt(m.scores.gce) << " LCE "
                  << fmt(m.scores.lce) << " segments " << fmt(m.segments, 1) << " s/model "
                  << fmt(m.seconds, 2) << std::endl;
      }
    std::cout << "Wrote " << (out_dir / "models.csv").string() << ", categories.csv, tables.md"
              << std::endl;
  }
  return 0;
}
