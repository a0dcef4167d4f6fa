/*
 * pcl_ncut_seg: supernode extraction with saddles and the 0.3 rule (Sec. 4.2).
 */
#pragma once

#include "core/graph/csr_graph.h"

#include <cstdint>
#include <limits>
#include <utility>
#include <vector>

namespace pcl_ncut_seg {

constexpr std::uint32_t kNone = std::numeric_limits<std::uint32_t>::max();

/** \brief A set of supernodes and the saddle relations between them.
 *
 * A supernode is either born at a local maximum of f (saddle == kNone) or created at a saddle
 * point, where the supernodes in children[] terminate (Fig. 6). parent[s] is the supernode
 * created at the saddle where s terminates (kNone if s never meets another).
 */
struct Supernodes {
  std::vector<std::uint32_t> label;  ///< per point, its supernode
  std::vector<std::uint32_t> origin; ///< per supernode, its local maximum or saddle point
  std::vector<bool> at_saddle;       ///< per supernode, created at a saddle point
  std::vector<std::uint32_t> parent; ///< per supernode, see above
  std::vector<std::vector<std::uint32_t>> children; ///< per supernode, see above

  std::size_t size() const { return origin.size(); }
  std::vector<std::uint32_t> localMaxima() const; ///< points where a supernode was born
  std::vector<std::uint32_t> saddles() const;     ///< points where a supernode was created
};

/** \brief Extract supernodes (Sec. 4.2) by processing points in descending f.
 *
 * Ties in f are broken by index (lower index first), so a point is a local maximum iff it
 * precedes all its neighbours in that order. For each other point p, M(p) holds its processed
 * neighbours; supernodes with fewer than crossing_fraction * |N(p)| of them are dropped as
 * reached through feature-crossing edges (rule (b)); one remaining supernode takes p (c), more
 * than one make p a saddle and create a new supernode (d) to which the merged ones redirect.
 * When rule (b) drops every supernode (the text gives no rule), p follows its steepest ascent:
 * the supernode of argmax_{q in M(p)} z(p, q).
 *
 * \param[in] graph              kNN graph; N(p) is p's neighbourhood in it
 * \param[in] f                  centrality per point
 * \param[in] crossing_fraction  the fraction of rule (b), 0.3 in the paper
 */
Supernodes extractSupernodes(const CsrGraph& graph, const std::vector<float>& f,
                             float crossing_fraction);

/** \brief Compact ids for labels, numbered in order of each label's first point (by index).
 *
 * \param[in]  label       per point, its label, in [0, num_labels)
 * \param[in]  num_labels  how many labels there may be (some may be carried by no point)
 * \param[out] id          per label, its compact id; kNone for a label no point carries
 * \param[out] compact     per point, its label's compact id (id[label[p]])
 * \return per compact id, its first point (its size is the number of compact ids) */
std::vector<std::uint32_t> compactLabels(const std::vector<std::uint32_t>& label,
                                         std::size_t num_labels, std::vector<std::uint32_t>& id,
                                         std::vector<std::uint32_t>& compact);

/** \brief Segments joined into groups, as the merges after the cut make them.
 *
 * \param[in]     group         per segment, its group, named by one of its segments
 * \param[in,out] segment       per vertex, its segment; on output its group's compact id,
 *                              numbered in order of each group's smallest segment
 * \param[out]    num_segments  the number of groups
 * \return per segment, its group's compact id */
std::vector<std::uint32_t> joinGroups(const std::vector<std::uint32_t>& group,
                                      std::vector<std::uint32_t>& segment,
                                      std::size_t& num_segments);

/** \brief Supernodes renumbered with compact ids in order of each one's first point (by
 * index), as refineSupernodes() and splitAtCreases() return them; those no point is in are
 * dropped.
 *
 * \param[in] sn  label, origin, at_saddle and parent (children are not read); a parent no
 *                point is in becomes kNone
 * \return the renumbered supernodes, each one's children in ascending id */
Supernodes renumberSupernodes(const Supernodes& sn);

/** \brief A vote among supernode labels, e.g. those of a point's neighbours, for where the
 * point should go: the label cast most often wins, ties go to the smaller label. Few distinct
 * labels are expected, so they are kept in a short list. */
class LabelVote {
public:
  void clear() { counts_.clear(); }
  void add(std::uint32_t label) {
    for (auto& c : counts_)
      if (c.first == label) {
        ++c.second;
        return;
      }
    counts_.emplace_back(label, 1);
  }
  /// The winning label; kNone when no vote was cast.
  std::uint32_t winner() const {
    std::uint32_t best = kNone, best_count = 0;
    for (const auto& c : counts_)
      if (c.second > best_count || (c.second == best_count && c.first < best)) {
        best = c.first;
        best_count = c.second;
      }
    return best;
  }

private:
  std::vector<std::pair<std::uint32_t, std::uint32_t>> counts_;
};

} // namespace pcl_ncut_seg
