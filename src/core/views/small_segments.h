/*
 * pcl_ncut_seg: small segments of an open view joined to their neighbours (an extension of
 * Sec. 4.3's "small" rule to the segments of a single view). A view ends at its rim and hides
 * parts behind others, so a part of the object may show only as a sliver or a fragment there;
 * a segment smaller than the paper's small supernode (1% of the object's area, footnote 4) is
 * such a piece, not a part, unless it hangs from its neighbour by a limb's neck (a table's leg,
 * a finger: small in area, a part all the same). Real depth images (PCL's milk.pcd) show such
 * pieces along the rim, where the sensor's edge pixels scatter.
 */
#pragma once

#include "core/graph/csr_graph.h"

#include <cstdint>
#include <vector>

namespace pcl_ncut_seg {

/** \brief Join each segment whose area is below min_area to the touching segment it shares
 * the most kNN edges with, unless their boundary's neck is below min_neck. The smallest such
 * segment (then the smallest id) joins first, and the joined segment is measured again, until none
 * is small or the small ones touch no other segment (an island stays).
 *
 * Inputs:
 * \param[in] graph        kNN graph
 * \param[in] point_area   per vertex, its area (pi r(p)^2, Sec. 4.3)
 * \param[in] min_area     a segment with less area is small
 * \param[in] min_neck     a small segment whose boundary with that neighbour has a narrower
 *                         neck (NeckMeasure in core/cut/short_cut.h) stays (0: no such test)
 * Inputs and outputs:
 * \param[in,out] segment       per vertex, its segment in [0, num_segments); compact ids on
 *                              output (joinGroups() in core/supernodes/supernodes.h)
 * \param[in,out] num_segments  the number of segments
 * \return per old segment, its new one (empty when nothing joined) */
std::vector<std::uint32_t> joinSmallSegments(const CsrGraph& graph,
                                             const std::vector<double>& point_area, double min_area,
                                             double min_neck, std::vector<std::uint32_t>& segment,
                                             std::size_t& num_segments);

} // namespace pcl_ncut_seg
