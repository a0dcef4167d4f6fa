/*
 * pcl_ncut_seg: concave creases between supernodes, so that boundaries follow them (people
 * cut shapes along concave creases: the minima rule). An extension of Sec. 5.1; see README.
 */
#pragma once

#include "core/cut/supernode_graph.h"
#include "core/graph/csr_graph.h"

#include <cstdint>
#include <vector>

namespace pcl_ncut_seg {

/** \brief Unit normals fitted (least squares plane) to each point and its graph neighbours,
 * oriented consistently by propagation along a minimum spanning tree of the kNN graph
 * (weights 1 - |n_p . n_q|, Hoppe et al. 1992), each component turned outwards by the more
 * decisive of two tests: the normal of the point farthest from the centroid (parallel to
 * p - centroid on a smooth closed surface; its cosine), and the sum of n . (p - centroid)
 * over the points (3 times the volume for outward normals, the divergence theorem; its ratio
 * to the sum of |n . (p - centroid)|). A point without a plane (fewer than 3 neighbours,
 * collinear) gets a zero normal. The tree is Prim's with the weights rounded down to
 * multiples of 1/1024, which keeps it O(n + m). For one view of a surface, give the sensor's
 * position: a camera sees a solid from outside, so each component is turned to face it on the
 * whole (the sum of n . (s - p) / |s - p| is positive) instead.
 * \param[in] xyz          3 floats per vertex
 * \param[in] num_threads  threads for the plane fits (0 = all cores); the result does not
 *                         depend on it
 * \param[in] viewpoint    3 floats, the sensor's position in xyz's coordinates; null: a
 *                         whole surface */
std::vector<float> orientedNormals(const CsrGraph& graph, const float* xyz,
                                   unsigned num_threads = 0, const float* viewpoint = nullptr);

/** \brief Signed bend of the kNN edge (p, q) of the given length: (n_p - n_q) . (p - q) /
 * |p - q|, about the angle between the normals; > 0 where the surface folds outwards
 * (convex), < 0 where it folds inwards (concave), 0 for an edge of zero length.
 * \param[in] normals  3 floats per vertex, from orientedNormals() */
inline double edgeBend(const float* xyz, const std::vector<float>& normals, std::size_t p,
                       std::size_t q, float length) {
  if (!(length > 0.0f))
    return 0.0;
  double s = 0.0;
  for (int d = 0; d < 3; ++d)
    s += (normals[3 * p + d] - normals[3 * q + d]) * (xyz[3 * p + d] - xyz[3 * q + d]);
  return s / length;
}

/** \brief The model's typical bend, the unit in which concavity is measured so that it does
 * not depend on the sampling density or the model's size: the mean |edgeBend| over the
 * graph's undirected edges, 0 without edges. Summed over fixed blocks of vertices, in block
 * order, so it does not depend on the number of threads. */
double meanAbsBend(const CsrGraph& graph, const float* xyz, const std::vector<float>& normals,
                   unsigned num_threads = 0);

/** \brief Per pair of touching supernodes (keyed (min, max), i != j), how concave their
 * contact is: the mean over the kNN edges (p, q) between them of the concave bend
 * max(0, -(n_p - n_q) . (p - q) / |p - q|) (about the angle between the normals where the
 * surface folds inwards, 0 where it folds outwards), divided by the mean bend |(n_p - n_q) .
 * (p - q)| / |p - q| over every edge of the graph (meanAbsBend()), so that it does not depend on
 * the sampling density or the model's size.
 * \param[in] normals       3 floats per vertex, from orientedNormals()
 * \param[in] label         per vertex, its supernode
 * \param[in] typical_bend  meanAbsBend(), when the caller has it already; 0: computed here */
Connectivity contactConcavity(const CsrGraph& graph, const float* xyz,
                              const std::vector<float>& normals,
                              const std::vector<std::uint32_t>& label, double typical_bend = 0.0);

} // namespace pcl_ncut_seg
