// Sec. 4.1: the k nearest neighbours, with FLANN's kd-tree as pcl::KdTreeFLANN uses it.
#include "core/graph/knn.h"

#include <flann/algorithms/dist.h>
#include <flann/algorithms/kdtree_single_index.h>
#include <flann/util/result_set.h>

#include <algorithm>
#include <vector>

namespace pcl_ncut_seg {

void kNearestNeighbours(const float* xyz, std::size_t n, std::size_t k, int num_threads,
                        std::uint32_t* knn) {
  if (n == 0 || k == 0)
    return;
  // The index and parameters of pcl::KdTreeFLANN: one kd-tree, leaves of at most 15 points,
  // eps 0 (exact), results unsorted.
  using Index = flann::KDTreeSingleIndex<flann::L2_Simple<float>>;
  Index index(flann::Matrix<float>(const_cast<float*>(xyz), n, 3),
              flann::KDTreeSingleIndexParams(15));
  index.buildIndex();
  const flann::SearchParams params(-1, 0.0f, false);
  // Each query asks for k + 1 (the point itself is among them); results go straight into knn.
#pragma omp parallel num_threads(num_threads)
  {
    flann::KNNSimpleResultSet<float> result(k + 1);
    std::vector<std::size_t> ids(k + 1);
    std::vector<float> dists(k + 1);
#pragma omp for schedule(dynamic, 1024)
    for (std::ptrdiff_t qi = 0; qi < static_cast<std::ptrdiff_t>(n); ++qi) {
      const auto i = static_cast<std::size_t>(qi);
      result.clear();
      index.findNeighbors(result, xyz + 3 * i, params);
      const std::size_t found = std::min(result.size(), k + 1);
      result.copy(ids.data(), dists.data(), found, false);
      std::size_t j = 0;
      for (std::size_t r = 0; r < found && j < k; ++r)
        if (ids[r] != i)
          knn[i * k + j++] = static_cast<std::uint32_t>(ids[r]);
    }
  }
}

} // namespace pcl_ncut_seg
