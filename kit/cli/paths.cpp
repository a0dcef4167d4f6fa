#include "cli/paths.h"

#include "files/values.h"

#include "cli/console.h"

#include <algorithm>
#include <cctype>
#include <vector>

#include <sys/stat.h>
#include <unistd.h>

namespace pcl_ncut_seg {
namespace tool {

std::string extension(const std::string& path) {
  return files::extensionOf(path);
}

std::string baseName(const std::string& path) {
  const std::size_t slash = path.find_last_of('/');
  return slash == std::string::npos ? path : path.substr(slash + 1);
}

std::string stem(const std::string& path) {
  const std::string base = baseName(path);
  const std::size_t dot = base.find_last_of('.');
  return dot == std::string::npos || dot == 0 ? base : base.substr(0, dot);
}

std::string directoryOf(const std::string& path) {
  const std::size_t slash = path.find_last_of('/');
  if (slash == std::string::npos)
    return ".";
  return slash == 0 ? "/" : path.substr(0, slash);
}

bool isReadableFile(const std::string& path) {
  struct stat st;
  return ::stat(path.c_str(), &st) == 0 && S_ISREG(st.st_mode) && ::access(path.c_str(), R_OK) == 0;
}

std::string findBundledModel() {
  const char* kModel = "armadillo.pcd";
  // The source tree, the configured install directory, and <prefix>/share/pcl_ncut_seg beside
  // this executable's bin/ (for an install to another prefix).
  std::vector<std::string> dirs = {PCL_NCUT_SEG_SOURCE_DATA_DIR, PCL_NCUT_SEG_INSTALL_DATA_DIR};
  std::vector<char> buffer(4096);
  const ssize_t n = ::readlink("/proc/self/exe", buffer.data(), buffer.size() - 1);
  if (n > 0) {
    const std::string exe(buffer.data(), static_cast<std::size_t>(n));
    dirs.push_back(directoryOf(directoryOf(exe)) + "/share/pcl_ncut_seg");
  }
  std::string looked;
  for (const std::string& dir : dirs) {
    if (isReadableFile(dir + "/" + kModel))
      return dir + "/" + kModel;
    looked += (looked.empty() ? "" : ", ") + dir;
  }
  fail(std::string("the bundled model ") + kModel + " is in none of " + looked +
       "; give an input file");
  return "";
}

} // namespace tool
} // namespace pcl_ncut_seg
