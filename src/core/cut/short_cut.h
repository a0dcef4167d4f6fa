/*
 * pcl_ncut_seg: the short-cut stopping rule, an automatic stopping rule for the hierarchy of
 * Sec. 5.2. People cut a shape into parts along short boundaries (the short-cut rule of
 * perception: a finger or a leg is cut off across its narrow base), while a piece chipped off
 * a flat wall or a cup has a long boundary for its size. The rule weighs each best-first
 * split's NCut by how long its boundary is relative to the size of its smaller side.
 */
#pragma once

#include "core/graph/csr_graph.h"

#include <cstdint>
#include <vector>

namespace pcl_ncut_seg {

/** \brief Measures the neck of splits of the supernodes: the boundary's length over the
 * square root of the smaller side's area, both estimated from the kNN graph (each point
 * stands for a disc of radius r(p), the mean length of its kNN edges). Dimensionless: about
 * 2 pi w / sqrt(2 pi w h) for a limb of width w and length h cut at its base, about 4 or more
 * for a square patch cut out of a flat region.
 *
 * On a noisy cloud (vote = true) the boundary is measured after one majority vote over each
 * point's kNN neighbourhood (the point's side becomes the one most of it and its neighbours
 * have; a tie keeps it): there the supernodes interleave along their boundaries by about the
 * noise, and every point of that fringe would count as boundary, a neck 1.5 times as long at
 * noise of one point spacing, for the same cut. A boundary straight at the scale of the
 * neighbourhoods is left as it is. On a clean cloud a fringe is not noise: a chip of a flat
 * wall, cut where the centrality is flat, has one, and its long boundary is what keeps it. */
class NeckMeasure {
public:
  /** \param[in] graph  the kNN graph (edge lengths)
   * \param[in] label  per vertex, its supernode
   * \param[in] num_supernodes  number of supernodes
   * \param[in] vote  measure after the vote (a noisy cloud: NoiseTest::projected) */
  NeckMeasure(const CsrGraph& graph, const std::vector<std::uint32_t>& label,
              std::size_t num_supernodes, bool vote);

  /** \brief side[s]: 0 or 1 for the supernodes of the two sides of a split, negative for
   * supernodes outside the split part. Returns the boundary length (the mean of the two sides'
   * sum of 2 r(p) over points with a kNN neighbour on the other side, after any vote) over
   * sqrt of the smaller side's area (sum of pi r(p)^2); 0 when the sides do not touch or a
   * side has no area. */
  double neck(const std::vector<std::int8_t>& side) const;

private:
  std::vector<double> area_; ///< per supernode, sum of pi r(p)^2
  // The fringe: points with a kNN neighbour in another supernode (the only ones a vote can
  // move) and their neighbours (the only others the moved ones can put on the boundary). Per
  // fringe point: its supernode, r(p) and its neighbours as fringe indices (CSR), only those
  // that vote for a point that does not. The voters come first, in point order.
  std::vector<std::uint32_t> fringe_label_;
  std::vector<double> fringe_radius_;
  std::vector<std::uint32_t> fringe_offsets_, fringe_neighbours_;
  std::size_t num_voters_ = 0;
  bool vote_ = false;
};

/** \brief The worth of a split under the short-cut rule:
 * log(bound / (max(ncut, floor) * max(neck, 1)^exponent)); positive when the split is worth
 * making by itself. */
double splitWorth(double ncut, double neck, double exponent, double bound, double floor);

/// The neck of a limb as long as it is wide, cut at its base: a tube of radius a and length 2a
/// has 2 pi a / sqrt(2 pi a 2a) = sqrt(pi). A piece chipped off at a view's rim has a wider one
/// (a half disc: sqrt(2 pi)); a limb a narrower one.
constexpr double kLimbNeck = 1.7724538509055160273; // sqrt(pi)

/// NCuts below this count as this in splitWorth(): no worth grows without bound.
constexpr double kNeckFloor = 1e-3;

/// The pipeline's exponent of the neck in splitWorth(): a boundary twice as long per unit of
/// the smaller side's size must cut eight times cheaper to be worth as much.
constexpr double kNeckExponent = 3.0;

/** \brief The short-cut rule over a tree of splits: which splits to keep.
 *
 * Node i of the tree (nodes in creation order: a child after its parent) is a split with
 * children left[i] and right[i], or a leaf (left[i] < 0). A split's value is
 * max(0, worth[i] + value(left[i]) + value(right[i])), a leaf's 0: a split is kept when it,
 * together with the best of the splits below it, is worth making, and the kept splits form
 * the subtree with the highest sum of worths. So a dear split (an ant's body from its head)
 * is kept when worthwhile ones below it (its legs) make up for it, and no split is kept, or
 * dropped, because of what happens in another branch.
 *
 * \param[in] worth  per node, its split's worth (splitWorth(); ignored for a leaf)
 * \param[in] left, right  per node, its children, -1 for a leaf
 * \return per node, whether its split is kept (false for a leaf and below a dropped split) */
std::vector<bool> shortCutKeep(const std::vector<double>& worth, const std::vector<int>& left,
                               const std::vector<int>& right);

} // namespace pcl_ncut_seg
