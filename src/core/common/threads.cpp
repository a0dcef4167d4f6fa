#include "core/common/threads.h"

#include <algorithm>
#include <cstdio>
#include <dirent.h>
#include <fstream>
#include <string>

#ifdef _OPENMP
#include <omp.h>
#endif

namespace pcl_ncut_seg {
namespace {

// Running entities system-wide: the "R/T" field of /proc/loadavg counts threads in state R,
// the reader included. -1 where it cannot be read.
int runningSystemWide() {
  std::ifstream in("/proc/loadavg");
  double avg[3];
  int running = -1, total = 0;
  char slash = 0;
  if (!(in >> avg[0] >> avg[1] >> avg[2] >> running >> slash >> total) || slash != '/')
    return -1;
  return running;
}

// This process's threads in state R (its OpenMP workers may still spin after a loop).
int runningInThisProcess() {
  DIR* tasks = opendir("/proc/self/task");
  if (!tasks)
    return -1;
  int running = 0;
  while (const dirent* entry = readdir(tasks)) {
    if (entry->d_name[0] == '.')
      continue;
    std::ifstream stat(std::string("/proc/self/task/") + entry->d_name + "/stat");
    std::string line;
    if (!std::getline(stat, line))
      continue;
    // The state follows the command name, which is in parentheses and may hold spaces.
    const std::size_t close = line.rfind(')');
    if (close != std::string::npos && close + 2 < line.size() && line[close + 2] == 'R')
      ++running;
  }
  closedir(tasks);
  return running;
}

} // namespace

int otherRunningThreads() {
  const int all = runningSystemWide();
  const int own = runningInThisProcess();
  if (all < 0 || own < 0)
    return 0;
  return std::max(0, all - std::max(own, 1));
}

int usableThreads(unsigned requested) {
#ifdef _OPENMP
  const int processors = std::max(omp_get_num_procs(), 1);
  if (requested > 0)
    return static_cast<int>(
        std::min<unsigned>(requested, std::max(processors, omp_get_max_threads())));
  const int free_cores = processors - otherRunningThreads();
  return std::clamp(free_cores, 1, std::max(omp_get_max_threads(), 1));
#else
  (void)requested;
  return 1;
#endif
}

} // namespace pcl_ncut_seg
