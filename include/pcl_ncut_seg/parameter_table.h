/*
 * pcl_ncut_seg: the one table of the parameters in parameters.h: for each, its name (the
 * flag of every tool is "-" + name, the Python keyword is the name), its stage, its range and
 * a line of help. Validation, the tools' flags and help, the README's parameter table and the
 * range tests read it, so that they cannot disagree.
 */
#pragma once

#include <pcl_ncut_seg/parameters.h>

#include <functional>
#include <string>
#include <vector>

namespace pcl_ncut_seg {

/** \brief What kind of value a parameter takes. */
enum class ValueKind {
  Integer, ///< a whole number in [lo, hi]
  Real,    ///< a number in [lo, hi] (lo or hi open where said)
  Switch,  ///< on when given (a tool flag without a value), "on" or "off" as text
  Boolean, ///< "on" or "off"
  Choice   ///< one of the words in choices
};

/** \brief One row of the table. */
struct ParameterInfo {
  std::string name;       ///< "k", "crease_split": the flag is "-k", the Python keyword k
  std::string field;      ///< its field in Parameters ("graph.k")
  Stage stage;            ///< the stage that reads it; analysis stages invalidate the analysis
  ValueKind kind;         ///< what it takes
  std::string value_name; ///< the value's name in the help ("K"); empty for a switch
  std::string help;       ///< what it does, one line
  std::string range;      ///< its values in words ("an integer >= 2", "a number in (0, 1] or off")
  double lo = 0, hi = 0;  ///< Integer, Real: the range
  bool lo_open = false, hi_open = false;
  std::string off_word;             ///< an optional field: the word for nullopt ("off", "auto")
  std::vector<std::string> choices; ///< Choice: the words, in the enum's order
  bool paper = false;               ///< a parameter of the paper itself (not an extension)

  /// The value as text, as parseValue() reads it back (shortest exact decimal for numbers).
  std::function<std::string(const Parameters&)> get;
  /// Set from text; false (params unchanged) with why = the reason when the text is no value
  /// of this parameter or out of its range.
  std::function<bool(Parameters&, const std::string& text, std::string* why)> set;
  /// The value in range? (false with why, for validate()).
  std::function<bool(const Parameters&, std::string* why)> check;
};

/** \brief Every parameter, grouped by stage in pipeline order. */
const std::vector<ParameterInfo>& parameterTable();

/** \brief The row with this name (without the leading '-'), or nullptr. */
const ParameterInfo* findParameter(const std::string& name);

/** \brief A shorthand switch of the tools: a flag that sets one parameter to one value
 * ("-exact" is "-centrality exact"). */
struct Shorthand {
  std::string name, parameter, value, help;
};
const std::vector<Shorthand>& parameterShorthands();

/** \brief Set the parameter called name from text; false (params unchanged) with
 * the reason, "k must be an integer >= 2, got 1", or "unknown parameter 'x'". */
bool setParameter(Parameters& params, const std::string& name, const std::string& text,
                  std::string* why = nullptr);

/** \brief The parameter's value as text ("" for an unknown name). */
std::string parameterValue(const Parameters& params, const std::string& name);

/** \brief The shortest decimal text that reads back as exactly this value. */
std::string formatNumber(double value);
std::string formatNumber(float value);

/** \brief The README's parameter table (Markdown), generated from the table; a test checks
 * that the README holds it. */
std::string parameterMarkdown();

} // namespace pcl_ncut_seg
