#include "cli/algorithm_flags.h"

#include "cli/console.h"

#include <pcl_ncut_seg/parameter_table.h>

#include <algorithm>
#include <string>
#include <utility>

namespace pcl_ncut_seg {
namespace tool {

namespace {

const char* const kPaperHelp =
    "the paper to the letter: every extension off, exact centrality, the threshold rule (each "
    "parameter's value under -paper is in its help); flags given with it apply on top";

/** A number written plainly: a decimal integer within int for an integer, a finite decimal
 * number for a real (no leading space, hexadecimal or trailing text), or the row's off word.
 * The table itself reads numbers more loosely ("0x10", " 10", "10.0" as integers). */
bool wellFormed(const ParameterInfo& row, const std::string& text) {
  long integer = 0;
  double real = 0;
  if (!row.off_word.empty() && text == row.off_word)
    return true;
  if (row.kind == ValueKind::Integer)
    return toInt(text, integer);
  if (row.kind == ValueKind::Real)
    return toDouble(text, real) && text.find_first_of("xX") == std::string::npos;
  return true;
}

/** The flag of a parameter: its text checked by the table, its default from base. */
Flag parameterFlag(const ParameterInfo& row, const Parameters& base, const Parameters& paper) {
  const bool is_switch = row.kind == ValueKind::Switch;
  const std::string help = is_switch ? row.help : row.help + "; " + row.range;
  std::string def = row.get(base);
  if (row.get(paper) != def)
    def += "; with -paper: " + row.get(paper);
  if (row.name == "segments" && base.stopping.rule != StoppingRule::Count)
    def = "off: the -stopping rule"; // the count is read only by the count rule
  Flag f = is_switch ? switchFlag("-" + row.name, help, def)
                     : textFlag("-" + row.name, row.value_name, help, def);
  f.group = std::string("algorithm, ") + stageName(row.stage);
  f.check = [&row](const std::string& text, std::string* why) {
    Parameters scratch;
    if (wellFormed(row, text) && row.set(scratch, text, nullptr))
      return true;
    *why = "expected " + row.range;
    return false;
  };
  return f;
}

/** Two flags that ask for different things, or for nothing more together; the second is a
 * parameter the first sets as well. */
const std::pair<const char*, const char*> kConflicts[] = {
    {"-segments", "-threshold"}, // the count rule does not read the threshold
    {"-segments", "-stopping"},  // -segments sets -stopping count
};

/** One error line for flags that cannot be given together. */
bool noConflicts(const Flags& flags) {
  for (const auto& [a, b] : kConflicts)
    if (flags.has(a) && flags.has(b)) {
      fail(std::string("give either ") + a + " or " + b + ", not both");
      return false;
    }
  for (const Shorthand& s : parameterShorthands())
    if (flags.has("-" + s.name) && flags.has("-" + s.parameter)) {
      fail("give either -" + s.name + " or -" + s.parameter + ", not both");
      return false;
    }
  return true;
}

/** Parameters::paper(), but run as base says: how the work runs is the tool's, not the
 * paper's. */
Parameters paperPreset(const Parameters& base) {
  Parameters paper = Parameters::paper();
  paper.execution = base.execution;
  return paper;
}

} // namespace

std::vector<Flag> algorithmFlags(const Parameters& base) {
  const Parameters paper = paperPreset(base);
  std::vector<Flag> table = {switchFlag("-paper", kPaperHelp)};
  table.back().group = "algorithm";
  for (const Shorthand& s : parameterShorthands()) {
    table.push_back(switchFlag("-" + s.name, s.help));
    table.back().group = "algorithm";
  }
  for (const ParameterInfo& row : parameterTable())
    table.push_back(parameterFlag(row, base, paper));
  return table;
}

bool parametersFromFlags(const Flags& flags, const Parameters& base, Parameters& params) {
  if (!noConflicts(flags))
    return false;
  params = flags.has("-paper") ? paperPreset(base) : base;
  for (const std::string& name : flags.order) {
    const std::string key = name.substr(1);
    const auto shorthand = std::find_if(parameterShorthands().begin(), parameterShorthands().end(),
                                        [&key](const Shorthand& s) { return s.name == key; });
    std::string why;
    const bool ok = shorthand != parameterShorthands().end()
                        ? setParameter(params, shorthand->parameter, shorthand->value, &why)
                        : !findParameter(key) || setParameter(params, key, flags.text(name), &why);
    if (!ok) { // the table checked each value: only a bug gets here
      fail(why);
      return false;
    }
  }
  return true;
}

bool applyAlgorithmFlags(const Flags& flags, Segmenter& seg, const Parameters& base) {
  Parameters params;
  if (!parametersFromFlags(flags, base, params))
    return false;
  std::string why;
  if (!validate(params, &why)) {
    fail(why);
    return false;
  }
  SilencePcl silence; // validated: setParameters has nothing to say
  return seg.setParameters(params);
}

} // namespace tool
} // namespace pcl_ncut_seg
