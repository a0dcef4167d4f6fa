/*
 * pcl_ncut_seg: the resolution of the analysis. An extension: the paper analyses every point.
 *
 * Every stage of Secs. 4-5 measures on the kNN graph, whose edges shrink as a cloud gets denser:
 * the centrality gains shallow maxima, the local refinement's merges cascade differently, and a
 * concave bend per edge grows against the mean bend (a mesh's facets become creases). So the
 * parts of one surface drift with its density (docs/sampling.md). A cloud denser than a
 * resolution at which parts are resolved is therefore analysed on a subset of that many of its
 * points, and every other point takes the segment of its nearest analysed point.
 */
#pragma once

#include <pcl_ncut_seg/core/pipeline.h>

#include <cstddef>
#include <cstdint>

namespace pcl_ncut_seg {

/** \brief A hash of a position (its float bits, -0 as +0): the same for a point wherever it
 * stands in the input, so that a subset chosen by it does not depend on the points' order. */
std::uint64_t positionHash(const float* xyz);

/** \brief Keep at most max_points of the prepared points, the ones with the smallest
 * positionHash() of their input position (ties by position): an unbiased random subset, the
 * same for any order of the input. Every dropped point, and every copy of one, becomes a copy
 * of its nearest kept point (Euclidean), so that it shares its
 * segment. The kept vertices are then exactly what preparePoints() makes of them alone (Morton
 * order, dense ranks in PointSet::order, centred on their centroid). Inputs
 * and outputs are those of preparePoints(); call it before the kNN graph is built (knn and rim
 * empty).
 * \param[in,out] prepared    from preparePoints()
 * \param[in]     max_points  the resolution of the analysis, >= 1
 * \param[in]     num_threads threads for the nearest-point queries (>= 1); the result does not
 *                            depend on it
 * \return the number of points dropped (0: the cloud has at most max_points) */
std::size_t subsamplePoints(PreparedPoints& prepared, std::size_t max_points, int num_threads);

} // namespace pcl_ncut_seg
