/*
 * pcl_ncut_seg: where the sensor of a single view was, read off the points when nothing says
 * (a crop handed over with sensor_origin_ left at 0 in another frame). A view is an open
 * surface whose rim runs around the silhouette the sensor saw; that rim lies across the
 * sensor's line of sight, so the sensor is on the axis of the rim's plane, on the side from
 * which the points form one layer (core/views/single_view.h decides).
 */
#pragma once

#include "core/graph/csr_graph.h"
#include <pcl_ncut_seg/analysis_report.h> // ViewTest

#include <array>
#include <cstdint>
#include <optional>
#include <vector>

namespace pcl_ncut_seg {

/** \brief Boundary points found from the points alone: a vertex whose graph neighbours,
 * projected onto the least-squares plane of its 1-ring, leave an angular gap above pi / 2
 * (pcl::BoundaryEstimation's test, with the 1-ring's plane for the normal). A vertex with
 * fewer than 3 neighbours or a degenerate 1-ring is no boundary point. A gap above pi / 2 must
 * also be left by the 2-ring's points (ten neighbours drawn at random leave one about two times
 * in three).
 * \param[in] graph        the symmetric kNN graph
 * \param[in] xyz          3 floats per vertex
 * \param[in] num_threads  0 = all cores; the result does not depend on it
 * \return per vertex 1 on a boundary, 0 inside */
std::vector<std::uint8_t> boundaryPoints(const CsrGraph& graph, const float* xyz,
                                         unsigned num_threads = 0);

/** \brief Whether a sensor at origin could have seen all the points: it is at least half their
 * bounding-box diagonal from their centroid. A sensor with a field of view of 60 degrees must
 * stand about one diagonal off to see a whole object; an origin among the points (a cloud
 * moved into the object's frame with sensor_origin_ left at 0) is none.
 * \param[in] xyz  3 floats per point, n points */
bool couldBeSensor(const float* xyz, std::size_t n, const float origin[3]);

/** \brief The sensor position of a view when it is not known. The boundary points
 * (boundaryPoints()) with at least two boundary points among their graph neighbours (a rim is a
 * curve; a lone one is a gap of an irregular sampling) are fitted with a plane; the candidates
 * are the two points on its axis through the points' centroid, three bounding-box diagonals
 * away, first on the side towards which the points bulge from their rim (a sensor sees an
 * object's near side). The first from which singleViewRim() finds one view whose rim and
 * boundary points agree (at least half the boundary points on the rim, and at least a quarter
 * of the rim boundary points: a view's surface ends where the sensor's sight does, while a
 * closed surface continues behind its silhouette) is returned. Nothing when there are fewer
 * boundary points than sqrt(n) (a closed surface, or a view with almost no rim) or neither
 * candidate sees such a view (an object seen all round, a mesh open at both ends, a closed surface
 * with thin parts). \param[in] graph        the symmetric kNN graph \param[in] xyz          3
 * floats per vertex \param[in] num_threads  0 = all cores; the result does not depend on it
 * \param[out] rim         if given and a position is returned, singleViewRim() from it */
std::optional<std::array<float, 3>> estimateViewOrigin(const CsrGraph& graph, const float* xyz,
                                                       unsigned num_threads = 0,
                                                       std::vector<std::uint8_t>* rim = nullptr);

} // namespace pcl_ncut_seg
