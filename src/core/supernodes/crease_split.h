/*
 * pcl_ncut_seg: splitting supernodes along concave creases that cross them (an extension of
 * Sec. 4.3). A head or a tail whose centrality rises into the body without a saddle, or the
 * top of a leg below the saddle where two legs meet, shares a supernode with a piece of the
 * body; people draw the boundary where the surface folds inwards (the minima rule).
 */
#pragma once

#include "core/graph/csr_graph.h"
#include "core/supernodes/supernodes.h"

#include <vector>

namespace pcl_ncut_seg {

/** \brief Parameters of splitAtCreases(). */
struct CreaseSplitParams {
  /// A supernode is split where the level cut of f through it is at least this concave (the
  /// mean concave bend of the kNN edges it crosses, in units of the mean |bend| of all edges,
  /// as in contactConcavity()); 0 = no split (the paper).
  double min_concavity = 0.75;
  /// Each side of a split keeps at least this fraction of the total feature area (the small
  /// supernode threshold of Sec. 4.3).
  float area_fraction = 0.01f;
  /// Threads for the first sweep of every supernode (0 = all cores); the result does not
  /// depend on it.
  unsigned num_threads = 0;
  /// meanAbsBend() of the graph, when the caller has it already; 0: computed here.
  double typical_bend = 0.0;
};

/** \brief Split refined supernodes along concave creases.
 *
 * The points of a supernode are swept in descending f (ties by index). After each point, the
 * cut between the points swept so far (the top) and the rest (the bottom) is a level cut of f
 * through the supernode; its concavity is the mean of max(0, -b) / mean |b| over the kNN edges
 * inside the supernode that it crosses, b the signed bend of contactConcavity(). The most
 * concave level cut with both sides at least `area_fraction` of the total area splits the
 * supernode when its concavity is at least `min_concavity`:
 *  - a supernode created at a saddle gives its top to the supernodes that terminate there
 *    (each top point, highest f first, joins the one most of its processed neighbours are in),
 *    as the local refinement merges a small saddle supernode up;
 *  - any other supernode keeps its bottom, and its top becomes a supernode that terminates at
 *    the bottom's highest point (the bottom then counts as created at a saddle).
 * Both remaining pieces are tested again, until no cut qualifies. Output ids are compact and
 * numbered in order of the first point (by index) of each supernode, as refineSupernodes().
 * \param[in] xyz      3 floats per vertex
 * \param[in] normals  3 floats per vertex, oriented (orientedNormals() in core/cut/concavity.h)
 * \param[in] f        centrality per vertex
 * \param[in] radii    r(p) per vertex (pointRadii()); a point's area is pi r(p)^2
 * \param[in] input    the refined supernodes
 * \param[out] num_splits  if not null, the number of splits made (0: the output is the input) */
Supernodes splitAtCreases(const CsrGraph& graph, const float* xyz,
                          const std::vector<float>& normals, const std::vector<float>& f,
                          const std::vector<float>& radii, const Supernodes& input,
                          const CreaseSplitParams& params, std::size_t* num_splits = nullptr);

} // namespace pcl_ncut_seg
