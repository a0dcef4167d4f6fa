// Sec. 4.3: the local refinement that merges insignificant supernodes (refineSupernodes() of
// refinement.h).
#include "core/common/radix_sort.h"
#include "core/supernodes/refinement.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <queue>

namespace pcl_ncut_seg {

namespace {
/// Working copy of the supernodes during refinement, with incrementally merged statistics.
struct Work {
  std::vector<std::uint32_t> label;
  std::vector<bool> alive, at_saddle;
  std::vector<std::uint32_t> origin, parent;
  std::vector<std::vector<std::uint32_t>> children, points;
  std::vector<double> area;
  std::vector<float> fmin, fmax;

  float height(std::uint32_t s) const { return fmax[s] - fmin[s]; }

  std::uint32_t add(std::uint32_t origin_point, bool saddle, std::uint32_t par) {
    const auto s = static_cast<std::uint32_t>(alive.size());
    alive.push_back(true);
    at_saddle.push_back(saddle);
    origin.push_back(origin_point);
    parent.push_back(par);
    children.emplace_back();
    points.emplace_back();
    area.push_back(0.0);
    fmin.push_back(std::numeric_limits<float>::infinity());
    fmax.push_back(-std::numeric_limits<float>::infinity());
    dirty.push_back(1);
    if (par != kNone)
      children[par].push_back(s);
    return s;
  }
  /// Per supernode: may be disconnected, so step 3 must search it. A supernode that loses
  /// points may split; one that gains points next to its own stays connected, so only the
  /// callers that add points not known to touch it set this for the gaining side.
  std::vector<std::uint8_t> dirty;

  void addPoint(std::uint32_t s, std::uint32_t p, const std::vector<float>& f, double a) {
    if (label[p] != kNone)
      dirty[label[p]] = 1;
    label[p] = s;
    points[s].push_back(p);
    area[s] += a;
    fmin[s] = std::min(fmin[s], f[p]);
    fmax[s] = std::max(fmax[s], f[p]);
  }
  void replaceChild(std::uint32_t par, std::uint32_t old_child,
                    const std::vector<std::uint32_t>& with) {
    if (par == kNone)
      return;
    auto& c = children[par];
    c.erase(std::remove(c.begin(), c.end(), old_child), c.end());
    for (std::uint32_t w : with) {
      c.push_back(w);
      parent[w] = par;
    }
    std::sort(c.begin(), c.end());
  }
  /// Merge s into t: s's points join t, s's children terminate at t's place in the tree.
  void mergeInto(std::uint32_t s, std::uint32_t t, const std::vector<float>& f,
                 const std::vector<double>& point_area) {
    for (std::uint32_t p : points[s])
      addPoint(t, p, f, point_area[p]);
    dirty[t] = 1; // s's points need not touch t's
    points[s].clear();
    if (parent[s] == t) {
      replaceChild(t, s, children[s]);
    } else {
      // s leaves its parent; if t was one of s's children, t takes s's place there.
      std::vector<std::uint32_t> moved, heir;
      for (std::uint32_t c : children[s])
        (c == t ? heir : moved).push_back(c);
      if (!heir.empty())
        parent[t] = kNone;
      replaceChild(parent[s], s, heir);
      replaceChild(t, s, moved); // s's other children now terminate at t
    }
    children[s].clear();
    parent[s] = kNone;
    alive[s] = false;
  }
  /// The other supernode that shares most kNN edges with these points (ties: smaller id).
  std::uint32_t bestNeighbour(const CsrGraph& g, const std::vector<std::uint32_t>& pts,
                              std::uint32_t self) const {
    LabelVote vote;
    for (std::uint32_t p : pts)
      for (std::uint32_t e = g.offsets[p]; e < g.offsets[p + 1]; ++e)
        if (label[g.targets[e]] != self)
          vote.add(label[g.targets[e]]);
    return vote.winner();
  }
};

/// Sec. 4.3's local refinement (refineSupernodes()): insignificant supernodes, small or skinny
/// by the thresholds taken before refinement, are merged up, merged down, cut into connected
/// regions and joined to their neighbours, in rounds over the working copy of the supernodes.
struct Refiner {
  const CsrGraph& graph;
  const std::vector<float>& f;
  std::vector<double> point_area; ///< per point, pi r(p)^2
  Work w;
  /// Per connected component of the graph (each is a surface of its own): small is f_a below
  /// small_area (footnote 4), skinny f_h below skinny_height (footnote 5).
  std::vector<std::uint32_t> component;
  std::vector<double> small_area;
  std::vector<float> skinny_height;
  std::vector<std::uint32_t> by_f;      // merge-up: the points of s in descending f
  std::vector<std::uint64_t> sort_keys; // merge-up: by_f's sort keys
  std::vector<std::uint32_t> members;   // merge-up: the points of s
  std::vector<std::uint32_t> slot;      // merge-up: position of a point in by_f
  std::vector<std::uint32_t> kid_index; // merge-up: position of a supernode in kids
  std::vector<std::uint32_t> edge_kid;  // merge-up: per edge of a point, see bestChild()
  static constexpr std::uint32_t kSelf = kNone - 1; // merge-up: edge_kid of a neighbour in s

  Refiner(const CsrGraph& graph, const std::vector<float>& f, const std::vector<float>& radii,
          const Supernodes& input, const RefinementParams& params)
      : graph(graph), f(f), point_area(graph.numVertices()) {
    const std::size_t n = graph.numVertices();
    for (std::size_t p = 0; p < n; ++p)
      point_area[p] = pointArea(radii[p]);
    copyInput(input);
    // Thresholds from the supernodes before refinement (footnotes 4 and 5), per component.
    const std::size_t num_components = connectedComponents(graph, component);
    std::vector<double> total_area(num_components, 0.0);
    skinny_height.assign(num_components, 0.0f);
    for (std::size_t s = 0; s < input.size(); ++s) {
      const std::uint32_t c = component[input.origin[s]];
      total_area[c] += w.area[s];
      skinny_height[c] = std::max(skinny_height[c], w.height(static_cast<std::uint32_t>(s)));
    }
    small_area.resize(num_components);
    for (std::size_t c = 0; c < num_components; ++c) {
      small_area[c] = params.area_fraction * total_area[c];
      skinny_height[c] *= params.height_fraction;
    }
    slot.assign(n, kNone);
  }

  /// The working copy of the input supernodes, with their statistics.
  void copyInput(const Supernodes& input) {
    const std::size_t n = graph.numVertices(), m = input.size();
    w.label.assign(n, kNone);
    for (std::size_t s = 0; s < m; ++s)
      w.add(input.origin[s], input.at_saddle[s], kNone);
    for (std::size_t s = 0; s < m; ++s) {
      w.parent[s] = input.parent[s];
      w.children[s] = input.children[s];
    }
    for (std::uint32_t p = 0; p < n; ++p)
      w.addPoint(input.label[p], p, f, point_area[p]);
    // Sec. 4.2 grows a supernode without children only from points next to its own (nothing
    // is redirected into it), so it starts connected: step 3 searches it only once it changes.
    for (std::size_t s = 0; s < m; ++s)
      w.dirty[s] = w.children[s].empty() ? 0 : 1;
  }

  /// s is small (footnote 4) or skinny (footnote 5) by the thresholds before refinement.
  bool small(std::uint32_t s) const { return w.area[s] < small_area[component[w.origin[s]]]; }
  bool skinny(std::uint32_t s) const { return w.height(s) < skinny_height[component[w.origin[s]]]; }

  /// 1. Merge-up: every small supernode created at a saddle goes back to the supernodes that
  ///    terminate there. Returns whether any did.
  bool mergeUpAll() {
    bool merged = false;
    for (std::uint32_t s = 0; s < w.alive.size(); ++s) {
      if (!w.alive[s] || !w.at_saddle[s] || !small(s) || w.children[s].empty())
        continue;
      merged = true;
      mergeUp(s);
    }
    return merged;
  }

  /// Merge-up of s: its points join its children by growing from them, highest f first; s
  /// is dissolved and its children take its place in the tree.
  void mergeUp(std::uint32_t s) {
    const std::vector<std::uint32_t> kids = w.children[s];
    takePointsByF(s);
    // Per by_f position: 0 pending, 1 scheduled, 2 assigned.
    std::vector<std::uint8_t> state(by_f.size(), 0);
    growIntoChildren(s, kids, state);
    placeUntouched(kids, state);
    w.replaceChild(w.parent[s], s, kids);
    if (w.parent[s] == kNone)
      for (std::uint32_t kid : kids)
        w.parent[kid] = kNone;
    w.children[s].clear();
    w.parent[s] = kNone;
    w.alive[s] = false;
  }

  /// Takes s's points out of s: into by_f in descending f, ties by ascending index (slot[p]
  /// its position there), and into members in s's own order, which follows memory.
  void takePointsByF(std::uint32_t s) {
    // Sorted as one 64-bit key per point (the order of floats as numbers in the high half,
    // the index in the low), so that the sort does not read f at random.
    sort_keys.resize(w.points[s].size());
    for (std::size_t i = 0; i < sort_keys.size(); ++i) {
      const std::uint32_t p = w.points[s][i];
      sort_keys[i] = (std::uint64_t(descendingKey(f[p])) << 32) | p;
    }
    std::sort(sort_keys.begin(), sort_keys.end());
    by_f.resize(sort_keys.size());
    for (std::size_t i = 0; i < sort_keys.size(); ++i)
      by_f[i] = static_cast<std::uint32_t>(sort_keys[i]);
    members.clear();
    members.swap(w.points[s]);
    w.area[s] = 0.0;
    for (std::uint32_t i = 0; i < by_f.size(); ++i)
      slot[by_f[i]] = i;
  }

  /// p has a neighbour in one of the kids (kid_index set).
  bool touchesChild(std::uint32_t p) const {
    for (std::uint32_t e = graph.offsets[p]; e < graph.offsets[p + 1]; ++e) {
      const std::uint32_t t = w.label[graph.targets[e]];
      if (t < kid_index.size() && kid_index[t] != kNone)
        return true;
    }
    return false;
  }

  /// Passes over s's points in by_f order, each point joining the child most of its
  /// neighbours belong to, until a pass changes nothing. Simulated by events: a point is
  /// examined only at its turn in the first pass where it touches a child, so the cost is
  /// linear in the supernode's edges instead of edges times passes.
  void growIntoChildren(std::uint32_t s, const std::vector<std::uint32_t>& kids,
                        std::vector<std::uint8_t>& state) {
    const auto count = static_cast<std::uint32_t>(by_f.size());
    std::priority_queue<std::uint64_t, std::vector<std::uint64_t>, std::greater<>> turns;
    // kid_index[t]: t's position in kids, for one pass over the edges whatever the number of
    // children.
    if (kid_index.size() < w.alive.size())
      kid_index.resize(w.alive.size(), kNone);
    for (std::uint32_t j = 0; j < kids.size(); ++j)
      kid_index[kids[j]] = j;
    std::vector<std::uint32_t> kid_count(kids.size(), 0);
    // Read in s's own order (by_f jumps around memory), then queued in by_f order.
    for (std::uint32_t p : members)
      if (touchesChild(p))
        state[slot[p]] = 1;
    for (std::uint32_t i = 0; i < count; ++i)
      if (state[i] == 1)
        turns.push(i); // pass 0
    while (!turns.empty()) {
      const std::uint64_t turn = turns.top();
      turns.pop();
      const std::uint64_t pass = turn >> 32;
      const auto i = static_cast<std::uint32_t>(turn);
      const std::uint32_t p = by_f[i];
      const std::uint32_t best = kids[bestChild(s, p, kids, kid_count)];
      // A child neighbour never leaves: best is set, and stays connected.
      w.addPoint(best, p, f, point_area[p]);
      state[i] = 2;
      const std::uint32_t b = graph.offsets[p], deg = graph.offsets[p + 1] - b;
      for (std::uint32_t k = 0; k < deg; ++k) {
        const std::uint32_t q = graph.targets[b + k];
        if (edge_kid[k] != kSelf || state[slot[q]] != 0)
          continue;
        state[slot[q]] = 1;
        turns.push(((slot[q] > i ? pass : pass + 1) << 32) | slot[q]);
      }
    }
    for (std::uint32_t kid : kids)
      kid_index[kid] = kNone;
  }

  /// The position in kids of the child most of p's neighbours belong to, ties to the first.
  /// One read of the neighbours' labels (the memory-bound part), kept in edge_kid: a
  /// neighbour's position in kids, kSelf when it is still in s, kNone otherwise. Assigning p
  /// changes only p's label, so the cached labels stay exact for growIntoChildren().
  std::uint32_t bestChild(std::uint32_t s, std::uint32_t p, const std::vector<std::uint32_t>& kids,
                          std::vector<std::uint32_t>& kid_count) {
    const std::uint32_t b = graph.offsets[p], deg = graph.offsets[p + 1] - b;
    edge_kid.resize(deg);
    for (std::uint32_t k = 0; k < deg; ++k) {
      const std::uint32_t t = w.label[graph.targets[b + k]];
      const std::uint32_t j = t < kid_index.size() ? kid_index[t] : kNone;
      edge_kid[k] = t == s ? kSelf : j;
      if (j != kNone)
        ++kid_count[j];
    }
    std::uint32_t best_j = kNone, best_count = 0;
    for (std::uint32_t k = 0; k < deg; ++k) {
      const std::uint32_t j = edge_kid[k];
      if (j >= kids.size())
        continue;
      const std::uint32_t c = kid_count[j];
      if (c > best_count || (c == best_count && j < best_j)) {
        best_j = j;
        best_count = c;
      }
    }
    for (std::uint32_t k = 0; k < deg; ++k)
      if (edge_kid[k] < kids.size())
        kid_count[edge_kid[k]] = 0;
    return best_j;
  }

  /// Points that never touch a child: the largest child takes them; step 3 re-tests them.
  void placeUntouched(const std::vector<std::uint32_t>& kids,
                      const std::vector<std::uint8_t>& state) {
    std::vector<std::uint32_t> pending;
    for (std::uint32_t i = 0; i < by_f.size(); ++i) {
      if (state[i] != 2)
        pending.push_back(by_f[i]);
      slot[by_f[i]] = kNone;
    }
    std::uint32_t largest = kids.front();
    for (std::uint32_t kid : kids)
      if (w.area[kid] > w.area[largest])
        largest = kid;
    for (std::uint32_t p : pending)
      w.addPoint(largest, p, f, point_area[p]);
    if (!pending.empty())
      w.dirty[largest] = 1;
  }

  /// 2. Merge-down: a skinny supernode, or a small one not merged up, that terminates at a
  ///    saddle joins the supernode created there. Returns whether any did.
  bool mergeDown() {
    bool merged = false;
    for (std::uint32_t s = 0; s < w.alive.size(); ++s)
      if (w.alive[s] && w.parent[s] != kNone && (skinny(s) || small(s))) {
        w.mergeInto(s, w.parent[s], f, point_area);
        merged = true;
      }
    return merged;
  }

  /// 3. Disconnected regions: in each supernode that may be disconnected, all regions but the
  ///    largest are re-tested. Returns whether any supernode was.
  bool splitDisconnected() {
    bool changed = false;
    std::vector<std::uint32_t> region(graph.numVertices(), kNone);
    const std::size_t before_regions = w.alive.size();
    for (std::uint32_t s = 0; s < before_regions; ++s) {
      // Only a supernode marked dirty can be disconnected (see Work::dirty): most are not.
      if (!w.alive[s] || w.points[s].empty() || !w.dirty[s])
        continue;
      w.dirty[s] = 0;
      std::vector<std::vector<std::uint32_t>> regions = regionsOf(s, region);
      if (regions.size() < 2)
        continue;
      changed = true;
      std::size_t keep = 0;
      for (std::size_t r = 1; r < regions.size(); ++r)
        if (regions[r].size() > regions[keep].size())
          keep = r;
      // Rebuild s from the kept region, then place the others.
      w.points[s].clear();
      w.area[s] = 0.0;
      w.fmin[s] = std::numeric_limits<float>::infinity();
      w.fmax[s] = -std::numeric_limits<float>::infinity();
      for (std::uint32_t p : regions[keep])
        w.addPoint(s, p, f, point_area[p]);
      for (std::size_t r = 0; r < regions.size(); ++r)
        if (r != keep)
          placeRegion(s, regions[r]);
    }
    return changed;
  }

  /// The connected regions of s's points on the graph, each from its first point in s's
  /// order (depth first). region: kNone per point, and so again on return.
  std::vector<std::vector<std::uint32_t>> regionsOf(std::uint32_t s,
                                                    std::vector<std::uint32_t>& region) const {
    std::vector<std::vector<std::uint32_t>> regions;
    std::vector<std::uint32_t> stack;
    for (std::uint32_t seed : w.points[s]) {
      if (region[seed] != kNone)
        continue;
      const auto r = static_cast<std::uint32_t>(regions.size());
      regions.emplace_back();
      region[seed] = r;
      stack.push_back(seed);
      while (!stack.empty()) {
        const std::uint32_t p = stack.back();
        stack.pop_back();
        regions[r].push_back(p);
        for (std::uint32_t e = graph.offsets[p]; e < graph.offsets[p + 1]; ++e) {
          const std::uint32_t q = graph.targets[e];
          if (w.label[q] == s && region[q] == kNone) {
            region[q] = r;
            stack.push_back(q);
          }
        }
      }
    }
    for (std::uint32_t p : w.points[s])
      region[p] = kNone;
    return regions;
  }

  /// A region cut off s: a small or skinny one joins the neighbouring supernode it shares most
  /// kNN edges with, any other becomes a supernode of its own (terminating where s does).
  void placeRegion(std::uint32_t s, std::vector<std::uint32_t>& points) {
    double area = 0.0;
    float lo = std::numeric_limits<float>::infinity(), hi = -lo;
    for (std::uint32_t p : points) {
      area += point_area[p];
      lo = std::min(lo, f[p]);
      hi = std::max(hi, f[p]);
    }
    std::sort(points.begin(), points.end());
    const std::uint32_t c = component[points.front()];
    const std::uint32_t t = (area < small_area[c] || hi - lo < skinny_height[c])
                                ? w.bestNeighbour(graph, points, s)
                                : kNone;
    if (t != kNone) { // t shares edges with the region: t stays connected if it was
      for (std::uint32_t p : points)
        w.addPoint(t, p, f, point_area[p]);
    } else {
      const std::uint32_t fresh = w.add(points.front(), false, w.parent[s]);
      for (std::uint32_t p : points)
        w.addPoint(fresh, p, f, point_area[p]);
    }
  }

  /// 4. A small or skinny supernode with no saddle relation joins its point-wise neighbour,
  ///    the smallest first.
  void mergeLoners() {
    std::vector<std::uint32_t> lone;
    for (std::uint32_t s = 0; s < w.alive.size(); ++s)
      if (w.alive[s] && !w.points[s].empty() && w.parent[s] == kNone && w.children[s].empty() &&
          (small(s) || skinny(s)))
        lone.push_back(s);
    std::sort(lone.begin(), lone.end(), [&](std::uint32_t a, std::uint32_t b) {
      return w.area[a] < w.area[b] || (w.area[a] == w.area[b] && a < b);
    });
    for (std::uint32_t s : lone) {
      if (!w.alive[s] || !(small(s) || skinny(s)))
        continue;
      const std::uint32_t t = w.bestNeighbour(graph, w.points[s], s);
      if (t != kNone)
        w.mergeInto(s, t, f, point_area);
    }
  }

  /// The refined supernodes, with compact ids numbered by each one's smallest point.
  Supernodes result() {
    Supernodes all;
    all.label = std::move(w.label);
    all.origin = std::move(w.origin);
    all.at_saddle = std::move(w.at_saddle);
    all.parent = std::move(w.parent);
    return renumberSupernodes(all);
  }
};
} // namespace

Supernodes refineSupernodes(const CsrGraph& graph, const std::vector<float>& f,
                            const std::vector<float>& radii, const Supernodes& input,
                            const RefinementParams& params) {
  Refiner refiner(graph, f, radii, input, params);
  // Steps 1-3 repeat until nothing changes (a few rounds at most): the kept region of a
  // split supernode is re-tested too.
  for (int round = 0; round < 8; ++round) {
    bool changed = false;
    // Steps 1 and 2 repeat until nothing merges: a merge moves children and grows supernodes,
    // which can make another supernode eligible.
    for (bool merged = true; merged;) {
      const bool up = refiner.mergeUpAll();
      const bool down = refiner.mergeDown();
      merged = up || down;
      changed = changed || merged;
    }
    if (refiner.splitDisconnected())
      changed = true;
    if (!changed)
      break;
  }
  refiner.mergeLoners();
  return refiner.result();
}

} // namespace pcl_ncut_seg
