#include "eval_spread.h"

#include <algorithm>
#include <map>
#include <sstream>

namespace pcl_ncut_seg {
namespace eval {

namespace {

/** The rows' metrics and counts of one (method, mode, model), folded into min and max. */
struct Fold {
  Spread spread;
  std::array<double, 6> lo{}, hi{};
  void add(const Row& r) {
    for (int k = 0; k < 6; ++k) {
      const double v = metricValue(r.scores, k);
      lo[k] = spread.draws == 0 ? v : std::min(lo[k], v);
      hi[k] = spread.draws == 0 ? v : std::max(hi[k], v);
    }
    spread.segments_min =
        spread.draws == 0 ? r.segments : std::min(spread.segments_min, r.segments);
    spread.segments_max =
        spread.draws == 0 ? r.segments : std::max(spread.segments_max, r.segments);
    ++spread.draws;
  }
};

/** The mean of spreads: the ranges, the share whose count changes, the disagreement. */
struct SpreadMean {
  std::array<double, 6> range{};
  double changes = 0, between = 0, segments_span = 0;
  std::size_t models = 0;
  void add(const Spread& s) {
    for (int k = 0; k < 6; ++k)
      range[k] += s.range[k];
    changes += s.countChanges() ? 1 : 0;
    between += s.between;
    segments_span += s.segments_max - s.segments_min;
    ++models;
  }
  SpreadMean result() const {
    SpreadMean m = *this;
    const double d = static_cast<double>(std::max<std::size_t>(models, 1));
    for (double& v : m.range)
      v /= d;
    m.changes /= d;
    m.between /= d;
    m.segments_span /= d;
    return m;
  }
};

using Key = std::tuple<std::string, std::string, std::string>; // mode, method, category

std::map<Key, SpreadMean> spreadMeans(const std::vector<Spread>& all) {
  std::map<Key, SpreadMean> out;
  for (const Spread& s : all) {
    out[{s.mode, s.method, s.category}].add(s);
    out[{s.mode, s.method, "Overall"}].add(s);
  }
  return out;
}

/** Items in the order of their first appearance. */
template <typename F> std::vector<std::string> firstSeen(const std::vector<Spread>& all, F get) {
  std::vector<std::string> out;
  for (const Spread& s : all)
    if (std::find(out.begin(), out.end(), get(s)) == out.end())
      out.push_back(get(s));
  return out;
}

void overallSpreadTable(const std::map<Key, SpreadMean>& means,
                        const std::vector<std::string>& methods, const std::string& mode,
                        std::ostringstream& md) {
  md << "\n| method | range 1 - RI | range Hamming | range Rm | range Rf | range GCE | range LCE "
        "| count changes | segments max - min | 1 - RI between draws |\n"
        "|---|---|---|---|---|---|---|---|---|---|\n";
  for (const auto& method : methods) {
    const auto it = means.find({mode, method, "Overall"});
    if (it == means.end())
      continue;
    const SpreadMean m = it->second.result();
    md << "| " << method;
    for (int k = 0; k < 6; ++k)
      md << " | " << fixed(m.range[k]);
    md << " | " << fixed(100 * m.changes, 0) << "% | " << fixed(m.segments_span, 2) << " | "
       << fixed(m.between) << " |\n";
  }
}

void categorySpreadTable(const std::map<Key, SpreadMean>& means,
                         const std::vector<std::string>& methods,
                         const std::vector<std::string>& categories, const std::string& mode,
                         std::ostringstream& md) {
  md << "\n| category |";
  for (const auto& method : methods)
    md << ' ' << method << " range 1 - RI | " << method << " count changes |";
  md << "\n|---|";
  for (std::size_t i = 0; i < methods.size(); ++i)
    md << "---|---|";
  md << '\n';
  for (const auto& c : categories) {
    md << "| " << (c == "Overall" ? "**Overall**" : c) << " |";
    for (const auto& method : methods) {
      const auto it = means.find({mode, method, c});
      if (it == means.end()) {
        md << " | |";
        continue;
      }
      const SpreadMean m = it->second.result();
      md << ' ' << fixed(m.range[0]) << " | " << fixed(100 * m.changes, 0) << "% |";
    }
    md << '\n';
  }
}

} // namespace

std::vector<Spread> spreads(const Report& report) {
  std::vector<std::tuple<std::string, std::string, int>> order;
  std::map<std::tuple<std::string, std::string, int>, Fold> folds;
  for (const Row& r : report.rows) {
    const auto key = std::make_tuple(r.method, r.mode, r.id);
    auto [it, added] = folds.try_emplace(key);
    if (added) {
      order.push_back(key);
      it->second.spread.method = r.method;
      it->second.spread.mode = r.mode;
      it->second.spread.category = r.category;
      it->second.spread.id = r.id;
    }
    it->second.add(r);
  }
  std::vector<Spread> out;
  for (const auto& key : order) {
    Fold& f = folds[key];
    if (f.spread.draws < 2) // the human baseline: once per model
      continue;
    for (int k = 0; k < 6; ++k)
      f.spread.range[k] = f.hi[k] - f.lo[k];
    const auto between = report.between_draws.find(key);
    f.spread.between = between == report.between_draws.end() ? 0.0 : between->second;
    out.push_back(f.spread);
  }
  return out;
}

std::string spreadCsv(const Report& report) {
  std::ostringstream csv;
  csv << "method,mode,id,category,draws,segments_min,segments_max,range_one_minus_rand_index,"
         "range_hamming,range_hamming_rm,range_hamming_rf,range_gce,range_lce,"
         "between_draws_one_minus_rand_index\n";
  for (const Spread& s : spreads(report)) {
    csv << '"' << s.method << "\"," << s.mode << ',' << s.id << ',' << s.category << ',' << s.draws
        << ',' << s.segments_min << ',' << s.segments_max;
    for (int k = 0; k < 6; ++k)
      csv << ',' << fixed(s.range[k], 6);
    csv << ',' << fixed(s.between, 6) << '\n';
  }
  return csv.str();
}

std::string spreadMarkdown(const Report& report) {
  const std::vector<Spread> all = spreads(report);
  const auto means = spreadMeans(all);
  const auto methods = firstSeen(all, [](const Spread& s) { return s.method; });
  auto categories = firstSeen(all, [](const Spread& s) { return s.category; });
  categories.push_back("Overall");
  std::ostringstream md;
  for (const auto& mode : report.modes) {
    md << "\n### " << (mode == "auto" ? "Automatic mode" : "Given number of segments")
       << ": spread over " << report.draws << " draws (" << report.ids.size()
       << " models; means over models of each model's max - min)\n";
    overallSpreadTable(means, methods, mode, md);
    md << "\n#### " << (mode == "auto" ? "Automatic" : "Given count") << ": spread per category\n";
    categorySpreadTable(means, methods, categories, mode, md);
  }
  return md.str();
}

std::string spreadSummary(const Report& report) {
  const std::vector<Spread> all = spreads(report);
  const auto means = spreadMeans(all);
  const auto methods = firstSeen(all, [](const Spread& s) { return s.method; });
  std::ostringstream out;
  for (const auto& mode : report.modes)
    for (const auto& method : methods) {
      const auto it = means.find({mode, method, "Overall"});
      if (it == means.end())
        continue;
      const SpreadMean m = it->second.result();
      out << mode << ' ' << method << " over " << report.draws << " draws: range 1-RI "
          << fixed(m.range[0]) << " Hamming " << fixed(m.range[1]) << " count changes on "
          << fixed(100 * m.changes, 0) << "% of models, 1-RI between draws " << fixed(m.between)
          << "\n";
    }
  return out.str();
}

} // namespace eval
} // namespace pcl_ncut_seg
