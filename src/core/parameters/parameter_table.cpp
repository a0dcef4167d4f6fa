#include <pcl_ncut_seg/parameter_table.h>

#include "core/parameters/parameter_row_builders.h"

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <sstream>

namespace pcl_ncut_seg {

namespace {
/// The shortest "%g" text that reads back as value (by read), in plain notation where %g
/// allows it at a larger precision (90, not 9e+01).
template <typename Read> std::string shortest(double value, int max_precision, Read read) {
  char buf[64];
  const double magnitude = std::fabs(value);
  const bool plain = magnitude >= 1e-4 && magnitude < 1e15;
  for (int precision = 1; precision <= max_precision; ++precision) {
    std::snprintf(buf, sizeof buf, "%.*g", precision, value);
    if (read(buf) && !(plain && std::strchr(buf, 'e')))
      break;
  }
  return buf;
}
} // namespace

std::string formatNumber(double value) {
  return shortest(value, 17, [value](const char* s) { return std::strtod(s, nullptr) == value; });
}

std::string formatNumber(float value) {
  return shortest(value, 9, [value](const char* s) { return std::strtof(s, nullptr) == value; });
}

const std::vector<ParameterInfo>& parameterTable() {
  static const std::vector<ParameterInfo> table = makeParameterTable();
  return table;
}

const ParameterInfo* findParameter(const std::string& name) {
  for (const ParameterInfo& r : parameterTable())
    if (r.name == name)
      return &r;
  return nullptr;
}

const std::vector<Shorthand>& parameterShorthands() {
  static const std::vector<Shorthand> shorthands = {
      {"exact", "centrality", "exact", "the same as -centrality exact"},
  };
  return shorthands;
}

bool setParameter(Parameters& params, const std::string& name, const std::string& text,
                  std::string* why) {
  const ParameterInfo* r = findParameter(name);
  if (!r) {
    if (why)
      *why = "unknown parameter '" + name + "'";
    return false;
  }
  return r->set(params, text, why);
}

std::string parameterValue(const Parameters& params, const std::string& name) {
  const ParameterInfo* r = findParameter(name);
  return r ? r->get(params) : std::string();
}

std::string parameterMarkdown() {
  const Parameters defaults, paper = Parameters::paper();
  std::ostringstream md;
  md << "| Stage | Flag / keyword | Field | Default | Paper | Values | Meaning |\n"
     << "|---|---|---|---|---|---|---|\n";
  for (const ParameterInfo& r : parameterTable()) {
    std::string help = r.help;
    for (std::size_t at = help.find('|'); at != std::string::npos; at = help.find('|', at + 2))
      help.replace(at, 1, "\\|");
    md << "| " << stageName(r.stage) << " | `-" << r.name << "` | `" << r.field << "` | "
       << r.get(defaults) << " | " << r.get(paper) << " | " << r.range << " | " << help
       << (r.paper ? "" : " *(extension)*") << " |\n";
  }
  return md.str();
}

} // namespace pcl_ncut_seg
