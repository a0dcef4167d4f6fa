/*
 * pcl_ncut_seg: open views (an extension). A single view of an object ends at a rim, where the
 * surface leaves the camera's sight or hides behind itself. The centrality (eq. 1) is largest
 * there, so the rim grows features of its own (Sec. 4.2) that the hierarchy (Sec. 5.2) cuts
 * off. Where such a cut crosses no concave crease, it is the rim's and not the shape's (the
 * minima rule: parts meet at concave creases), and the two segments are one part.
 */
#pragma once

#include "core/graph/csr_graph.h"

#include <cstdint>
#include <vector>

namespace pcl_ncut_seg {

/** \brief Merge touching segments of an open surface whose common boundary is neither a
 * concave crease nor a limb's neck, when one of the two reaches the rim. Each side of a
 * boundary is its points within band_width of the other side (along kNN edges, inside the
 * side: a length of the surface, so that a denser cloud measures the same band); a plane
 * fitted to each (least squares, oriented by the normals) gives the angle at which the two
 * sides meet, concave when the normals lean towards each other. Noise along a flat face
 * averages out over the band, where the bends between single normals, along boundaries that
 * earlier stages drew through the most concave of them, do not. A limb's neck is narrower
 * than sqrt(pi) (core/cut/short_cut.h's neck of a tube as long as it is wide); a piece chipped off
 * at the rim has a wider one. Of the qualifying pairs the least concave (then the smallest
 * ids) merges first, and the merged boundaries are measured again, until none qualifies.
 * \param[in] graph          kNN graph
 * \param[in] rim            per vertex, 1 on the view's rim
 * \param[in] xyz            3 floats per vertex
 * \param[in] normals        3 floats per vertex, oriented (orientedNormals() in
 * core/cut/concavity.h) \param[in] max_degrees    a boundary whose sides meet at a concave angle
 * below this is not a crease \param[in] band_width     the width of each side's band, in the units
 * of xyz (> 0) \param[in,out] segment    per vertex, its segment; compact ids on output
 * \param[in,out] num_segments
 * \return per old segment, its new one (empty when nothing merged) */
std::vector<std::uint32_t>
mergeAcrossRim(const CsrGraph& graph, const std::vector<std::uint8_t>& rim,
               const std::vector<float>& xyz, const std::vector<float>& normals, double max_degrees,
               double band_width, std::vector<std::uint32_t>& segment, std::size_t& num_segments);

} // namespace pcl_ncut_seg
