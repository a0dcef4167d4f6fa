#include "core/common/threads.h"

#include <algorithm>

#ifdef _OPENMP
#include <omp.h>
#endif

namespace pcl_ncut_seg {

int usableThreads(unsigned requested) {
#ifdef _OPENMP
  const int usable = std::max(omp_get_num_procs(), omp_get_max_threads());
  return requested > 0 ? static_cast<int>(std::min<unsigned>(requested, usable))
                       : omp_get_max_threads();
#else
  (void)requested;
  return 1;
#endif
}

} // namespace pcl_ncut_seg
