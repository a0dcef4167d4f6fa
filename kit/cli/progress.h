/*
 * pcl_ncut_seg tools: a progress bar on stderr, and the process's peak memory.
 */
#pragma once

#include "cli/flags.h"

#include <chrono>
#include <condition_variable>
#include <cstdint>
#include <functional>
#include <mutex>
#include <string>
#include <thread>

namespace pcl_ncut_seg {
namespace tool {

/** \brief A progress bar on stderr for phases that take longer than a delay (1 s, or the
 * PCL_NCUT_SEG_PROGRESS_DELAY environment variable in seconds). A background thread redraws
 * it every 100 ms; a report redraws it at once when the phase's first fraction arrives or the
 * last drawing is 100 ms old. The line is cleared when the phase ends. Does nothing when disabled.
 */
class ProgressBar {
public:
  explicit ProgressBar(bool enabled);
  ~ProgressBar();
  ProgressBar(const ProgressBar&) = delete;
  ProgressBar& operator=(const ProgressBar&) = delete;
  /** \brief 0 starts a phase, 1 ends it; values in between say how far it is. */
  void update(const char* phase, double fraction);
  /** \brief The callback for SupernodeNCutSegmentation::setProgressCallback. */
  std::function<void(const char*, double)> callback();

private:
  void run();
  void draw(bool final_clear);

  bool enabled_;
  double delay_ = 1.0;
  std::mutex mutex_;
  std::condition_variable wake_;
  std::thread thread_;
  bool stop_ = false;
  std::string phase_;
  double fraction_ = 0;
  bool known_ = false; ///< a fraction strictly inside (0, 1) was reported for this phase
  bool drawn_ = false;
  std::chrono::steady_clock::time_point start_;
  std::chrono::steady_clock::time_point last_draw_;
};

/** \brief True when stderr is a terminal and -quiet is not given. */
bool progressWanted(const Flags& flags);

/** \brief Peak resident memory of this process so far, in bytes (getrusage). */
std::uint64_t peakMemoryBytes();

} // namespace tool
} // namespace pcl_ncut_seg
