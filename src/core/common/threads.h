/*
 * pcl_ncut_seg: how many threads a phase uses for a request.
 */
#pragma once

namespace pcl_ncut_seg {

/// \brief The threads to use for a request of \a requested: never more than the processors,
/// which would only cost memory (one work array per thread). 1 without OpenMP.
///
/// 0 asks for the cores that are free now: the processors less the threads of other processes
/// that are running (Linux's /proc/loadavg less this process's own running threads, read at
/// most every 10 ms), at least 1. On a machine another job keeps busy, a phase then runs no
/// slower than on one thread: more threads than free cores make each parallel loop wait for a
/// thread that is not running. The labels do not depend on the count.
int usableThreads(unsigned requested);

/// \brief The threads of other processes running at this instant, from /proc/loadavg and
/// /proc/self/task; 0 where the system does not say (not Linux).
int otherRunningThreads();

} // namespace pcl_ncut_seg
