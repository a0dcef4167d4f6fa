/*
 * pcl_ncut_seg: the weighted graph of supernodes G_s (Sec. 5.1, Fig. 6, eqs. 7-9).
 */
#pragma once

#include <pcl_ncut_seg/parameters.h>

#include "core/graph/csr_graph.h"
#include "core/supernodes/refinement.h"
#include "core/supernodes/supernodes.h"

#include <cstdint>
#include <map>
#include <utility>
#include <vector>

namespace pcl_ncut_seg {

/** \brief conn(s_i, s_j) of eq. (8) for every pair of supernodes joined by a kNN edge
 * (including i == j), keyed (min, max). */
using Connectivity = std::map<std::pair<std::uint32_t, std::uint32_t>, double>;

Connectivity supernodeConnectivity(const CsrGraph& graph, const std::vector<float>& f,
                                   const std::vector<std::uint32_t>& label,
                                   unsigned num_threads = 1);

/** \brief Weighted undirected graph over 2l vertices: r_i = i, m_i = l + i. */
struct WeightedGraph {
  std::size_t num_vertices = 0;
  struct Edge {
    std::uint32_t a, b;
    double w;
  };
  std::vector<Edge> edges;
};

/// Adjacency::All: a pair of supernodes that meets at no saddle is joined only when its contact
/// is at least this share of the smaller of the two supernodes' contacts with all others: a
/// neighbour across a long common boundary, not one that grazes it.
constexpr double kAdjacentShare = 0.45;

/** \brief Build G_s: r_i - m_i with weight (7); m_i - m_j with weight (9) when s_i was created
 * at the saddle where s_j terminates (or vice versa); with Adjacency::Trees, also the most
 * connected kNN-adjacent pair between member trees that no saddle joins, and with
 * Adjacency::All every pair whose contact is at least kAdjacentShare, each weighted by (9).
 */
WeightedGraph buildSupernodeGraph(const Supernodes& supernodes, const FeatureStats& stats,
                                  const Connectivity& conn, const SimilarityParams& params,
                                  const Connectivity* concavity = nullptr,
                                  const std::vector<float>* thickness = nullptr);

} // namespace pcl_ncut_seg
