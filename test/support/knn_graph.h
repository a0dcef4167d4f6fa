/*
 * pcl_ncut_seg tests: symmetric kNN graphs of point sets built with PCL's kd-tree, independent of
 * the library's own neighbour search, for the phase-by-phase tests.
 */
#pragma once

#include "core/graph/csr_graph.h"

#include <pcl/point_cloud.h>
#include <pcl/point_types.h>

#include <cstddef>
#include <vector>

namespace pcl_ncut_seg {
namespace test {

/** \brief The coordinates of a cloud, 3 floats per point, in its order. */
std::vector<float> xyzOf(const pcl::PointCloud<pcl::PointXYZ>& cloud);

/** \brief The symmetric k-nearest-neighbour graph (buildSymmetricKnnGraph) of points given as 3
 * floats each, their neighbours found by pcl::search::KdTree (sorted, self excluded); vertices in
 * the points' order. */
CsrGraph kdTreeKnnGraph(const std::vector<float>& xyz, std::size_t k);

} // namespace test
} // namespace pcl_ncut_seg
