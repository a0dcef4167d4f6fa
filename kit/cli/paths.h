/*
 * pcl_ncut_seg tools: file names and where the bundled model is.
 */
#pragma once

#include <string>

namespace pcl_ncut_seg {
namespace tool {

std::string extension(const std::string& path);   ///< lower case, with the dot ("" for none)
std::string baseName(const std::string& path);    ///< without the directory
std::string stem(const std::string& path);        ///< file name without directory and extension
std::string directoryOf(const std::string& path); ///< "." for a bare name, "/" at the root

/** \brief A regular file this process may read. */
bool isReadableFile(const std::string& path);

/** \brief Where the bundled model armadillo.pcd is, or "" with one error line. */
std::string findBundledModel();

} // namespace tool
} // namespace pcl_ncut_seg
