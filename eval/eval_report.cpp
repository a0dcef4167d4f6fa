#include "eval_report.h"
#include "eval_oracle.h"

#include <algorithm>
#include <iomanip>
#include <map>
#include <set>
#include <sstream>
#include <tuple>

namespace pcl_ncut_seg {
namespace eval {

std::string fixed(double v, int digits) {
  std::ostringstream s;
  s << std::fixed << std::setprecision(digits) << v;
  return s.str();
}

const char* const kMetricNames[6] = {"1 - RI", "Hamming", "Rm", "Rf", "GCE", "LCE"};

double metricValue(const SegmentationScores& s, int k) {
  const double v[] = {s.rand_index_error, s.hamming, s.hamming_rm, s.hamming_rf, s.gce, s.lce};
  return v[k];
}

bool isViewMode(const std::string& mode) {
  return mode == "view" || mode == "crop" || mode == "voxel" || mode == "laser";
}

namespace {

/// The metrics, then (view mode only) the segments and seconds per view.
const char* kTableMetricNames[] = {
    "1 - RI", "Hamming", "Rm", "Rf", "GCE", "LCE", "segments per view", "seconds per view"};

double metric(const SegmentationScores& s, int m) {
  return metricValue(s, m);
}

/** The mean of rows. */
struct Mean {
  SegmentationScores scores;
  double segments = 0, seconds = 0;
  std::size_t models = 0, rows = 0;
  std::set<int> ids;
  void add(const Row& r) {
    scores += r.scores;
    segments += r.segments;
    seconds += r.seconds;
    ++rows;
    ids.insert(r.id);
    models = ids.size();
  }
  /** The mean over the rows: over the models, each model's draws weighing alike. */
  Mean result() const {
    Mean m = *this;
    const double d = static_cast<double>(std::max<std::size_t>(rows, 1));
    m.scores = scores / d;
    m.segments = segments / d;
    m.seconds = seconds / d;
    return m;
  }
};

/** Means per (mode, method, category); "Overall" = over every model. */
using Means = std::map<std::tuple<std::string, std::string, std::string>, Mean>;

Means means(const Report& report) {
  Means out;
  for (const Row& r : report.rows) {
    out[{r.mode, r.method, r.category}].add(r);
    out[{r.mode, r.method, "Overall"}].add(r);
  }
  return out;
}

/** The methods in the order of their first row (ours first, then peers as given). */
std::vector<std::string> methods(const Report& report) {
  std::vector<std::string> out;
  for (const Row& r : report.rows)
    if (std::find(out.begin(), out.end(), r.method) == out.end())
      out.push_back(r.method);
  return out;
}

/** The categories of the models in order of their first model, then "Overall". */
std::vector<std::string> categoriesAndOverall(const Report& report) {
  std::vector<std::string> out;
  for (const int id : report.ids) {
    const std::string c = psbCategory(id);
    if (std::find(out.begin(), out.end(), c) == out.end())
      out.push_back(c);
  }
  out.push_back("Overall");
  return out;
}

/** A mode's heading, long (the overall table) or short (a metric's table). */
std::string modeTitle(const std::string& mode, bool long_form) {
  if (mode == "auto")
    return long_form ? "Automatic mode" : "Automatic";
  if (mode == "view")
    return long_form ? "Depth-camera views (organized frames), on the faces each view sees"
                     : "Views";
  if (mode == "crop")
    return long_form ? "Views cropped to their valid points (unorganized), on the faces seen"
                     : "Crops";
  if (mode == "voxel")
    return long_form ? "Cropped views on a voxel grid (1% of the crop's diagonal)" : "Voxel crops";
  if (mode == "laser")
    return long_form ? "Laser-like views (even samples of the seen faces, isotropic noise)"
                     : "Laser views";
  return long_form ? "Given number of segments" : "Given count";
}

/** One mode's overall table. */
void overallTable(const Report& report, const Means& all, const std::string& mode,
                  std::ostringstream& md) {
  const bool view = isViewMode(mode);
  md << "\n### " << modeTitle(mode, true) << ": overall (" << report.ids.size() << " models)\n\n";
  md << "| method | 1 - RI | Hamming | Rm | Rf | GCE | LCE | segments"
     << (view ? " / view | s / view" : " | s / model") << " |\n";
  md << "|---|---|---|---|---|---|---|---|---|\n";
  for (const auto& method : methods(report)) {
    const auto it = all.find({mode, method, "Overall"});
    if (it == all.end())
      continue;
    const Mean m = it->second.result();
    md << "| " << method;
    for (int k = 0; k < 6; ++k)
      md << " | " << fixed(metric(m.scores, k));
    md << " | " << fixed(m.segments, 1) << " | " << fixed(m.seconds, 2) << " |\n";
  }
}

/** Column k of a mean: a metric (0-5), the segments (6) or the seconds (7), as text. */
std::string column(const Mean& m, int k) {
  if (k < 6)
    return fixed(metric(m.scores, k));
  return k == 6 ? fixed(m.segments, 1) : fixed(m.seconds, 2);
}

/** One mode's table of a metric per category. */
void categoryTable(const Report& report, const Means& all, const std::string& mode, int k,
                   std::ostringstream& md) {
  const std::vector<std::string> method_list = methods(report);
  md << "\n#### " << modeTitle(mode, false) << ": " << kTableMetricNames[k]
     << " per category\n\n| category |";
  for (const auto& method : method_list)
    md << ' ' << method << " |";
  md << "\n|---|";
  for (std::size_t i = 0; i < method_list.size(); ++i)
    md << "---|";
  md << '\n';
  for (const auto& c : categoriesAndOverall(report)) {
    md << "| " << (c == "Overall" ? "**Overall**" : c) << " |";
    for (const auto& method : method_list) {
      const auto it = all.find({mode, method, c});
      md << ' ' << (it == all.end() ? "" : column(it->second.result(), k)) << " |";
    }
    md << '\n';
  }
}

/** Whether an oracle's rows are in the report: then every file and summary says it read the
 * people's answers. */
bool hasOracle(const Report& report) {
  for (const Row& r : report.rows)
    if (isOracleMethod(r.method))
      return true;
  return false;
}

} // namespace

std::string modelsCsv(const Report& report) {
  std::ostringstream csv;
  csv << "method,mode,id,category,faces,segments,seconds,one_minus_rand_index,hamming,"
         "hamming_rm,hamming_rf,gce,lce,human_segmentations,draw\n";
  for (const Row& r : report.rows)
    csv << '"' << r.method << "\"," << r.mode << ',' << r.id << ',' << r.category << ',' << r.faces
        << ',' << r.segments << ',' << fixed(r.seconds, 4) << ','
        << fixed(r.scores.rand_index_error, 6) << ',' << fixed(r.scores.hamming, 6) << ','
        << fixed(r.scores.hamming_rm, 6) << ',' << fixed(r.scores.hamming_rf, 6) << ','
        << fixed(r.scores.gce, 6) << ',' << fixed(r.scores.lce, 6) << ',' << r.humans << ','
        << r.draw << '\n';
  return csv.str();
}

std::string categoriesCsv(const Report& report) {
  const Means all = means(report);
  std::ostringstream csv;
  csv << "method,mode,category,models,segments,seconds,one_minus_rand_index,hamming,"
         "hamming_rm,hamming_rf,gce,lce\n";
  for (const auto& mode : report.modes)
    for (const auto& method : methods(report))
      for (const auto& c : categoriesAndOverall(report)) {
        const auto it = all.find({mode, method, c});
        if (it == all.end())
          continue;
        const Mean m = it->second.result();
        csv << '"' << method << "\"," << mode << ',' << c << ',' << m.models << ','
            << fixed(m.segments, 2) << ',' << fixed(m.seconds, 4);
        for (int k = 0; k < 6; ++k)
          csv << ',' << fixed(metric(m.scores, k), 6);
        csv << '\n';
      }
  return csv.str();
}

std::string tablesMarkdown(const Report& report) {
  const Means all = means(report);
  std::ostringstream md;
  md << "<!-- written by pcl_ncut_seg_eval -->\n";
  if (hasOracle(report))
    md << "\n**Diagnostic.** " << kOracleNote << "\n";
  for (const auto& mode : report.modes) {
    overallTable(report, all, mode, md);
    for (int k = 0; k < (isViewMode(mode) ? 8 : 6); ++k)
      categoryTable(report, all, mode, k, md);
  }
  return md.str();
}

std::string summary(const Report& report) {
  const Means all = means(report);
  std::ostringstream out;
  if (hasOracle(report))
    out << kOracleNote << "\n";
  for (const auto& mode : report.modes)
    for (const auto& method : methods(report)) {
      const auto it = all.find({mode, method, "Overall"});
      if (it == all.end())
        continue;
      const Mean m = it->second.result();
      out << mode << " " << method << ": 1-RI " << fixed(m.scores.rand_index_error) << " Hamming "
          << fixed(m.scores.hamming) << " GCE " << fixed(m.scores.gce) << " LCE "
          << fixed(m.scores.lce) << " segments " << fixed(m.segments, 1)
          << (isViewMode(mode) ? " s/view " : " s/model ") << fixed(m.seconds, 2) << "\n";
    }
  return out.str();
}

std::string modelResults(const Report& report, int id) {
  std::ostringstream out;
  for (const Row& r : report.rows)
    if (r.id == id)
      out << " " << r.method << "/" << r.mode
          << (report.draws > 1 ? " draw " + std::to_string(r.draw + 1) : std::string()) << " "
          << fixed(r.scores.rand_index_error) << "/" << fixed(r.scores.hamming) << " ("
          << r.segments << " seg, " << fixed(r.seconds, 2) << " s);";
  return out.str();
}

} // namespace eval
} // namespace pcl_ncut_seg
