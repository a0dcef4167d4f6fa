// The count rule bottom-up from the refined supernodes (see core/cut/part_merge.h).
#include "core/cut/part_merge.h"

#include <algorithm>
#include <iterator>
#include <map>
#include <set>
#include <utility>

namespace pcl_ncut_seg {

namespace {
using Pair = std::pair<std::uint32_t, std::uint32_t>; // two clusters, smaller id first

/// G_s's vertices of a part: r_i and m_i of each of its supernodes (sorted, as they are).
std::vector<std::uint32_t> verticesOf(const std::vector<std::uint32_t>& supernodes, std::size_t l) {
  std::vector<std::uint32_t> v(supernodes);
  for (std::uint32_t s : supernodes)
    v.push_back(static_cast<std::uint32_t>(l + s));
  return v;
}

std::vector<std::uint32_t> joined(const std::vector<std::uint32_t>& a,
                                  const std::vector<std::uint32_t>& b) {
  std::vector<std::uint32_t> out;
  std::merge(a.begin(), a.end(), b.begin(), b.end(), std::back_inserter(out));
  return out;
}

/// Every merge, weakest boundary first, until one part is left. Clusters 0..l-1 are the
/// supernodes, cluster l + k the one merge k made.
struct MergeSequence {
  struct Merge {
    std::uint32_t a, b;
    double ncut;
  };
  std::vector<std::vector<std::uint32_t>> members; ///< per cluster, its supernodes (sorted)
  std::vector<Merge> merges;
};

/// The touching pairs of supernodes: those an edge of G_s joins (r_i stands for s_i too).
std::set<Pair> touchingSupernodes(const WeightedGraph& graph, std::size_t l) {
  auto supernodeOf = [l](std::uint32_t v) { return v < l ? v : static_cast<std::uint32_t>(v - l); };
  std::set<Pair> touching;
  for (const auto& e : graph.edges) {
    const std::uint32_t a = supernodeOf(e.a), b = supernodeOf(e.b);
    if (a != b && e.w > 0.0)
      touching.emplace(std::min(a, b), std::max(a, b));
  }
  return touching;
}

/// The touching pairs after clusters x and y merged into c.
std::set<Pair> afterMerge(const std::set<Pair>& touching, std::uint32_t x, std::uint32_t y,
                          std::uint32_t c) {
  std::set<Pair> next;
  for (const auto& [a, b] : touching) {
    const bool in_a = a == x || a == y, in_b = b == x || b == y;
    if (in_a && in_b)
      continue;
    if (in_a || in_b)
      next.emplace(in_a ? b : a, c); // c is the newest cluster: the larger id
    else
      next.emplace(a, b);
  }
  return next;
}

/// Parts that touch no other merge last, at NCut 0, as a bisection splits a disconnected
/// subset first: the last two (by smallest supernode) first, so that the root's split is the
/// first part against the rest.
void joinUntouched(MergeSequence& seq) {
  std::vector<bool> merged(seq.members.size(), false);
  for (const auto& m : seq.merges)
    merged[m.a] = merged[m.b] = true;
  std::vector<std::uint32_t> roots;
  for (std::uint32_t c = 0; c < seq.members.size(); ++c)
    if (!merged[c])
      roots.push_back(c);
  std::sort(roots.begin(), roots.end(), [&](std::uint32_t a, std::uint32_t b) {
    return seq.members[a].front() < seq.members[b].front();
  });
  for (std::size_t i = roots.size(); i-- > 1;) {
    const std::uint32_t rest = roots[i], first = roots[i - 1];
    roots[i - 1] = static_cast<std::uint32_t>(seq.members.size());
    seq.members.push_back(joined(seq.members[first], seq.members[rest]));
    seq.merges.push_back({first, rest, 0.0});
  }
}

MergeSequence mergeAll(const WeightedGraph& graph, std::size_t l, const BoundaryWorthFn& worth) {
  MergeSequence seq;
  for (std::uint32_t s = 0; s < l; ++s)
    seq.members.push_back({s});
  std::set<Pair> touching = touchingSupernodes(graph, l);
  std::map<Pair, std::pair<double, double>> measured; // per pair: worth, NCut
  std::vector<bool> in_a(graph.num_vertices, false);
  auto measure = [&](const Pair& p) {
    if (auto it = measured.find(p); it != measured.end())
      return it->second;
    const std::vector<std::uint32_t>& a = seq.members[p.first];
    for (std::uint32_t s : a)
      in_a[s] = in_a[l + s] = true;
    const double ncut = normalizedCut(graph, verticesOf(joined(a, seq.members[p.second]), l), in_a);
    for (std::uint32_t s : a)
      in_a[s] = in_a[l + s] = false;
    return measured[p] = {worth(a, seq.members[p.second], ncut), ncut};
  };
  while (!touching.empty()) {
    // The weakest boundary; ties go to the first pair in id order (deterministic).
    Pair pick = *touching.begin();
    std::pair<double, double> weakest = measure(pick);
    for (const Pair& p : touching)
      if (const auto m = measure(p); m.first < weakest.first) {
        weakest = m;
        pick = p;
      }
    const auto c = static_cast<std::uint32_t>(seq.members.size());
    seq.members.push_back(joined(seq.members[pick.first], seq.members[pick.second]));
    seq.merges.push_back({pick.first, pick.second, weakest.second});
    touching = afterMerge(touching, pick.first, pick.second, c);
  }
  joinUntouched(seq);
  return seq;
}

/// The hierarchy of the clusters left after `stop` merges: the later merges are its splits,
/// the last one at the root.
class TreeBuilder {
public:
  TreeBuilder(const MergeSequence& seq, std::size_t l, std::size_t stop)
      : seq_(seq), l_(l), stop_(stop) {}

  Hierarchy build() {
    addCluster(static_cast<std::uint32_t>(seq_.members.size() - 1), -1); // the whole
    return std::move(h_);
  }

private:
  int addNode(const std::vector<std::uint32_t>& supernodes, int parent, bool has_split,
              double ncut) {
    Hierarchy::Node node;
    node.vertices = verticesOf(supernodes, l_);
    std::sort(node.vertices.begin(), node.vertices.end());
    node.parent = parent;
    node.has_split = has_split;
    node.ncut = ncut;
    h_.nodes.push_back(std::move(node));
    return static_cast<int>(h_.nodes.size() - 1);
  }

  int addCluster(std::uint32_t c, int parent) {
    const bool is_merge = c >= l_;
    const std::size_t k = is_merge ? c - l_ : 0;
    const int id = addNode(seq_.members[c], parent, is_merge, is_merge ? seq_.merges[k].ncut : 0.0);
    if (is_merge && k >= stop_) { // undone: a split, its left child holds the smaller vertex
      std::uint32_t left = seq_.merges[k].a, right = seq_.merges[k].b;
      if (seq_.members[right].front() < seq_.members[left].front())
        std::swap(left, right);
      const int li = addCluster(left, id);
      const int ri = addCluster(right, id);
      h_.nodes[id].left = li;
      h_.nodes[id].right = ri;
    }
    return id;
  }

  const MergeSequence& seq_;
  std::size_t l_, stop_;
  Hierarchy h_;
};
} // namespace

Hierarchy mergeParts(const WeightedGraph& graph, std::size_t l, const BoundaryWorthFn& worth,
                     int parts) {
  if (l == 0)
    return Hierarchy();
  const MergeSequence seq = mergeAll(graph, l, worth);
  // Each merge leaves one part fewer: after s merges, l - s parts.
  const std::size_t asked = static_cast<std::size_t>(std::max(parts, 1));
  const std::size_t stop = l > asked ? std::min(l - asked, seq.merges.size()) : 0;
  return TreeBuilder(seq, l, stop).build();
}

} // namespace pcl_ncut_seg
