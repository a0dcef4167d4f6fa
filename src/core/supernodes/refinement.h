/*
 * pcl_ncut_seg: feature height, area and width (eqs. 2-4) and local refinement (Sec. 4.3).
 */
#pragma once

#include <pcl_ncut_seg/parameters.h>

#include "core/graph/csr_graph.h"
#include "core/supernodes/supernodes.h"

#include <cmath>
#include <vector>

namespace pcl_ncut_seg {

/** \brief ||p - q||_2 of eq. (3): mixes the centrality difference and the Euclidean length. */
inline float featureDistance(float df, float d) {
  return std::sqrt(df * df + d * d);
}

/** \brief A point's feature area pi r(p)^2 (Sec. 4.3; f_a sums it), r(p) from pointRadii(). */
inline double pointArea(float radius) {
  constexpr double kPi = 3.14159265358979323846;
  return kPi * radius * radius;
}

/** \brief r(p) of Sec. 4.3: mean of ||p - q||_2 (eq. 3) over the neighbours N(p). */
std::vector<float> pointRadii(const CsrGraph& graph, const std::vector<float>& f,
                              unsigned num_threads = 1);

/** \brief Per supernode: feature height (eq. 2), area and width (eq. 4). */
struct FeatureStats {
  std::vector<float> height; ///< f_h(s) = max f - min f over s
  std::vector<float> area;   ///< f_a(s) = sum_{p in s} pi r(p)^2
  std::vector<float> width;  ///< f_w(s) = f_a(s) / f_h(s); f_h is floored at 1e-6 max f_h
};

FeatureStats featureStats(const Supernodes& supernodes, const std::vector<float>& f,
                          const std::vector<float>& radii);

/** \brief Local refinement (Sec. 4.3), in this order:
 *  1. merge-up: a small supernode created at a saddle is dissolved into the supernodes that
 *     terminate at that saddle (each of its points joins the nearest of them on the graph);
 *  2. merge-down: a skinny supernode, or a small one not merged up, that terminates at a saddle
 *     joins the supernode created there;
 *  3. each disconnected region of a supernode but its largest is re-tested: small or skinny
 *     ones join the neighbouring supernode they share most kNN edges with, others become
 *     supernodes of their own;
 *  4. a small or skinny supernode with no saddle relation joins the point-wise neighbour it
 *     shares most kNN edges with.
 * Thresholds are taken from the supernodes before refinement, per connected component of the
 * graph (each is a surface of its own: 1% of its own area, of its own largest height). Output
 * ids are compact and numbered in order of the first point (by index) of each supernode.
 *
 * \param[in] input supernodes as extractSupernodes() returns them, where one without children
 *            is connected in graph (step 3 does not search those until they change).
 */
Supernodes refineSupernodes(const CsrGraph& graph, const std::vector<float>& f,
                            const std::vector<float>& radii, const Supernodes& input,
                            const RefinementParams& params);

} // namespace pcl_ncut_seg
