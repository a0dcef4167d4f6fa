/*
 * pcl_ncut_seg: the resolution of the analysis. An extension: the paper analyses every point.
 *
 * Every stage of Secs. 4-5 measures on the kNN graph, whose edges shrink as a cloud gets denser:
 * the centrality gains shallow maxima, the local refinement's merges cascade differently, and a
 * concave bend per edge grows against the mean bend (a mesh's facets become creases). So the
 * parts of one surface drift with its density (docs/sampling.md). A cloud denser than a
 * resolution at which parts are resolved is therefore analysed on an even subset of at most that
 * many of its points, and every other point takes the segment of its nearest analysed point. Even,
 * not random: on the benchmark's meshes sampled densely, an even subset scores much nearer to
 * people than a random one (docs/sampling.md).
 */
#pragma once

#include "core/model/points.h"

#include <cstddef>
#include <cstdint>
#include <vector>

namespace pcl_ncut_seg {

/** \brief An even subset of at most max_points of the m points: the point nearest the centre of
 * each occupied cube of a grid from the points' lower bounding corner, whose edge is chosen so
 * that between 97% and 100% of max_points cubes are occupied (fewer only when the points are so
 * far apart that the cubes would need more than 21 bits per axis). Ties go by position, so the
 * subset depends on the set of positions only, not on their order; it moves with the points.
 * \param[in]  raw         m points, x y z each, finite (copies of a position share its cube:
 *                         the first of them is kept, if any)
 * \param[in]  max_points  at most this many are kept, >= 1
 * \param[out] cube_edge   the grid's edge (optional)
 * \return per point, 1 if kept */
std::vector<char> evenSubset(const float* raw, std::size_t m, std::size_t max_points,
                             double* cube_edge = nullptr);

/** \brief preparePoints() at the resolution max_points: a cloud of more than max_points points
 * is analysed on its evenSubset() alone, and every other point becomes a copy of its nearest kept
 * point (Euclidean), so that it shares its segment. Only the kept points are ordered: in the
 * order they have among all the points (Morton codes over the whole cloud's box), with dense
 * ranks in PointSet::order by input index, centred on their centroid. The result does not
 * depend on the order of the input.
 * \param[in] xyz         n points, 3 floats each, finite; consumed
 * \param[in] max_points  the resolution of the analysis; 0: none (preparePoints())
 * \param[in] num_threads threads for the nearest-point queries (>= 1); the result does not
 *                        depend on it */
PreparedPoints prepareAtResolution(std::vector<float> xyz, std::size_t max_points, int num_threads);

} // namespace pcl_ncut_seg
