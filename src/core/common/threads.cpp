#include "core/common/threads.h"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cstdint>
#include <dirent.h>
#include <fstream>
#include <limits>
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

// otherRunningThreads() costs about 50 us (a file per thread of this process): a reading stays
// good for a scheduler's few ticks, shared by every thread of the process.
int recentOtherRunningThreads() {
  using Clock = std::chrono::steady_clock;
  constexpr std::int64_t kFreshFor =
      std::chrono::nanoseconds(std::chrono::milliseconds(10)).count();
  static std::atomic<std::int64_t> read_at{std::numeric_limits<std::int64_t>::min()};
  static std::atomic<int> others{0};
  const std::int64_t now =
      std::chrono::duration_cast<std::chrono::nanoseconds>(Clock::now().time_since_epoch()).count();
  const std::int64_t last = read_at.load(std::memory_order_acquire);
  if (last != std::numeric_limits<std::int64_t>::min() && now - last < kFreshFor)
    return others.load(std::memory_order_relaxed);
  const int fresh = otherRunningThreads();
  others.store(fresh, std::memory_order_relaxed);
  read_at.store(now, std::memory_order_release);
  return fresh;
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
  const int free_cores = processors - recentOtherRunningThreads();
  return std::clamp(free_cores, 1, std::max(omp_get_max_threads(), 1));
#else
  (void)requested;
  return 1;
#endif
}

} // namespace pcl_ncut_seg
