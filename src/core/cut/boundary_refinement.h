/*
 * pcl_ncut_seg: point-level boundary refinement after the hierarchy (an extension of Sec. 5.2,
 * in the spirit of Katz and Tal's fuzzy cuts, SIGGRAPH 2003). A segment boundary is a supernode
 * boundary, where the centrality's gradient flows meet (Secs. 4.2-4.3); people draw it along
 * the concave crease, which can lie a little to one side. Each pair of touching segments gets a
 * band (fuzzy region) around their common boundary, which a minimum cut on the kNN graph recuts
 * with capacities that are low across concave creases.
 */
#pragma once

#include <pcl_ncut_seg/parameters.h>

#include "core/graph/csr_graph.h"

#include <cstdint>
#include <vector>

namespace pcl_ncut_seg {

/** \brief Per directed edge of the graph (the same positions as graph.targets), how concave
 * the surface is across it: the concave bend max(0, -(n_p - n_q) . (p - q) / |p - q|) (as in
 * contactConcavity()) divided by meanAbsBend(), stored as round(16 c)
 * clamped to 255 (one byte per edge, kept from the expensive stage).
 * \param[in] xyz          3 floats per vertex
 * \param[in] normals      3 floats per vertex, from orientedNormals()
 * \param[in] num_threads  0 = all cores; the result does not depend on it
 * \param[in] typical_bend meanAbsBend(), when the caller has it already; 0: computed here */
std::vector<std::uint8_t> edgeCreases(const CsrGraph& graph, const float* xyz,
                                      const std::vector<float>& normals, unsigned num_threads = 0,
                                      double typical_bend = 0.0);

/// A kNN edge's cut cost is its length times exp(-w c), c its concave bend: the weight w of
/// the concavity term of eq. (9)'s default, so a boundary prefers the creases the cut did.
constexpr double kBoundaryCreaseWeight = 3.0;

/** \brief Recut the boundary of each pair of touching segments (in order of their ids) with a
 * minimum cut over the pair's band on the kNN graph: the segments' points outside the band
 * are the source and the sink. Every point keeps a segment and no segment empties (each keeps
 * the part of it outside the band). When a recut cuts a piece off a segment (its points
 * outside the band were connected only through the band), the piece joins the neighbouring
 * segment it shares the most kNN edges with, so that no segment ends with more connected
 * components in the kNN graph than it had. Sequential and deterministic.
 * \param[in] radii          r(p) of Sec. 4.3; a point's area is pi r(p)^2, as in f_a
 * \param[in] crease         from edgeCreases(); empty: no crease term
 * \param[in,out] segment    per vertex, its segment in [0, num_segments)
 * \return the number of points whose segment changed */
std::size_t refineBoundaries(const CsrGraph& graph, const std::vector<float>& radii,
                             const std::vector<std::uint8_t>& crease, const BoundaryParams& params,
                             std::vector<std::uint32_t>& segment, std::size_t num_segments);

} // namespace pcl_ncut_seg
