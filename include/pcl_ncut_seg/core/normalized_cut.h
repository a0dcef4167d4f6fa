/*
 * pcl_ncut_seg: normalized-cut bisection (Sec. 5.2, eqs. 5, 6, 10) and the hierarchy.
 */
#pragma once

#include <pcl_ncut_seg/core/supernode_graph.h>

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

/** \brief Cut parameters of the hierarchy. */
struct CutParams {
  double threshold = 0.1;  ///< split while the best NCut <= threshold
  int num_segments = 0;    ///< > 0: instead split the lowest-NCut leaf until this many leaves
  int num_splits = 100;    ///< uniform split values tried per bisection
  /// Threshold mode only: a split is accepted only if each side holds at least this fraction
  /// of the total mass (WeightedGraph::mass, feature area); 0 = the paper (no such rule).
  double min_segment_fraction = 0.0;
  /// Threshold mode only, an automatic stopping rule: split the lowest-NCut part first (as
  /// with num_segments) while the NCut is at most the threshold and at most max_segments
  /// parts exist, then keep the splits up to the largest relative jump of the NCut
  /// (log scale). The NCut's scale differs from model to model by orders of magnitude; its
  /// jump does not. false = the paper (recursive bisection while NCut <= threshold).
  bool largest_gap = true;
  int max_segments = 20; ///< upper bound on the parts for largest_gap
  double gap_floor = 3e-3; ///< largest_gap: NCuts below this count as this (no jump among them)
  /// largest_gap, with a neck measure given to buildHierarchy(): the short-cut rule
  /// (core/short_cut.h) replaces the largest jump: split j is worth
  /// log(neck_bound / (max(NCut_j, neck_floor) * max(neck_j, 1)^neck_exponent)) and the
  /// best-first splits are kept up to the highest running sum of worths. 0 = the largest gap.
  double neck_exponent = 3.0;
  double neck_bound = 0.25; ///< short-cut rule: a split is worth making below this weighted NCut
  double neck_floor = 1e-3; ///< short-cut rule: NCuts below this count as this
};

/** \brief Per split of the hierarchy, its neck (core/short_cut.h): called with the two sides'
 * vertex ids of G_s. */
using SplitNeckFn =
    std::function<double(const std::vector<std::uint32_t>&, const std::vector<std::uint32_t>&)>;

Hierarchy buildHierarchy(const WeightedGraph& graph, std::size_t num_supernodes,
                         const CutParams& params, const SplitNeckFn& split_neck = nullptr);

} // namespace pcl_ncut_seg
