/*
 * The count rule bottom-up (core/cut/part_merge.h): the weakest boundaries merge first, and
 * the hierarchy it returns is a tree of the parts left.
 */
#include "core/cut/part_merge.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <vector>

using namespace pcl_ncut_seg;

namespace {

// l supernodes: r_i - m_i at weight 1, members joined by the given (i, j, w) links.
WeightedGraph chain(std::size_t l, const std::vector<std::tuple<int, int, double>>& links) {
  WeightedGraph g;
  g.num_vertices = 2 * l;
  for (std::uint32_t i = 0; i < l; ++i)
    g.edges.push_back({i, static_cast<std::uint32_t>(l + i), 1.0});
  for (const auto& [i, j, w] : links)
    g.edges.push_back({static_cast<std::uint32_t>(l + i), static_cast<std::uint32_t>(l + j), w});
  return g;
}

// A boundary is worth the less, the more strongly its two sides are joined.
const BoundaryWorthFn kByNcut = [](const std::vector<std::uint32_t>&,
                                   const std::vector<std::uint32_t>&,
                                   double ncut) { return -ncut; };

// Per leaf (in leaves() order), its supernodes.
std::vector<std::vector<std::uint32_t>> parts(const Hierarchy& h, std::size_t l) {
  std::vector<std::vector<std::uint32_t>> out;
  for (int leaf : h.leaves()) {
    out.emplace_back();
    for (std::uint32_t v : h.nodes[leaf].vertices)
      if (v >= l)
        out.back().push_back(static_cast<std::uint32_t>(v - l));
  }
  return out;
}

// Every split's children divide it; the root holds every vertex.
void expectTree(const Hierarchy& h, std::size_t num_vertices) {
  ASSERT_FALSE(h.nodes.empty());
  EXPECT_EQ(h.nodes[0].vertices.size(), num_vertices);
  EXPECT_EQ(h.nodes[0].parent, -1);
  for (std::size_t i = 0; i < h.nodes.size(); ++i) {
    const Hierarchy::Node& n = h.nodes[i];
    if (n.left < 0) {
      EXPECT_LT(n.right, 0);
      continue;
    }
    EXPECT_TRUE(n.has_split);
    EXPECT_EQ(h.nodes[n.left].parent, static_cast<int>(i));
    EXPECT_EQ(h.nodes[n.right].parent, static_cast<int>(i));
    std::vector<std::uint32_t> both;
    std::merge(h.nodes[n.left].vertices.begin(), h.nodes[n.left].vertices.end(),
               h.nodes[n.right].vertices.begin(), h.nodes[n.right].vertices.end(),
               std::back_inserter(both));
    EXPECT_EQ(both, n.vertices);
    EXPECT_LT(h.nodes[n.left].vertices.front(), h.nodes[n.right].vertices.front());
  }
}

} // namespace

TEST(PartMerge, TheStrongestBoundariesAreKept) {
  // 0 - 1 strongly, 1 - 2 weakly, 2 - 3 moderately, 3 - 4 strongly.
  const WeightedGraph g = chain(5, {{0, 1, 1.0}, {1, 2, 0.01}, {2, 3, 0.2}, {3, 4, 1.0}});
  const Hierarchy two = mergeParts(g, 5, kByNcut, 2);
  expectTree(two, 10);
  EXPECT_EQ(parts(two, 5), (std::vector<std::vector<std::uint32_t>>{{0, 1}, {2, 3, 4}}));
  const Hierarchy three = mergeParts(g, 5, kByNcut, 3);
  expectTree(three, 10);
  EXPECT_EQ(parts(three, 5), (std::vector<std::vector<std::uint32_t>>{{0, 1}, {2}, {3, 4}}));
  // The root's split is the strongest boundary, 1 | 2, at the NCut of the whole chain's split
  // there: asso({0, 1}) = 2 + 2 + 2 + 0.01, asso({2, 3, 4}) = 2 + 0.4 + 2 + 2 + 2 + 0.01.
  EXPECT_EQ(three.nodes[0].left, 1);
  EXPECT_NEAR(three.nodes[0].ncut, 0.01 / (6 + 0.01) + 0.01 / (8.4 + 0.01), 1e-9);
  // One part: the whole; as many parts as supernodes or more: one part per supernode.
  EXPECT_EQ(mergeParts(g, 5, kByNcut, 1).leaves().size(), 1u);
  for (int n : {5, 6, 100}) {
    const Hierarchy h = mergeParts(g, 5, kByNcut, n);
    expectTree(h, 10);
    EXPECT_EQ(h.leaves().size(), 5u);
  }
}

TEST(PartMerge, TheWorthIsMeasuredOnTheTwoPartsAlone) {
  // A triangle of supernodes: the worth of merging {0} and {1} sees only their own edges.
  const WeightedGraph g = chain(3, {{0, 1, 0.5}, {1, 2, 0.5}, {0, 2, 0.5}});
  bool seen = false;
  const BoundaryWorthFn record = [&seen](const std::vector<std::uint32_t>& a,
                                         const std::vector<std::uint32_t>& b, double ncut) {
    if (a == std::vector<std::uint32_t>{0} && b == std::vector<std::uint32_t>{1}) {
      seen = true;
      EXPECT_NEAR(ncut, 2 * 0.5 / 2.5, 1e-12); // cut 0.5 over asso 2 + 0.5 either side
    }
    return -ncut;
  };
  mergeParts(g, 3, record, 1);
  EXPECT_TRUE(seen);
}

TEST(PartMerge, PartsThatTouchNoOtherMergeLast) {
  // Two components, {0, 1} and {2, 3}: asked for two parts, the components, split at NCut 0.
  const WeightedGraph g = chain(4, {{0, 1, 1.0}, {2, 3, 1.0}});
  const Hierarchy two = mergeParts(g, 4, kByNcut, 2);
  expectTree(two, 8);
  EXPECT_EQ(parts(two, 4), (std::vector<std::vector<std::uint32_t>>{{0, 1}, {2, 3}}));
  EXPECT_EQ(two.nodes[0].ncut, 0.0);
  // One part: the whole, never more than asked for.
  EXPECT_EQ(mergeParts(g, 4, kByNcut, 1).leaves().size(), 1u);
  // Three parts: the two components and one of them split.
  EXPECT_EQ(mergeParts(g, 4, kByNcut, 3).leaves().size(), 3u);
  // Three components, 0 - 1, 2 and 3: the root splits the first from the rest.
  const WeightedGraph lone = chain(4, {{0, 1, 1.0}});
  const Hierarchy h = mergeParts(lone, 4, kByNcut, 3);
  expectTree(h, 8);
  EXPECT_EQ(parts(h, 4), (std::vector<std::vector<std::uint32_t>>{{0, 1}, {2}, {3}}));
  EXPECT_EQ(h.nodes[h.nodes[0].left].vertices, (std::vector<std::uint32_t>{0, 1, 4, 5}));
  EXPECT_EQ(parts(mergeParts(lone, 4, kByNcut, 2), 4),
            (std::vector<std::vector<std::uint32_t>>{{0, 1}, {2, 3}}));
}

TEST(PartMerge, NoSupernodesNoHierarchy) {
  EXPECT_TRUE(mergeParts(WeightedGraph(), 0, kByNcut, 3).nodes.empty());
}
