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

} // namespace test
} // namespace pcl_ncut_seg
