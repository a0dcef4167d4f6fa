/*
 * pcl_ncut_seg: how many threads a phase uses for a request.
 */
#pragma once

namespace pcl_ncut_seg {

/// \brief The threads to use for a request of \a requested (0 = all cores): never more than
/// the processors, which would only cost memory (one work array per thread). 1 without OpenMP.
int usableThreads(unsigned requested);

} // namespace pcl_ncut_seg
