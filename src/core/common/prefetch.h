/*
 * pcl_ncut_seg: a cache hint for the graph searches that jump around memory, and forced
 * inlining for their inner loops' steps.
 */
#pragma once

/// For a step of a search's inner loop put in a function of its own: GCC leaves such a step
/// out of line in a large loop, which costs BucketDijkstra a third of its speed.
#if defined(__GNUC__) || defined(__clang__)
#define PCL_NCUT_SEG_ALWAYS_INLINE __attribute__((always_inline)) inline
#else
#define PCL_NCUT_SEG_ALWAYS_INLINE inline
#endif

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
