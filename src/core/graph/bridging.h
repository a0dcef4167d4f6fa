/*
 * pcl_ncut_seg: joining the components of the kNN graph that only a sampling gap separates.
 */
#pragma once

#include "core/graph/csr_graph.h"

#include <cstddef>
#include <vector>

namespace pcl_ncut_seg {

/** \brief Join components of the kNN graph across sampling gaps.
 *
 * A surface sampled unevenly (long thin triangles, face centroids) can fall into several
 * components of the kNN graph; each would become its own segment at NCut 0. Two components
 * are joined by their shortest point pair (p, q) when |p - q| is at most `max_gap` times the
 * smaller of the kNN radii of p and q (a point's distance to the farthest of its graph
 * neighbours): the gap is then of the order of the sampling spacing on both sides. (In a depth
 * view, a far surface seen at a grazing angle is sampled sparsely; the larger radius would let
 * it reach across the depth jump to a dense near surface that hides part of it.) The result
 * does not depend on how the points are numbered. Candidate pairs are
 * taken shortest first and only join components not yet joined (Kruskal), so each bridge is
 * the shortest link between what it joins. Objects farther apart than that stay separate.
 *
 * \param[in,out] graph  the symmetric kNN graph with Euclidean lengths; bridges are added as
 *                       edges (rows stay sorted)
 * \param[in] xyz        3 floats per vertex
 * \param[in] max_gap    the largest bridge, in kNN radii, >= 0 (0: no bridge)
 * \param[out] bridge_ratios  if not null, each added bridge's length over the smaller radius (at
 * most max_gap) \return the number of bridges added
 */
std::size_t bridgeComponents(CsrGraph& graph, const float* xyz, double max_gap,
                             std::vector<double>* bridge_ratios = nullptr);

} // namespace pcl_ncut_seg
