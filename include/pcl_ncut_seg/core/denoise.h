/*
 * pcl_ncut_seg: sensor noise, detected and projected away before the graph is measured (an
 * extension of Sec. 4.1). Noise of the order of the point spacing bends the kNN graph's
 * geodesics and the normals of the concavity measures, and the parts then follow the noise
 * (more segments on smooth surfaces). Whether a cloud is noisy is read off the cloud itself:
 * the scatter about a least-squares plane grows with the square of the neighbourhood's
 * radius where the surface's curvature causes it, and not at all where noise does.
 */
#pragma once

#include <pcl_ncut_seg/core/csr_graph.h>

#include <vector>

namespace pcl_ncut_seg {

/** \brief Least-squares planes of each point's 1-ring (the point and its graph neighbours) and
 * 2-ring (with the neighbours' neighbours). */
struct LocalPlanes {
  /// Residual growth: the sum over points of the RMS distance to their 2-ring's plane over the
  /// same sum for their 1-ring's. About 4 where curvature makes the scatter (it grows with the
  /// squared radius, and the 2-ring reaches about twice as far), about 1 where noise makes it;
  /// 0 when no point has a plane (a cloud without neighbourhoods, or exactly flat).
  double residual_growth = 0.0;
  /// Per vertex, 3 floats: the vertex projected onto its 2-ring's plane (the vertex itself
  /// where the 2-ring has no plane: fewer than 3 points, collinear or coincident).
  std::vector<float> projected;
};

/** \brief Fits the planes of every vertex's 1-ring and 2-ring.
 * \param[in] graph        the symmetric kNN graph
 * \param[in] xyz          3 floats per vertex
 * \param[in] num_threads  0 = all cores; the result does not depend on it */
LocalPlanes fitLocalPlanes(const CsrGraph& graph, const float* xyz, unsigned num_threads = 0);

/** \brief Whether a cloud counts as noisy: residual growth below the bound (2: halfway between
 * noise's 1 and curvature's 4 on a log scale), with at least one plane fitted. */
inline bool isNoisy(const LocalPlanes& planes, double growth_bound) {
  return planes.residual_growth > 0.0 && planes.residual_growth < growth_bound;
}

} // namespace pcl_ncut_seg
