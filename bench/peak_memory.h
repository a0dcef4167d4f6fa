/*
 * pcl_ncut_seg benchmarks: peak resident memory of this process (Linux).
 */
#pragma once

#include <malloc.h>

#include <cstdlib>
#include <cstring>
#include <fstream>
#include <string>

namespace pcl_ncut_seg_bench {

/// A field of /proc/self/status in bytes (VmRSS, VmHWM), or 0.
inline std::size_t procStatusBytes(const char* field) {
  std::ifstream in("/proc/self/status");
  std::string line;
  const std::size_t len = std::strlen(field);
  while (std::getline(in, line))
    if (line.compare(0, len, field) == 0 && line.size() > len && line[len] == ':')
      return std::strtoull(line.c_str() + len + 1, nullptr, 10) * 1024;
  return 0;
}

/// Start measuring peak memory from here: return freed heap to the system and reset the
/// kernel's high-water mark (Linux >= 4.0). Returns the resident size now.
inline std::size_t startPeakMemory() {
  malloc_trim(0);
  std::ofstream("/proc/self/clear_refs") << "5";
  return procStatusBytes("VmRSS");
}

} // namespace pcl_ncut_seg_bench
