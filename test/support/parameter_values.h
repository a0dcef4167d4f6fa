/*
 * Values of each row of the parameter table (pcl_ncut_seg::parameterTable()) at the edges of its
 * range and just past them, as the text the table and the tools read. Tests that loop over the
 * table with them cover a row added to it without a change of their own.
 */
#pragma once

#include <pcl_ncut_seg/parameter_table.h>

#include <cfloat>
#include <cmath>
#include <string>
#include <vector>

namespace pcl_ncut_seg {
namespace test {

/// The largest value every integer field holds and the tools read (they read an int).
constexpr double kLargestInteger = 2147483647.0;
/// Past every integer field, int or unsigned (2^32).
constexpr double kPastEveryInteger = 4294967296.0;

/** \brief The nearest value beyond x (upwards when up, else downwards) that is a normal float:
 * a value of float fields as well as of double ones, which the tools read without underflow. */
inline double floatBeyond(double x, bool up) {
  if (x == 0)
    return up ? FLT_MIN : -FLT_MIN;
  float f = static_cast<float>(x);
  while (up ? f <= x : f >= x)
    f = std::nextafter(f, up ? FLT_MAX : -FLT_MAX);
  return f;
}

/** \brief The ends of a numeric row's range, the nearest value inside where an end is open. An
 * unbounded end is the largest value every field of the kind holds. */
inline std::vector<double> rangeEnds(const ParameterInfo& row) {
  const bool integer = row.kind == ValueKind::Integer;
  const double lo = !row.lo_open ? row.lo : integer ? row.lo + 1 : floatBeyond(row.lo, true);
  double hi = integer ? kLargestInteger : FLT_MAX;
  if (std::isfinite(row.hi))
    hi = !row.hi_open ? row.hi : integer ? row.hi - 1 : floatBeyond(row.hi, false);
  return {lo, hi};
}

/** \brief Every value of the row worth trying at the edges: both ends of a number's range, its
 * off word, each choice, on and off. */
inline std::vector<std::string> valuesAtTheEdges(const ParameterInfo& row) {
  std::vector<std::string> values;
  switch (row.kind) {
  case ValueKind::Integer:
  case ValueKind::Real:
    for (double v : rangeEnds(row))
      values.push_back(formatNumber(v));
    break;
  case ValueKind::Choice:
    values = row.choices;
    break;
  case ValueKind::Switch:
  case ValueKind::Boolean:
    values = {"on", "off"};
    break;
  }
  if (!row.off_word.empty())
    values.push_back(row.off_word);
  return values;
}

/** \brief Values just past the row's range: the nearest number outside each end (an unbounded
 * end: a number no field of the kind holds), a word that is no choice, a number for on/off. */
inline std::vector<std::string> valuesJustPast(const ParameterInfo& row) {
  const bool integer = row.kind == ValueKind::Integer;
  switch (row.kind) {
  case ValueKind::Integer:
  case ValueKind::Real: {
    const double lo = row.lo_open ? row.lo : integer ? row.lo - 1 : floatBeyond(row.lo, false);
    if (!std::isfinite(row.hi))
      return {formatNumber(lo), integer ? formatNumber(kPastEveryInteger) : "1e400"};
    const double hi = row.hi_open ? row.hi : integer ? row.hi + 1 : floatBeyond(row.hi, true);
    return {formatNumber(lo), formatNumber(hi)};
  }
  case ValueKind::Choice:
    return {"no_such_" + row.name};
  case ValueKind::Switch:
  case ValueKind::Boolean:
    return {"1"};
  }
  return {};
}

} // namespace test
} // namespace pcl_ncut_seg
