/*
 * pcl_ncut_seg: the weighted graph of supernodes G_s (Sec. 5.1, Fig. 6, eqs. 7-9).
 */
#pragma once

#include <pcl_ncut_seg/core/csr_graph.h>
#include <pcl_ncut_seg/core/refinement.h>
#include <pcl_ncut_seg/core/supernodes.h>

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
  /// Optional mass of each vertex (empty: none): the feature area f_a of a member vertex's
  /// supernode, 0 for representative vertices. Used by CutParams::min_segment_fraction.
  std::vector<double> mass;
};

struct SimilarityParams {
  double beta = 2.0;   ///< eq. (7)
  double alpha1 = 2.0; ///< eq. (9)
  double alpha2 = 0.5; ///< alpha_ij = alpha2 * min(f_w) / max(f_w)
  /// Feature width divided by sqrt(total feature area), so eq. (7) does not change with units.
  bool normalize_width = true;
  /// Join member-vertex trees that share no saddle but touch in the kNN graph (see README).
  bool connect_adjacent_trees = true;
  /// Join every pair of supernodes that touch in the kNN graph with the weight of eq. (9), not
  /// only pairs that meet at a saddle (false = the paper). Without it the member vertices form
  /// a tree, and on shapes without elongated parts any supernode can be cut off at the price
  /// of one small edge.
  bool connect_all_adjacent = true;
  /// With connect_all_adjacent: join a pair that meets at no saddle only if their contact,
  /// conn(s_i, s_j), is at least this share of the contact of the one of them with less
  /// contact to all other supernodes (0 = every touching pair). Patches of a flat region share
  /// long borders; limbs touch each other through a few feature-crossing edges.
  double adjacent_share = 0.45;
  /// Concave creases: the weight of eq. (9) between two supernodes is multiplied by
  /// exp(-concavity_weight * c_ij), c_ij the concavity of their contact (contactConcavity() in
  /// core/concavity.h), so that cuts follow concave creases. 0 = the paper (no such factor).
  /// Without a concavity map (buildSupernodeGraph's last argument) it has no effect.
  double concavity_weight = 3.0;
  /// Flat patches: a supernode is flat when its feature height is below flat_elongation times
  /// the square root of its feature area (f_h < e sqrt(f_a)); between two flat supernodes
  /// alpha_ij of eq. (9) is alpha2, without the width ratio, as their widths f_a / f_h are
  /// inflated by a near-zero height. 0 = the paper (no supernode is flat).
  double flat_elongation = 0.1;
};

/** \brief Build G_s: r_i - m_i with weight (7); m_i - m_j with weight (9) when s_i was created
 * at the saddle where s_j terminates (or vice versa); with connect_adjacent_trees, also the
 * most connected kNN-adjacent pair between member trees that no saddle joins, weighted by (9).
 */
WeightedGraph buildSupernodeGraph(const Supernodes& supernodes, const FeatureStats& stats,
                                  const Connectivity& conn, const SimilarityParams& params,
                                  const Connectivity* concavity = nullptr);

} // namespace pcl_ncut_seg
