/*
 * pcl_ncut_seg: sensor noise, detected and projected away before the graph is measured (an
 * extension of Sec. 4.1). Noise of the order of the point spacing bends the kNN graph's
 * geodesics and the normals of the concavity measures, and the parts then follow the noise
 * (more segments on smooth surfaces). Whether a cloud is noisy is read off the cloud itself:
 * the scatter about a least-squares plane grows with the square of the neighbourhood's
 * radius where the surface's curvature causes it, and not at all where noise does.
 */
#pragma once

#include "core/graph/csr_graph.h"
#include <pcl_ncut_seg/analysis_report.h> // NoiseTest

#include <cstdint>
#include <vector>

namespace pcl_ncut_seg {

/** \brief The 2-ring fits residualGrowth() made, for projectOntoLocalPlanes() on the same graph
 * and points to reuse (the same fits, bit for bit: a quarter of the projection's work). */
struct RingFits {
  /// Per vertex 4 i: 0 not fitted (its 1-ring has no plane), 1 fitted, 2 its 2-ring has none.
  std::vector<std::uint8_t> state;
  std::vector<float> projected; ///< per vertex 4 i with state 1: it projected, x y z
};

/** \brief Residual growth: over every 4th vertex (in vertex order; a mean needs no more), the
 * sum of the RMS distances to the least-squares planes of their 2-rings (the vertex, its graph
 * neighbours and theirs) over the same sum for their 1-rings (the vertex and its neighbours).
 * About 4 where curvature makes the scatter (it grows with the squared radius, and the 2-ring
 * reaches about twice as far), about 1 where noise makes it; 0 when no vertex has both planes
 * or there is no scatter (an exactly flat cloud).
 * \param[in] graph        the symmetric kNN graph
 * \param[in] xyz          3 floats per vertex
 * \param[in] num_threads  0 = all cores; the result does not depend on it
 * \param[out] fits        if given, the 2-ring fits, for projectOntoLocalPlanes() */
double residualGrowth(const CsrGraph& graph, const float* xyz, unsigned num_threads = 0,
                      RingFits* fits = nullptr);

/** \brief Sampling irregularity: over the vertices with an edge, the coefficient of variation
 * (standard deviation over mean) of the ratio of each vertex's shortest graph edge to its mean
 * graph edge. The ratio does not depend on the density, so neither does the result. About 0.45
 * for points drawn at random (uniformly by area, or with any smooth density: locally their
 * spacings are those of a Poisson process), 0.05-0.2 for points spread evenly (a mesh's face
 * centroids, a sensor's pixel grid), 0.2-0.25 for the grid subsample of points drawn at random
 * (core/graph/subsample.h); 0 for fewer than 2 vertices with an edge. Summed in vertex order.
 *
 * Drawn at random, neighbouring points are closer or farther apart than the surface makes
 * them, the geodesics of eq. (1) zig-zag through the clumps and gaps as through noise, and f
 * has shallow maxima that belong to the draw. When graph.irregular_sampling is set (by
 * default 0.3, between even, at most about 0.2, and random), a whole surface whose
 * irregularity is at least the bound has f taken through neighbourhoodMean() once, as a noisy
 * one. On evenly spread points the shallow maxima belong to the surface, and the mean would
 * blur them.
 * \param[in] graph  the symmetric kNN graph (before any bridges) */
double samplingIrregularity(const CsrGraph& graph);

/** \brief Whether a cloud counts as noisy: a residual growth below the bound (2: halfway
 * between noise's 1 and curvature's 4 on a log scale) and above 0. */
inline bool isNoisy(double residual_growth, double growth_bound) {
  return residual_growth > 0.0 && residual_growth < growth_bound;
}

/** \brief Each vertex projected onto the least-squares plane of its 2-ring: 3 floats per
 * vertex (the vertex itself where the 2-ring has no plane: fewer than 3 points, collinear or
 * coincident).
 * \param[in] num_threads  0 = all cores; the result does not depend on it
 * \param[in] fits         if given, residualGrowth()'s fits on the same graph and points */
std::vector<float> projectOntoLocalPlanes(const CsrGraph& graph, const float* xyz,
                                          unsigned num_threads = 0, const RingFits* fits = nullptr);

/** \brief Per vertex, the mean of values over its closed neighbourhood in the graph (the vertex
 * and its neighbours, equally weighted), summed in double in edge order.
 *
 * On a noisy whole surface (not an open view, whose sensor's noise runs along its rays, where
 * the projection takes it out) the centrality of eq. (1) is taken through this mean once. The
 * geodesics of eq. (1) zig-zag through the noise that the projection leaves, and neighbouring
 * points differ in f by more than the surface makes them differ: on a bearing sampled with noise of
 * one point spacing, 0.47 spacings (RMS, after taking out f's scale) against a typical 0.23
 * between clean neighbours, and f has 807 local maxima against 84 clean. Each maximum starts a
 * supernode (Sec. 4.2), and a plateau broken into many becomes chips. One mean over about a
 * dozen points divides independent noise by about 3.5, below the clean differences; it smooths
 * at the scale at which the noise was found (the 1-ring of residualGrowth()), as the short-cut
 * rule's vote does (core/cut/short_cut.h).
 * \param[in] graph   the kNN graph
 * \param[in] values  one per vertex
 * \param[in] num_threads  0 = all cores; the result does not depend on it */
std::vector<float> neighbourhoodMean(const CsrGraph& graph, const std::vector<float>& values,
                                     unsigned num_threads = 0);

} // namespace pcl_ncut_seg
