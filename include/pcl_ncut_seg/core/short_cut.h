/*
 * pcl_ncut_seg: the short-cut stopping rule, an automatic stopping rule for the hierarchy of
 * Sec. 5.2. People cut a shape into parts along short boundaries (the short-cut rule of
 * perception: a finger or a leg is cut off across its narrow base), while a piece chipped off
 * a flat wall or a cup has a long boundary for its size. The rule weighs each best-first
 * split's NCut by how long its boundary is relative to the size of its smaller side.
 */
#pragma once

#include <pcl_ncut_seg/core/csr_graph.h>

#include <cstdint>
#include <vector>

namespace pcl_ncut_seg {

/** \brief Measures the neck of splits of the supernodes: the boundary's length over the
 * square root of the smaller side's area, both estimated from the kNN graph (each point
 * stands for a disc of radius r(p), the mean length of its kNN edges). Dimensionless: about
 * 2 pi w / sqrt(2 pi w h) for a limb of width w and length h cut at its base, about 4 or more
 * for a square patch cut out of a flat region. */
class NeckMeasure {
public:
  /** \param[in] graph  the kNN graph (edge lengths)
   * \param[in] label  per vertex, its supernode
   * \param[in] num_supernodes  number of supernodes */
  NeckMeasure(const CsrGraph& graph, const std::vector<std::uint32_t>& label,
              std::size_t num_supernodes);

  /** \brief side[s]: 0 or 1 for the supernodes of the two sides of a split, negative for
   * supernodes outside the split part. Returns the boundary length (the mean of the two sides'
   * sum of 2 r(p) over points with a kNN neighbour on the other side) over sqrt of the smaller
   * side's area (sum of pi r(p)^2); 0 when the sides do not touch or a side has no area. */
  double neck(const std::vector<std::int8_t>& side) const;

private:
  std::vector<double> area_; ///< per supernode, sum of pi r(p)^2
  // Points with a kNN neighbour in another supernode: their supernode, 2 r(p), and the other
  // supernodes among their neighbours (CSR).
  std::vector<std::uint32_t> border_label_;
  std::vector<double> border_length_;
  std::vector<std::uint32_t> border_offsets_, border_neighbours_;
};

/** \brief The worth of a split under the short-cut rule:
 * log(bound / (max(ncut, floor) * max(neck, 1)^exponent)); positive when the split is worth
 * making by itself. */
double splitWorth(double ncut, double neck, double exponent, double bound, double floor);

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
