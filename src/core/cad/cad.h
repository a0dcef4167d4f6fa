/*
 * pcl_ncut_seg: point-sampled CAD models (Sec. 7). The kNN graph is transformed so that the
 * faces of the part become elongated features and its ridges their boundaries; the supernodes
 * of the transformed graph are then compared by the orientation of the faces they represent.
 *
 * Sec. 7 is a sketch; the choices made here are documented in docs/cad.md.
 */
#pragma once

#include <pcl_ncut_seg/parameters.h>

#include "core/cut/supernode_graph.h"
#include "core/graph/csr_graph.h"
#include "core/model/model.h"
#include "core/supernodes/supernodes.h"

#include <cstdint>
#include <vector>

namespace pcl_ncut_seg {

/** \brief Laplacian smoothing of unoriented unit normals over the kNN graph (Sec. 7): each step
 * replaces n_p by the normalised sum of n_p and its neighbours' normals, each neighbour's flipped
 * to agree with n_p. Non-finite or zero normals are left out of the sums and come out as
 * zero when no neighbour has one.
 * \param[in] normals  3 floats per vertex */
std::vector<float> smoothNormals(const CsrGraph& graph, const float* normals, int iterations);

/** \brief Ridge points: vertices whose (smoothed) normal turns, on average over N(p), by more
 * than ridge_angle degrees to their neighbours' normals. */
std::vector<bool> ridgePoints(const CsrGraph& graph, const std::vector<float>& normals,
                              float ridge_angle);

/** \brief Geodesic distance (over the graph's lengths) from every vertex to the nearest ridge
 * point; +infinity in a component without ridge points. */
std::vector<float> ridgeDistance(const CsrGraph& graph, const std::vector<bool>& ridge);

/** \brief Supernodes that do not cross ridges. The points of each supernode off the ridges
 * fall into connected regions; a region of fewer than min_points points joins the neighbouring
 * region (off the ridges) it shares most kNN edges with, smallest first. A region with no such
 * neighbour that holds fewer than twice the mean |N(p)| points is dissolved like ridge points; each
 * remaining region is a supernode. Each ridge point joins, among the regions with at least six
 * off-ridge points within four kNN steps, the one whose plane fitted to those points passes nearest
 * to it (the nearest region on the graph when no plane can be fitted). The saddle relations are
 * dropped (the CAD graph of supernodes does not use them). \param[in] graph  the kNN graph with
 * Euclidean lengths \param[in] xyz    3 floats per vertex \param[in] label  per vertex, its
 * supernode */
Supernodes splitAtRidges(const CsrGraph& graph, const float* xyz, const std::vector<bool>& ridge,
                         const std::vector<std::uint32_t>& label, std::size_t min_points);

/** \brief The transformed graph of Sec. 7. An edge (p, q) of length d gets the length
 *   d * (shrink + (stretch - shrink) * a),  a = |phi(p) - phi(q)| / d in [0, 1],
 * with phi the ridge distance: an edge between points equidistant from a ridge (a = 0) is
 * shrunk, an edge pointing straight away from it (a = 1) is stretched. Centrality then grows
 * with the distance from the ridges: each face becomes a feature whose tip is its middle and
 * whose boundary is its ridges. Vertices with infinite phi keep shrink * d. */
CsrGraph transformGraph(const CsrGraph& graph, const std::vector<float>& phi, float shrink,
                        float stretch);

/** \brief Per pair of supernodes that touch in the kNN graph, the median angle in degrees between
 * the orientations of the faces they represent at their contact. For each kNN edge (p, q) with
 * p in s_i and q in s_j, the face normal of s_i at p is fitted (least squares) to the points of
 * s_i off the ridges within three kNN steps of p (through s_i), at least six, likewise for s_j
 * at q; the median of the angle between the two (unoriented) normals is taken over the edges
 * where both fits are planar. A pair with no such edge gets 90 degrees. Keyed (min, max), i != j.
 * \param[in] xyz    3 floats per vertex
 * \param[in] label  per vertex, its supernode
 * \param[in] ridge  per vertex, whether it is a ridge point (empty: none is) */
std::map<std::pair<std::uint32_t, std::uint32_t>, double>
faceContactAngles(const CsrGraph& graph, const float* xyz, const std::vector<std::uint32_t>& label,
                  const std::vector<bool>& ridge = {});

/// Sec. 7 leaves these open. Laplacian smoothing steps of the approximate normals: enough to
/// quiet the sampling's scatter, few enough to keep a ridge one or two points wide.
constexpr int kCadSmoothingIterations = 3;
/// Length factors of kNN edges: between points equidistant from a ridge (shrunk, so that a face
/// becomes an elongated feature along the ridge) and pointing straight away from it (kept).
constexpr float kRidgeShrink = 0.1f;
constexpr float kRidgeStretch = 1.0f;
/// Angle scale in degrees of the face-orientation similarity exp(-(angle / a)^2): faces
/// meeting at 15 degrees are e times less similar than coplanar ones.
constexpr double kFaceAngle = 15.0;

/** \brief G_s in CAD mode (Sec. 7 after Sec. 5.1): r_i - m_i with the weight of eq. (7); m_i -
 * m_j for every pair of supernodes touching in the kNN graph, weighted by the similarity of
 * their faces' orientations exp(-(theta_ij / kFaceAngle)^2) (theta_ij from faceContactAngles)
 * times the share of their contact in the smaller of their boundaries,
 * conn(s_i, s_j) / min(sum_k conn(s_i, s_k), sum_k conn(s_j, s_k)) over k != i, j resp.
 */
WeightedGraph buildCadSupernodeGraph(const Supernodes& supernodes, const FeatureStats& stats,
                                     const Connectivity& conn, const Connectivity& face_angles,
                                     const SimilarityParams& params);

/** \brief Sec. 7's transformed graph and its ridges. */
struct CadGraph {
  CsrGraph graph;          ///< transformGraph() of the kNN graph
  std::vector<bool> ridge; ///< ridgePoints() of the smoothed normals
};

/** \brief The graph CAD mode analyses (Sec. 7): the normals smoothed (smoothNormals()), the
 * ridge points found (ridgePoints()), and the kNN graph transformed by the distance from them
 * (ridgeDistance(), transformGraph()). Secs. 4.1-4.3 then run on CadGraph::graph.
 * \param[in] graph        the kNN graph with Euclidean lengths
 * \param[in] normals      3 floats per vertex, approximate normals (any orientation)
 * \param[in] ridge_angle  cad.ridge_angle, degrees */
CadGraph cadGraph(const CsrGraph& graph, const float* normals, float ridge_angle);

/** \brief CAD mode's faces (Sec. 7, "ridges to feature boundaries") on an analysis of the
 * transformed graph after Secs. 4.1-4.3: its refined supernodes split at the ridges
 * (splitAtRidges(), regions of fewer than area_fraction of the points joined), their features
 * and eq. (8) measured again, and the angles between touching faces (faceContactAngles()).
 * Sets analysis.cad.
 * \param[in] graph          the kNN graph with Euclidean lengths (not the transformed one)
 * \param[in] xyz            3 floats per vertex
 * \param[in] ridge          CadGraph::ridge
 * \param[in] area_fraction  refinement.area_fraction */
void cadFaces(Analysis& analysis, const CsrGraph& graph, const float* xyz,
              const std::vector<bool>& ridge, float area_fraction);

} // namespace pcl_ncut_seg
