/*
 * pcl_ncut_seg: how a row of the parameter table (parameter_table.h) is built: its range, its
 * words, and how it reads and prints its field. Private to parameter_table.cpp and
 * parameter_rows.cpp.
 */
#pragma once

#include <pcl_ncut_seg/parameter_table.h>

#include <cmath>
#include <cstdlib>
#include <limits>
#include <optional>
#include <string>
#include <type_traits>
#include <vector>

namespace pcl_ncut_seg {
namespace table_rows {

constexpr double kInf = std::numeric_limits<double>::infinity();

/** \brief A numeric range and the words for it. */
struct Range {
  double lo = -kInf, hi = kInf;
  bool lo_open = false, hi_open = false;

  bool contains(double v) const {
    return std::isfinite(v) && (lo_open ? v > lo : v >= lo) && (hi_open ? v < hi : v <= hi);
  }
  std::string words(bool integer) const {
    const std::string what = integer ? "an integer" : "a number";
    const std::string l = formatNumber(lo), h = formatNumber(hi);
    if (hi == kInf)
      return what + (lo_open ? " > " : " >= ") + l;
    return what + " in " + (lo_open ? "(" : "[") + l + ", " + h + (hi_open ? ")" : "]");
  }
};
inline Range atLeast(double lo) {
  return {lo, kInf, false, false};
}
inline Range above(double lo) {
  return {lo, kInf, true, false};
}
inline Range closed(double lo, double hi) {
  return {lo, hi, false, false};
}
inline Range leftOpen(double lo, double hi) {
  return {lo, hi, true, false};
}

inline bool fail(std::string* why, const ParameterInfo& row, const std::string& got) {
  if (why)
    *why = row.name + " must be " + row.range + ", got " + got;
  return false;
}

/** \brief The text as a number, or nullopt: decimal only (no hexadecimal, no spaces, no
 * "inf" or "nan"), an integer as optional sign and digits. */
inline std::optional<double> parseNumber(const std::string& text, bool integer) {
  const char* allowed = integer ? "+-0123456789" : "+-0123456789.eE";
  if (text.empty() || text.find_first_not_of(allowed) != std::string::npos)
    return std::nullopt;
  char* end = nullptr;
  const double v = std::strtod(text.c_str(), &end); // (an underflow reads as a denormal)
  if (*end != '\0' || !std::isfinite(v))
    return std::nullopt;
  return v;
}

template <typename T> std::string numberText(T v) {
  if constexpr (std::is_integral_v<T>)
    return std::to_string(v);
  else
    return formatNumber(v);
}

/** \brief Common fields of a row. */
inline ParameterInfo row(const char* name, const char* field, Stage stage, ValueKind kind,
                         const char* value_name, const char* help, bool paper) {
  ParameterInfo r;
  r.name = name;
  r.field = field;
  r.stage = stage;
  r.kind = kind;
  r.value_name = value_name;
  r.help = help;
  r.paper = paper;
  return r;
}

/** \brief A number field of type T (int, unsigned, float, double), or an optional one when
 * off_word is given (nullopt reads and prints as off_word). Access returns the field. */
template <typename T, typename Field, typename Access>
ParameterInfo number(ParameterInfo r, Range range, Access access, const char* off_word = "") {
  constexpr bool kInteger = std::is_integral_v<T>;
  constexpr bool kOptional = !std::is_same_v<Field, T>;
  r.kind = kInteger ? ValueKind::Integer : ValueKind::Real;
  r.lo = range.lo;
  r.hi = range.hi;
  r.lo_open = range.lo_open;
  r.hi_open = range.hi_open;
  r.off_word = off_word;
  r.range = range.words(kInteger) + (kOptional ? std::string(" or ") + off_word : "");
  // In range, whole for an integer, and representable by the field's type (no undefined cast).
  const auto valid = [range](double v) {
    return range.contains(v) && (!kInteger || v == std::floor(v)) &&
           v >= static_cast<double>(std::numeric_limits<T>::lowest()) &&
           v <= static_cast<double>(std::numeric_limits<T>::max());
  };
  r.get = [access, off = r.off_word](const Parameters& p) -> std::string {
    const Field& f = access(const_cast<Parameters&>(p));
    if constexpr (kOptional)
      return f ? numberText<T>(*f) : off;
    else
      return numberText<T>(f);
  };
  r.set = [r, access, valid](Parameters& p, const std::string& text, std::string* why) {
    if constexpr (kOptional)
      if (text == r.off_word) {
        access(p) = std::nullopt;
        return true;
      }
    const std::optional<double> v = parseNumber(text, kInteger);
    if (!v || !valid(*v) || !valid(static_cast<double>(static_cast<T>(*v))))
      return fail(why, r, "'" + text + "'");
    access(p) = static_cast<T>(*v);
    return true;
  };
  r.check = [r, access, valid](const Parameters& p, std::string* why) {
    const Field& f = access(const_cast<Parameters&>(p));
    if constexpr (kOptional) {
      if (!f)
        return true;
      return valid(static_cast<double>(*f)) || fail(why, r, numberText<T>(*f));
    } else {
      return valid(static_cast<double>(f)) || fail(why, r, numberText<T>(f));
    }
  };
  return r;
}

/** \brief A bool field: "on" or "off" (a switch: on when given). */
template <typename Access> ParameterInfo boolean(ParameterInfo r, Access access) {
  r.range = "on or off";
  r.get = [access](const Parameters& p) {
    return access(const_cast<Parameters&>(p)) ? std::string("on") : std::string("off");
  };
  r.set = [r, access](Parameters& p, const std::string& text, std::string* why) {
    if (text == "on" || (text.empty() && r.kind == ValueKind::Switch))
      access(p) = true;
    else if (text == "off")
      access(p) = false;
    else
      return fail(why, r, "'" + text + "'");
    return true;
  };
  r.check = [](const Parameters&, std::string*) { return true; };
  return r;
}

/** \brief An enum field: one of the words, in the enum's order. */
template <typename E, typename Access>
ParameterInfo choice(ParameterInfo r, std::vector<std::string> words, Access access) {
  r.kind = ValueKind::Choice;
  r.choices = words;
  std::string range = "one of ";
  for (std::size_t i = 0; i < words.size(); ++i)
    range += (i ? ", " : "") + words[i];
  r.range = range;
  r.get = [words, access](const Parameters& p) {
    const auto i = static_cast<std::size_t>(access(const_cast<Parameters&>(p)));
    return i < words.size() ? words[i] : std::to_string(i);
  };
  r.set = [r, words, access](Parameters& p, const std::string& text, std::string* why) {
    for (std::size_t i = 0; i < words.size(); ++i)
      if (text == words[i]) {
        access(p) = static_cast<E>(i);
        return true;
      }
    return fail(why, r, "'" + text + "'");
  };
  r.check = [r, words, access](const Parameters& p, std::string* why) {
    const auto i = static_cast<std::size_t>(access(const_cast<Parameters&>(p)));
    return i < words.size() || fail(why, r, std::to_string(i));
  };
  return r;
}

} // namespace table_rows

/** \brief Every row, in the order of the pipeline's stages (parameter_rows.cpp). */
std::vector<ParameterInfo> makeParameterTable();

} // namespace pcl_ncut_seg
