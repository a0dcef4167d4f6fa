/*
 * Small helpers for tests that drive the tools: files read back, directory listings, output
 * lines, shell quoting.
 */
#pragma once

#include <filesystem>
#include <set>
#include <string>
#include <vector>

namespace pcl_ncut_seg {
namespace test {

/** \brief The whole file as bytes (empty if it cannot be read). */
std::string readText(const std::filesystem::path& path);

/** \brief s quoted for a POSIX shell (single quotes). */
std::string quote(const std::string& s);

/** \brief The names of the files in a directory. */
std::set<std::string> listDir(const std::filesystem::path& dir);

/** \brief The lines of a text, without terminal colour codes. */
std::vector<std::string> lines(const std::string& text);

/** \brief How a command ended and what it printed. */
struct CommandRun {
  int status = -1; ///< exit status, or -1 if the command did not exit normally
  std::string out, err;
};

/** \brief Runs a shell command line with its stdout and stderr sent to the files `out` and
 * `err`, reads them back and removes them. */
CommandRun runCommand(const std::string& command, const std::filesystem::path& out,
                      const std::filesystem::path& err);

/** \brief A new empty directory in the temporary directory, named `prefix` and six unique
 * characters (mkdtemp); an empty path if it cannot be made. */
std::filesystem::path makeTempDir(const std::string& prefix);

} // namespace test
} // namespace pcl_ncut_seg
