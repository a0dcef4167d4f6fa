/*
 * pcl_ncut_seg: single views (a depth camera's or a laser scanner's frame) recognised from the
 * points and the sensor's position, and the rim of such a view. A view is an open surface: it
 * ends where the surface leaves the sensor's sight, hides behind itself or is cut off by the
 * frame, and those ends are no extremities of the object. In the image plane a view is a
 * height field (one range per ray), so its rim is where a point's neighbours, seen along its
 * ray, leave a wide angular gap.
 */
#pragma once

#include "core/graph/csr_graph.h"

#include <cstdint>
#include <vector>

namespace pcl_ncut_seg {

/** \brief Whether the points are one view of a surface seen from `origin` (a depth camera's or
 * laser scanner's), and if so, per vertex, whether it lies on the view's rim: where the seen
 * surface ends because it leaves the sensor's sight, hides behind itself, or was cut off.
 *
 * One view: every point's direction from the origin lies within 80 degrees of their mean
 * direction, and the points form one layer along the rays. The directions are binned on a grid
 * in the image plane across the mean direction, cells of about a point spacing there; at most
 * 2% of the occupied cells may hold two points inside their layers (they and their graph
 * neighbours off the rim) whose ranges differ by more than 5 times their mean graph edge
 * length, a surface seen through another. Both layers end where one hides the other, so a
 * depth image with occlusions is one view and a closed surface seen from outside is not.
 *
 * Rim: the vertex's graph neighbours, projected along its ray onto the plane across it (the
 * image plane there), leave an angular gap above pi / 2 (pcl::BoundaryEstimation's test with
 * the ray for the normal), and so do they with their own neighbours (where a surface turns
 * away from the sensor, the graph's neighbours crowd along the silhouette); or the vertex has
 * fewer than 3 neighbours. Exact for a surface sampled by the sensor's rays (evenly in the
 * image); on one sampled evenly in space, where it is seen at more than about 75 degrees from
 * its normal is flagged too. Time O(n k), and O(k^2) more per vertex whose neighbours leave
 * a gap; a surface seen through another is told from the cells that could hold two layers
 * before the rim is decided everywhere.
 * \param[in] graph        the symmetric kNN graph
 * \param[in] xyz          3 floats per vertex
 * \param[in] origin       the sensor's position
 * \param[in] num_threads  0 = all cores; the result does not depend on it
 * \return per vertex 1 on the rim, 0 inside; empty when the points are not one view from origin
 * (also for fewer than 3 points, and for a point at the origin or not finite) */
std::vector<std::uint8_t> singleViewRim(const CsrGraph& graph, const float* xyz,
                                        const float origin[3], unsigned num_threads = 0);

} // namespace pcl_ncut_seg
