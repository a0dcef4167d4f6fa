/*
 * pcl_ncut_seg tools: the command-line layer every tool shares. A tool describes its flags in a
 * table, one row per flag (name, value, help, default, range); parseFlags reads
 * argv against it and printFlags prints its help, so that a flag is spelt, checked and
 * documented the same way in every tool.
 */
#pragma once

#include <functional>
#include <map>
#include <string>
#include <vector>

namespace pcl_ncut_seg {
namespace tool {

enum class FlagKind { Switch, Integer, Real, Text };

/** \brief A command-line flag: its name, what it takes, its range and its help line. */
struct Flag {
  std::string name;                 ///< "-k"
  FlagKind kind = FlagKind::Switch; ///< a switch, or the kind of its value
  std::string value;                ///< the value's name in the help ("K"), empty for a switch
  std::string help;                 ///< what it does, with its range
  std::string def;                  ///< its default, for the help ("" for none)
  double lo = 0, hi = 0;
  bool open_lo = false; ///< lo itself is out of range
  std::string range;    ///< the range in words, for the error ("an integer >= 2")
  /// A check of the value's text beyond the kind and range: false with the reason (appended
  /// to "bad value 'x' for -name: "). Empty: none.
  std::function<bool(const std::string& text, std::string* why)> check;
  std::string group; ///< a heading the help prints before the first flag of a group
};

/** \brief Switch / value flag builders, so that a table row stays one line. */
Flag switchFlag(const std::string& name, const std::string& help, const std::string& def = "off");
Flag intFlag(const std::string& name, const std::string& value, const std::string& help,
             const std::string& def, double lo, double hi = 1e300);
Flag realFlag(const std::string& name, const std::string& value, const std::string& help,
              const std::string& def, double lo, double hi = 1e300, bool open_lo = false);
Flag textFlag(const std::string& name, const std::string& value, const std::string& help,
              const std::string& def = "");

/** \brief The row of the table called name, or nullptr. */
Flag* findFlag(std::vector<Flag>& table, const std::string& name);

/** \brief The parsed command line: flags given (each at most once), in the order given, and
 * the file arguments. */
struct Flags {
  std::map<std::string, std::string> given; ///< flag -> its text ("" for a switch)
  std::vector<std::string> order;           ///< the flags given, in command-line order
  std::vector<std::string> files;

  bool has(const std::string& name) const { return given.count(name) > 0; }
  long integer(const std::string& name) const;
  double real(const std::string& name) const;
  const std::string& text(const std::string& name) const { return given.at(name); }
};

/** \brief Parse argv against the table; on a bad command line (unknown flag, missing or out of
 * range value, flag given twice) print one error line and return false. */
bool parseFlags(int argc, char** argv, const std::vector<Flag>& table, Flags& flags);

/** \brief The help lines of the flags in the table, with their defaults. */
void printFlags(const std::vector<Flag>& table);

/** \brief -quiet and -h (also --help). */
std::vector<Flag> commonFlags();

/** \brief Append the rows of more to table, under this group's heading if one is given. */
void append(std::vector<Flag>& table, const std::vector<Flag>& more, const std::string& group = "");

/** \brief Strict conversions: the whole text must be a finite number (an int for toInt). */
bool toDouble(const std::string& text, double& value);
bool toInt(const std::string& text, long& value);

/** \brief The comma-separated items of a list ("1,2,,3": "1", "2", "3"). */
std::vector<std::string> splitList(const std::string& text);

} // namespace tool
} // namespace pcl_ncut_seg
