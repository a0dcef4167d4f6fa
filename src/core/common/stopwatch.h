/*
 * pcl_ncut_seg: wall time of the phases, for PhaseTimes.
 */
#pragma once

#include <chrono>

namespace pcl_ncut_seg {

/** \brief Seconds since the last lap (or construction). */
class Stopwatch {
public:
  double lap() {
    const auto now = std::chrono::steady_clock::now();
    const double s = std::chrono::duration<double>(now - start_).count();
    start_ = now;
    return s;
  }
  /** \brief Seconds since the last lap, without starting a new one. */
  double elapsed() const {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
  }

private:
  std::chrono::steady_clock::time_point start_ = std::chrono::steady_clock::now();
};

} // namespace pcl_ncut_seg
