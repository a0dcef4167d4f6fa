/*
 * pcl_ncut_seg: the kNN graph of Sec. 4.1 as a compressed sparse row (CSR) graph.
 */
#pragma once

#include <cstdint>
#include <vector>

namespace pcl_ncut_seg {

/** \brief Undirected graph in CSR form; every edge is stored in both directions.
 *
 * Vertex v's neighbours are targets[offsets[v] .. offsets[v+1]), sorted ascending,
 * with Euclidean edge lengths in lengths[] at the same positions.
 */
struct CsrGraph {
  std::vector<std::uint32_t> offsets; ///< size n + 1
  std::vector<std::uint32_t> targets; ///< size 2|E|
  std::vector<float> lengths;         ///< size 2|E|, Euclidean length d(p, q) >= 0

  std::size_t numVertices() const { return offsets.empty() ? 0 : offsets.size() - 1; }
  std::size_t numDirectedEdges() const { return targets.size(); }
  std::uint32_t degree(std::uint32_t v) const { return offsets[v + 1] - offsets[v]; }
};

/** \brief Build the symmetric kNN graph (Sec. 4.1): edge {p, q} iff q is among p's k nearest
 * neighbours or p among q's (the union of both directions). A direction p -> q longer than 10
 * times q's kNN radius (its distance to the farthest of its own k nearest) is not used, so a
 * lone far point (an outlier) does not reach into a surface.
 *
 * \param[in] xyz        n points, 3 floats each
 * \param[in] n          number of points
 * \param[in] knn        n * k neighbour indices (row p: p's neighbours, self excluded);
 *                       entries >= n are ignored (fewer neighbours found)
 * \param[in] k          neighbours per row
 * \param[in] num_threads threads (>= 1); the graph does not depend on it
 * \return the graph; duplicate edges are merged.
 */
CsrGraph buildSymmetricKnnGraph(const float* xyz, std::size_t n, const std::uint32_t* knn,
                                std::size_t k, int num_threads = 1);

/** \brief Sets every edge's length to the Euclidean distance between its ends in xyz, as
 * buildSymmetricKnnGraph() does (after the points moved; the edges stay). */
void measureLengths(CsrGraph& graph, const float* xyz);

/** \brief Connected components of a graph.
 * \param[out] component  per vertex, its component id; ids are numbered in order of each
 *                        component's smallest vertex
 * \return the number of components
 */
std::size_t connectedComponents(const CsrGraph& graph, std::vector<std::uint32_t>& component);

} // namespace pcl_ncut_seg
