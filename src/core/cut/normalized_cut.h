/*
 * pcl_ncut_seg: normalized-cut bisection (Sec. 5.2, eqs. 5, 6, 10) and the hierarchy.
 */
#pragma once

#include <pcl_ncut_seg/parameters.h>

#include "core/cut/supernode_graph.h"

#include <cstdint>
#include <functional>
#include <vector>

namespace pcl_ncut_seg {

/** \brief NCut(V1, V2) = cut/asso(V1, V) + cut/asso(V2, V) (eq. 5, corrected as in Shi and
 * Malik). in_v1[v] says which side v is on; vertices outside `subset` are ignored. */
double normalizedCut(const WeightedGraph& graph, const std::vector<std::uint32_t>& subset,
                     const std::vector<bool>& in_v1);

/** \brief A bisection of a vertex subset. */
struct Bisection {
  bool valid = false;            ///< false: the subset cannot be split
  double ncut = 0.0;             ///< NCut of the split
  std::vector<std::uint32_t> v1; ///< side holding the subset's smallest vertex
  std::vector<std::uint32_t> v2;
};

/** \brief Bisect `subset` (sorted) of the graph. Both sides must hold a member vertex
 * (id >= num_supernodes). A disconnected subset is split along its components at NCut 0 (the
 * component of the smallest member vertex against the rest). Otherwise the Fiedler vector y
 * of (D - W) y = lambda D y (eq. 10) is split at the best of `num_splits` uniform values between
 * min y and max y.
 */
Bisection bisect(const WeightedGraph& graph, std::size_t num_supernodes,
                 const std::vector<std::uint32_t>& subset, int num_splits);

/// Sec. 5.2 leaves the number of uniform split values open; 100 places the split within 1% of
/// the eigenvector's range, finer than the supernodes resolve on any model we measured.
constexpr int kSplitValues = 100;

/** \brief The binary tree of bisections (Sec. 5.2). Node 0 is the root (all vertices). */
struct Hierarchy {
  struct Node {
    std::vector<std::uint32_t> vertices; ///< sorted vertex ids of G_s
    double ncut = 0.0;                   ///< NCut of this node's best bisection (if has_split)
    bool has_split = false;              ///< a bisection exists
    int left = -1, right = -1;           ///< children when split (accepted), else -1
    int parent = -1;
  };
  std::vector<Node> nodes;
  std::vector<int> leaves() const; ///< leaf node ids, in order of their smallest vertex
};

/** \brief Per split of the hierarchy, its neck (core/cut/short_cut.h): called with the two sides'
 * vertex ids of G_s. */
using SplitNeckFn =
    std::function<double(const std::vector<std::uint32_t>&, const std::vector<std::uint32_t>&)>;

/** \brief The hierarchy top-down under the threshold rule or the short-cut rule (the count rule
 * is bottom-up: core/cut/part_merge.h; here it reads as the threshold rule). The short-cut rule
 * weighs each split by its neck from `split_neck`; without one, by its NCut alone (every neck
 * counts as 0). */
Hierarchy buildHierarchy(const WeightedGraph& graph, std::size_t num_supernodes,
                         const StoppingParams& params, const SplitNeckFn& split_neck = nullptr);

} // namespace pcl_ncut_seg
