/*
 * pcl_ncut_seg: a cache hint for the graph searches that jump around memory.
 */
#pragma once

namespace pcl_ncut_seg {

/** \brief Ask for the cache line at p ahead of its use. A hint: it never faults, even past an
 * array's end, and does nothing where the compiler has no prefetch builtin. */
inline void prefetch(const void* p) {
#if defined(__GNUC__) || defined(__clang__)
  __builtin_prefetch(p);
#else
  (void)p;
#endif
}

} // namespace pcl_ncut_seg
