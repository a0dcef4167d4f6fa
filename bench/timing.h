/*
 * pcl_ncut_seg benchmarks: clocks and the machine's load (Linux).
 */
#pragma once

#include <time.h>

#include <chrono>
#include <fstream>
#include <string>

namespace pcl_ncut_seg_bench {

/// Wall time in seconds (steady clock).
inline double now() {
  return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count();
}

/// CPU time of the process (all threads) in seconds: less noisy than wall time on a loaded
/// machine.
inline double cpuNow() {
  timespec t{};
  clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &t);
  return static_cast<double>(t.tv_sec) + 1e-9 * static_cast<double>(t.tv_nsec);
}

/// The load averages over 1, 5 and 15 minutes, as /proc/loadavg gives them.
inline std::string loadAverage() {
  std::ifstream in("/proc/loadavg");
  std::string a, b, c;
  in >> a >> b >> c;
  return a + " " + b + " " + c;
}

} // namespace pcl_ncut_seg_bench
