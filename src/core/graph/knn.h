/*
 * pcl_ncut_seg: the k nearest neighbours of Sec. 4.1 with FLANN's kd-tree.
 */
#pragma once

#include <cstddef>
#include <cstdint>

namespace pcl_ncut_seg {

/** \brief The k nearest other points of each point, with the kd-tree that pcl::KdTreeFLANN
 * builds (FLANN's single kd-tree, at most 15 points per leaf, exact search), so the neighbours
 * are those pcl::search::KdTree finds. The queries run in parallel with no per-query
 * allocation; each point's list does not depend on the number of threads.
 * \param[in] xyz          n points, x y z each; no two at the same position
 * \param[in] n            number of points
 * \param[in] k            neighbours per point, < n
 * \param[in] num_threads  threads for the queries (>= 1)
 * \param[out] knn         n * k indices, row p holds p's neighbours (nearest first) */
void kNearestNeighbours(const float* xyz, std::size_t n, std::size_t k, int num_threads,
                        std::uint32_t* knn);

} // namespace pcl_ncut_seg
