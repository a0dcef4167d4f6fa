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

/** \brief The short-cut rule over a best-first sequence of splits: the worth of split j is
 * log(bound / (max(ncut_j, floor) * max(neck_j, 1)^exponent)), and the first `keep` splits
 * are kept where the running sum of worths is highest (0 when no prefix has a positive sum).
 * A prefix rather than a threshold, so that splits that are not worth much by themselves
 * (separating an ant's body from its head) are kept when clearly worthwhile ones (its legs)
 * follow. */
std::size_t shortCutKeep(const std::vector<double>& ncuts, const std::vector<double>& necks,
                         double exponent, double bound, double floor);

} // namespace pcl_ncut_seg
