#include "cli/flags.h"

#include "cli/console.h"

#include <pcl/console/print.h>

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <limits>
#include <sstream>

namespace pcl_ncut_seg {
namespace tool {

namespace {
std::string numberText(double v) {
  std::ostringstream s;
  s << v;
  return s.str();
}
} // namespace

namespace {
Flag makeFlag(const std::string& name, FlagKind kind, const std::string& value,
              const std::string& help, const std::string& def) {
  Flag f;
  f.name = name;
  f.kind = kind;
  f.value = value;
  f.help = help;
  f.def = def;
  return f;
}
} // namespace

Flag switchFlag(const std::string& name, const std::string& help, const std::string& def) {
  return makeFlag(name, FlagKind::Switch, "", help, def);
}

Flag intFlag(const std::string& name, const std::string& value, const std::string& help,
             const std::string& def, double lo, double hi) {
  Flag f = makeFlag(name, FlagKind::Integer, value, help, def);
  f.lo = lo;
  f.hi = hi;
  f.range = hi >= 1e300 ? "an integer >= " + numberText(lo)
                        : "an integer in [" + numberText(lo) + ", " + numberText(hi) + "]";
  return f;
}

Flag realFlag(const std::string& name, const std::string& value, const std::string& help,
              const std::string& def, double lo, double hi, bool open_lo) {
  Flag f = makeFlag(name, FlagKind::Real, value, help, def);
  f.lo = lo;
  f.hi = hi;
  f.open_lo = open_lo;
  f.range = hi >= 1e300 ? std::string("a number ") + (open_lo ? "> " : ">= ") + numberText(lo)
                        : "a number in [" + numberText(lo) + ", " + numberText(hi) + "]";
  return f;
}

Flag textFlag(const std::string& name, const std::string& value, const std::string& help,
              const std::string& def) {
  return makeFlag(name, FlagKind::Text, value, help, def);
}

Flag* findFlag(std::vector<Flag>& table, const std::string& name) {
  const auto it =
      std::find_if(table.begin(), table.end(), [&name](const Flag& f) { return f.name == name; });
  return it == table.end() ? nullptr : &*it;
}

void append(std::vector<Flag>& table, const std::vector<Flag>& more, const std::string& group) {
  for (const Flag& f : more) {
    table.push_back(f);
    if (!group.empty())
      table.back().group = group;
  }
}

bool toDouble(const std::string& s, double& value) {
  if (s.empty() || std::isspace(static_cast<unsigned char>(s[0])))
    return false;
  char* end = nullptr;
  errno = 0;
  const double v = std::strtod(s.c_str(), &end);
  if (errno != 0 || end == s.c_str() || *end != '\0' || !std::isfinite(v))
    return false;
  value = v;
  return true;
}

bool toInt(const std::string& s, long& value) {
  if (s.empty() || std::isspace(static_cast<unsigned char>(s[0])))
    return false;
  char* end = nullptr;
  errno = 0;
  const long v = std::strtol(s.c_str(), &end, 10);
  if (errno != 0 || end == s.c_str() || *end != '\0' || v < std::numeric_limits<int>::min() ||
      v > std::numeric_limits<int>::max())
    return false;
  value = v;
  return true;
}

std::vector<std::string> splitList(const std::string& text) {
  std::vector<std::string> out;
  std::stringstream in(text);
  std::string item;
  while (std::getline(in, item, ','))
    if (!item.empty())
      out.push_back(item);
  return out;
}

long Flags::integer(const std::string& name) const {
  long v = 0;
  toInt(given.at(name), v);
  return v;
}

double Flags::real(const std::string& name) const {
  double v = 0;
  toDouble(given.at(name), v);
  return v;
}

namespace {

/** The row for arg ("--help" is "-h", "--version" "-version"); nullptr for none. */
const Flag* lookUp(const std::vector<Flag>& table, const std::string& arg) {
  const std::string name = arg == "--help" ? "-h" : arg == "--version" ? "-version" : arg;
  for (const Flag& f : table)
    if (f.name == name)
      return &f;
  return nullptr;
}

/** The value's text right for the flag? Else one error line. */
bool checkValue(const Flag& flag, const std::string& arg, const std::string& text) {
  const std::string bad = "bad value '" + text + "' for " + arg + ": ";
  if (flag.kind == FlagKind::Text && text.empty()) {
    fail("option " + arg + " needs a non-empty value");
    return false;
  }
  if (flag.kind == FlagKind::Integer || flag.kind == FlagKind::Real) {
    double value = 0;
    long integer = 0;
    const bool ok = flag.kind == FlagKind::Integer
                        ? (toInt(text, integer) && (value = static_cast<double>(integer), true))
                        : toDouble(text, value);
    if (!ok || value < flag.lo || value > flag.hi || (flag.open_lo && value == flag.lo)) {
      fail(bad + "expected " + flag.range);
      return false;
    }
  }
  std::string why;
  if (flag.check && !flag.check(text, &why)) {
    fail(bad + why);
    return false;
  }
  return true;
}

} // namespace

bool parseFlags(int argc, char** argv, const std::vector<Flag>& table, Flags& flags) {
  for (int i = 1; i < argc; ++i) {
    const std::string arg = argv[i];
    const Flag* flag = lookUp(table, arg);
    if (!flag) {
      if (arg.size() > 1 && arg[0] == '-') {
        fail("unknown option " + arg + " (see -h)");
        return false;
      }
      flags.files.push_back(arg);
      continue;
    }
    if (flags.has(flag->name)) {
      fail("option " + arg + " given more than once" +
           (arg == flag->name ? "" : " (it is " + flag->name + ")"));
      return false;
    }
    std::string text;
    if (flag->kind != FlagKind::Switch) {
      if (i + 1 >= argc) {
        fail("option " + arg + " needs a value (see -h)");
        return false;
      }
      text = argv[++i]; // a value may look like a flag ("-1")
    }
    if (!checkValue(*flag, arg, text))
      return false;
    flags.given[flag->name] = text;
    flags.order.push_back(flag->name);
  }
  return true;
}

void printFlags(const std::vector<Flag>& table) {
  std::string group;
  for (const Flag& f : table) {
    if (!f.group.empty() && f.group != group)
      pcl::console::print_info("  %s:\n", f.group.c_str());
    group = f.group;
    std::string head = "    " + f.name + (f.value.empty() ? "" : " " + f.value);
    if (head.size() < 22)
      head.resize(22, ' ');
    std::string line = head + " = " + f.help;
    if (!f.def.empty())
      line += " (default: " + f.def + ")";
    pcl::console::print_info("%s\n", line.c_str());
  }
}

std::vector<Flag> commonFlags() {
  std::vector<Flag> table = {switchFlag("-quiet", "print errors and warnings only"),
                             switchFlag("-h", "this help (also --help)", ""),
                             switchFlag("-version", "the version and build (also --version)", "")};
  for (Flag& f : table)
    f.group = "general";
  return table;
}

} // namespace tool
} // namespace pcl_ncut_seg
