/*
 * pcl_ncut_seg: the cut's intermediate results as plain public types. SupernodeGraph is the
 * supernode graph G_s of Sec. 5.1 (its vertices and weighted edges); SegmentTree the hierarchy
 * of normalized-cut bisections over it (Sec. 5.2), each part with the NCut of its best
 * bisection. Both are copies of the core's (private) types, made after a cut
 * (SupernodeNCutSegmentation::getSupernodeGraph() and getHierarchy(), PointSegmenter).
 */
#pragma once

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <vector>

namespace pcl_ncut_seg {

/** \brief The supernode graph G_s (Sec. 5.1) over the l refined supernodes: two vertices per
 * supernode i, its feature vertex r_i = i and its member vertex m_i = l + i; the edges r_i - m_i
 * weigh its features (eq. (7)), the edges m_i - m_j the similarity of two touching supernodes
 * (eq. (9)). */
struct SupernodeGraph {
  /** \brief One undirected edge. */
  struct Edge {
    std::uint32_t source = 0; ///< a vertex, in [0, num_vertices)
    std::uint32_t target = 0; ///< the other vertex
    double weight = 0.0;      ///< its weight, >= 0
  };
  std::size_t num_supernodes = 0; ///< l
  std::size_t num_vertices = 0;   ///< 2 l
  std::vector<Edge> edges;

  /** \brief Whether a vertex is a member vertex m_i (else a feature vertex r_i).
   * \param[in] vertex  in [0, num_vertices) */
  bool isMember(std::uint32_t vertex) const { return vertex >= num_supernodes; }
  /** \brief The supernode i of a vertex (r_i or m_i).
   * \param[in] vertex  in [0, num_vertices) */
  std::uint32_t supernode(std::uint32_t vertex) const {
    return isMember(vertex) ? vertex - static_cast<std::uint32_t>(num_supernodes) : vertex;
  }
};

/** \brief The hierarchy of bisections (Sec. 5.2): node 0 holds every vertex of G_s, and a split
 * node's two children divide its vertices between them. The leaves are the parts the cut kept;
 * their supernodes make up the segments (which the end of the pipeline may still merge:
 * supernode_segment says where each supernode ended). Empty before a cut. */
struct SegmentTree {
  /** \brief One part of the hierarchy. */
  struct Node {
    int parent = -1; ///< its parent node, -1 for the root
    int left = -1;   ///< its first child, -1 for a leaf
    int right = -1;  ///< its second child, -1 for a leaf
    /// The NCut of the node's best bisection (the one its children are, if split), in [0, 2];
    /// NaN where no bisection exists (a single supernode).
    double ncut = std::numeric_limits<double>::quiet_NaN();
    std::vector<std::uint32_t> vertices;   ///< its vertices of G_s, sorted
    std::vector<std::uint32_t> supernodes; ///< the supernodes i whose m_i it holds, sorted

    /** \brief Whether the node was not split. */
    bool isLeaf() const { return left < 0; }
  };
  std::vector<Node> nodes;        ///< parents before their children; node 0 is the root
  std::size_t num_supernodes = 0; ///< l, as in SupernodeGraph
  /// Per refined supernode, the segment it ended in (0-based, numbered as extract()'s segments;
  /// -1 for none).
  std::vector<int> supernode_segment;

  /** \brief The leaves, ordered by their smallest vertex. */
  std::vector<int> leaves() const {
    std::vector<int> out;
    for (std::size_t i = 0; i < nodes.size(); ++i)
      if (nodes[i].isLeaf())
        out.push_back(static_cast<int>(i));
    const auto first = [this](int i) {
      return nodes[i].vertices.empty() ? std::numeric_limits<std::uint32_t>::max()
                                       : nodes[i].vertices.front();
    };
    std::sort(out.begin(), out.end(), [&first](int a, int b) { return first(a) < first(b); });
    return out;
  }
};

} // namespace pcl_ncut_seg
