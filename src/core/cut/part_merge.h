/*
 * pcl_ncut_seg: the count rule bottom-up. The finest level of the hierarchy of Sec. 5.2 is the
 * refined supernodes, and the boundaries people draw are among theirs; what a count must choose
 * is which of them to keep. Starting from the supernodes, the two touching parts whose common
 * boundary is worth least merge, by the worth the short-cut rule gives a split (its NCut and
 * its neck, core/cut/short_cut.h) measured on the two parts alone, until the count is left:
 * the N - 1 weakest merges undone are the N strongest boundaries kept.
 */
#pragma once

#include "core/cut/normalized_cut.h"

#include <cstdint>
#include <functional>
#include <vector>

namespace pcl_ncut_seg {

/** \brief A boundary's worth: for two touching parts (their supernode ids, sorted) and the NCut
 * of the split between them in G_s restricted to the two, how much the boundary is worth keeping
 * (higher: stronger). */
using BoundaryWorthFn = std::function<double(const std::vector<std::uint32_t>&,
                                             const std::vector<std::uint32_t>&, double ncut)>;

/** \brief Merge the supernodes bottom-up, weakest boundary first, until `parts` are left.
 *
 * Parts touch when an edge of G_s joins them. Parts that touch no other merge last, at NCut 0,
 * as a bisection splits a disconnected subset first. Fewer than `parts` are left only when there
 * are fewer supernodes.
 * \param[in] graph  G_s over 2 l vertices (r_i = i, m_i = l + i)
 * \param[in] num_supernodes  l
 * \param[in] worth  a boundary's worth
 * \param[in] parts  the number of parts asked for (>= 1)
 * \return the hierarchy: its leaves the parts left; its splits the merges from the last one (at
 * the root) back to the one that left `parts`, each with the NCut of its pair. */
Hierarchy mergeParts(const WeightedGraph& graph, std::size_t num_supernodes,
                     const BoundaryWorthFn& worth, int parts);

} // namespace pcl_ncut_seg
