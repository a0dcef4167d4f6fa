/*
 * pcl_ncut_seg benchmarks: a measurement in a fresh child process, and the growth of a time
 * with n.
 */
#pragma once

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <map>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

namespace pcl_ncut_seg_bench {

/// What a child printed: key=value pairs.
using Result = std::map<std::string, double>;

/// The key=value pairs of `line`, added to `result`.
inline void parseFields(const std::string& line, Result& result) {
  std::istringstream fields(line);
  std::string field;
  while (fields >> field) {
    const auto eq = field.find('=');
    if (eq != std::string::npos)
      result[field.substr(0, eq)] = std::strtod(field.c_str() + eq + 1, nullptr);
  }
}

/// Run `command` (a child that prints key=value pairs on its output) and parse what it printed;
/// false when it could not run or failed.
inline bool runChild(const std::string& command, Result& result) {
  result.clear();
  FILE* pipe = popen(command.c_str(), "r");
  if (!pipe)
    return false;
  char buffer[1024];
  std::string line;
  while (std::fgets(buffer, sizeof buffer, pipe))
    line += buffer;
  if (pclose(pipe) != 0)
    return false;
  parseFields(line, result);
  return true;
}

/// Least-squares slope of log(y) against log(n) over the points (n, y) with y >= 1 ms: the
/// exponent a of y ~ n^a; NaN with fewer than two such points. used: how many there were.
inline double fitExponent(const std::vector<std::pair<double, double>>& points,
                          int* used = nullptr) {
  double sx = 0, sy = 0, sxx = 0, sxy = 0;
  int k = 0;
  for (const auto& [n, y] : points) {
    if (y < 1e-3)
      continue;
    const double x = std::log(n), v = std::log(y);
    sx += x, sy += v, sxx += x * x, sxy += x * v, ++k;
  }
  if (used)
    *used = k;
  if (k < 2 || sxx * k - sx * sx <= 0)
    return NAN;
  return (k * sxy - sx * sy) / (k * sxx - sx * sx);
}

} // namespace pcl_ncut_seg_bench
