// Splitting supernodes along concave creases (an extension of Sec. 4.3; see crease_split.h).
#include <pcl_ncut_seg/core/concavity.h>
#include <pcl_ncut_seg/core/crease_split.h>
#include <pcl_ncut_seg/core/flow_network.h>
#include <pcl_ncut_seg/core/prefetch.h>
#include <pcl_ncut_seg/core/radix_sort.h>
#include <pcl_ncut_seg/core/refinement.h>
#include <pcl_ncut_seg/core/threads.h>

#include <algorithm>
#include <cmath>
#include <deque>

namespace pcl_ncut_seg {
namespace {
/// The total feature area of the n points, summed in blocks of 4096 points as meanAbsBend()
/// sums the bends.
double totalArea(const std::vector<float>& radii, std::size_t n) {
  double total_area = 0.0;
  for (std::uint32_t first = 0; first < n; first += 4096) {
    double block_area = 0.0;
    for (std::uint32_t p = first; p < std::min<std::size_t>(n, first + 4096u); ++p)
      block_area += pointArea(radii[p]);
    total_area += block_area;
  }
  return total_area;
}

/// Per supernode, its points in descending f (ties by index): the order of the sweeps.
std::vector<std::vector<std::uint32_t>> pointsByF(const Supernodes& sn,
                                                  const std::vector<float>& f) {
  std::vector<std::vector<std::uint32_t>> points(sn.size());
  for (std::uint32_t p : descendingOrder(f))
    points[sn.label[p]].push_back(p);
  return points;
}

/// The most concave level cut through a supernode with min_area on each side: its concavity
/// (-1 when there is none) and the number of the supernode's points (in descending f) above it.
struct LevelCut {
  double concavity = -1.0;
  std::size_t end = 0;
};

/// The minimum crease cut through a supernode: its score (-1 when there is none) and its source
/// side, the top, in descending f.
struct CreaseCut {
  double score = -1.0;
  std::vector<std::uint32_t> top;
};

/// splitAtCreases() in steps over its state: the supernodes as they are split, each one's
/// points in descending f, and the cuts found for them.
struct CreaseSplitter {
  const CsrGraph& graph;
  const float* xyz;
  const std::vector<float>& normals;
  const std::vector<float>& f;
  const std::vector<float>& radii;
  const CreaseSplitParams& params;
  const bool level_cuts, crease_cuts;
  const double typical;  ///< the mean |bend|: the unit of concavity
  const double min_area; ///< each side of a split keeps this much (Sec. 4.3's small area)
  Supernodes sn;
  std::vector<std::vector<std::uint32_t>> points; ///< per supernode, in descending f
  std::vector<char> in_top; ///< per point: in the top of the level cut being swept
  /// Per point: its node in the crease cut's network, a seed (kTopSeed, kBottomSeed), or -1.
  std::vector<std::int32_t> local;
  static constexpr std::int32_t kTopSeed = -2, kBottomSeed = -3;
  std::vector<LevelCut> level;     ///< per supernode, its last sweep's level cut
  std::vector<CreaseCut> crease;   ///< per supernode, its last sweep's crease cut
  std::vector<char> fresh;         ///< per supernode: level and crease are of its current points
  std::deque<std::uint32_t> queue; ///< the supernodes to test
  std::size_t splits = 0;

  CreaseSplitter(const CsrGraph& graph, const float* xyz, const std::vector<float>& normals,
                 const std::vector<float>& f, const std::vector<float>& radii,
                 const Supernodes& input, const CreaseSplitParams& params, double typical)
      : graph(graph), xyz(xyz), normals(normals), f(f), radii(radii), params(params),
        level_cuts(params.min_concavity > 0.0), crease_cuts(params.cut_concavity > 0.0),
        typical(typical), min_area(params.area_fraction * totalArea(radii, graph.numVertices())),
        sn(input), points(pointsByF(input, f)), in_top(graph.numVertices(), 0),
        local(crease_cuts ? graph.numVertices() : 0, -1), level(input.size()), crease(input.size()),
        fresh(input.size(), 0) {
    for (std::uint32_t s = 0; s < sn.size(); ++s)
      queue.push_back(s);
  }

  /// Point a precedes point b in descending f (ties by index).
  bool higher(std::uint32_t a, std::uint32_t b) const {
    return f[a] > f[b] || (f[a] == f[b] && a < b);
  }

  /// The concave bend of edge e from p, in units of the mean |bend| (as contactConcavity()).
  double concave(std::uint32_t p, std::uint32_t e) const {
    return std::max(0.0, -edgeBend(xyz, normals, p, graph.targets[e], graph.lengths[e])) / typical;
  }

  /// The feature area of supernode s.
  double area(std::uint32_t s) const {
    double sum = 0.0;
    for (std::uint32_t p : points[s])
      sum += pointArea(radii[p]);
    return sum;
  }

  /// The most concave level cut through s (the split rule of crease_split.h). Reads only s's
  /// points and writes only in_top of s's points, so supernodes can be swept in parallel.
  LevelCut levelCut(std::uint32_t s) {
    static constexpr double kSign[2] = {1.0, -1.0};
    const std::vector<std::uint32_t>& pts = points[s];
    const double area = this->area(s);
    LevelCut best;
    if (area < 2.0 * min_area)
      return best;
    double sum = 0.0, top_area = 0.0;
    std::int64_t count = 0;
    constexpr std::size_t kAhead = 8;
    for (std::size_t i = 0; i < pts.size(); ++i) {
      // Points in f order are scattered in memory: fetch the data of those a few steps ahead
      // (here, not in a function of its own: GCC finds one that only prefetches pure and
      // drops the calls).
      if (i + 2 * kAhead < pts.size())
        prefetch(&graph.offsets[pts[i + 2 * kAhead]]);
      if (i + kAhead < pts.size()) {
        const std::uint32_t a = pts[i + kAhead];
        prefetch(&graph.targets[graph.offsets[a]]);
        prefetch(&graph.lengths[graph.offsets[a]]);
        prefetch(&normals[3 * a]);
        prefetch(&xyz[3 * a]);
        prefetch(&sn.label[a]);
        prefetch(&in_top[a]);
        prefetch(&radii[a]);
      }
      const std::uint32_t p = pts[i];
      in_top[p] = 1;
      top_area += pointArea(radii[p]);
      for (std::uint32_t e = graph.offsets[p]; e < graph.offsets[p + 1]; ++e) {
        const std::uint32_t q = graph.targets[e];
        if (q == p || sn.label[q] != s)
          continue;
        // sum -= c when q is in the top already, else sum += c, without a branch (the two
        // are equally likely, and -1 * c is exact).
        const double c = concave(p, e);
        const int above = in_top[q];
        sum += kSign[above] * c;
        count += 1 - 2 * above;
      }
      if (i + 1 < pts.size() && f[pts[i + 1]] == f[p])
        continue; // not a level cut
      if (count > 0 && top_area >= min_area && area - top_area >= min_area) {
        const double concavity = sum / static_cast<double>(count);
        if (concavity > best.concavity)
          best = {concavity, i + 1};
      }
    }
    for (std::uint32_t p : pts)
      in_top[p] = 0;
    return best;
  }

  /// A crease cut's seeds in pts (descending f): the highest points up to `seed` of area end at
  /// top_end, the lowest likewise begin at bottom_begin.
  void seeds(const std::vector<std::uint32_t>& pts, double seed, std::size_t& top_end,
             std::size_t& bottom_begin) const {
    top_end = 0;
    bottom_begin = pts.size();
    for (double a = 0.0; top_end < pts.size() && a < seed; ++top_end)
      a += pointArea(radii[pts[top_end]]);
    for (double a = 0.0; bottom_begin > 0 && a < seed; --bottom_begin)
      a += pointArea(radii[pts[bottom_begin - 1]]);
  }

  /// The capacity of edge e from p in the crease cut: its length, lowered across concave bends.
  double capacity(std::uint32_t p, std::uint32_t e) const {
    return static_cast<double>(graph.lengths[e]) *
           std::exp(-params.cut_crease_weight * concave(p, e));
  }

  /// The crease cut's network: the m points of s between the seeds (from top_end in pts; local
  /// holds their nodes), the source m (the top seed) and the sink m + 1 (the bottom seed).
  FlowNetwork cutNetwork(std::uint32_t s, std::size_t top_end, std::uint32_t m) const {
    const std::vector<std::uint32_t>& pts = points[s];
    FlowNetwork net;
    net.reset(m);
    for (std::uint32_t i = 0; i < m; ++i) {
      const std::uint32_t p = pts[top_end + i];
      for (std::uint32_t e = graph.offsets[p]; e < graph.offsets[p + 1]; ++e) {
        const std::uint32_t q = graph.targets[e];
        if (q == p || sn.label[q] != s)
          continue;
        if (local[q] >= 0)
          ++net.first[i + 1];
        else if (local[q] == kTopSeed)
          net.to_source[i] += capacity(p, e);
        else
          net.to_sink[i] += capacity(p, e);
      }
    }
    net.allocateArcs();
    for (std::uint32_t i = 0; i < m; ++i) {
      const std::uint32_t p = pts[top_end + i];
      for (std::uint32_t e = graph.offsets[p]; e < graph.offsets[p + 1]; ++e) {
        const std::uint32_t q = graph.targets[e];
        if (q > p && sn.label[q] == s && local[q] >= 0) {
          const double c = capacity(p, e);
          net.addPair(i, static_cast<std::uint32_t>(local[q]), c, c);
        }
      }
      net.addTerminalArcs(i);
    }
    return net;
  }

  /// The top of s's cut (the top seed and the source side of the network, in descending f) and
  /// the cut's score: the share of the kNN edges inside s it crosses whose concave bend is at
  /// least cut_min_bend (a crease all along the cut, rather than a few deep folds).
  CreaseCut scoreCut(std::uint32_t s, const std::vector<char>& source_side) const {
    auto onTop = [&](std::uint32_t q) {
      return local[q] == kTopSeed || (local[q] >= 0 && source_side[local[q]]);
    };
    CreaseCut cut;
    std::size_t concave_count = 0, count = 0;
    for (std::uint32_t p : points[s]) {
      if (!onTop(p))
        continue;
      cut.top.push_back(p);
      for (std::uint32_t e = graph.offsets[p]; e < graph.offsets[p + 1]; ++e) {
        const std::uint32_t q = graph.targets[e];
        if (q != p && sn.label[q] == s && !onTop(q)) {
          concave_count += concave(p, e) >= params.cut_min_bend ? 1 : 0;
          ++count;
        }
      }
    }
    if (count > 0)
      cut.score = static_cast<double>(concave_count) / static_cast<double>(count);
    return cut;
  }

  /// The minimum crease cut through s between its top and its bottom seeds (crease cuts).
  /// Reads and writes only s's entries of `local`, so supernodes can be cut in parallel.
  CreaseCut creaseCut(std::uint32_t s) {
    const std::vector<std::uint32_t>& pts = points[s];
    const double area = this->area(s);
    if (area < 2.0 * min_area)
      return {};
    std::size_t top_end, bottom_begin;
    seeds(pts, std::max(min_area, params.cut_seed_fraction * area), top_end, bottom_begin);
    if (top_end >= bottom_begin)
      return {};
    const auto m = static_cast<std::uint32_t>(bottom_begin - top_end);
    for (std::size_t i = 0; i < pts.size(); ++i)
      local[pts[i]] = i < top_end         ? kTopSeed
                      : i >= bottom_begin ? kBottomSeed
                                          : static_cast<std::int32_t>(i - top_end);
    FlowNetwork net = cutNetwork(s, top_end, m);
    CreaseCut cut = scoreCut(s, net.sourceSide(m, m + 1));
    for (std::uint32_t p : pts)
      local[p] = -1;
    return cut;
  }

  /// The cuts of every queued supernode whose points changed since its last cut (all at
  /// first), in parallel, biggest first. A cut depends only on its supernode's points, and one
  /// whose points change later is cut again, so the result does not depend on the threads.
  void cutAhead() {
    std::vector<std::uint32_t> ahead;
    for (std::uint32_t s : queue)
      if (!fresh[s]) {
        fresh[s] = 1; // also keeps s out of ahead twice
        ahead.push_back(s);
      }
    std::stable_sort(ahead.begin(), ahead.end(), [&](std::uint32_t a, std::uint32_t b) {
      return points[a].size() > points[b].size();
    });
    const auto num_ahead = static_cast<std::ptrdiff_t>(ahead.size());
#pragma omp parallel for schedule(dynamic, 1) num_threads(usableThreads(params.num_threads))
    for (std::ptrdiff_t k = 0; k < num_ahead; ++k) {
      const std::uint32_t t = ahead[k];
      level[t] = level_cuts ? levelCut(t) : LevelCut{};
      crease[t] = {};
      if (crease_cuts && !(level_cuts && level[t].concavity >= params.min_concavity))
        crease[t] = creaseCut(t);
    }
  }

  /// The top and the bottom (each in descending f) of the cut that splits s: its level cut if
  /// that qualifies, else its crease cut; false when neither does.
  bool cutAt(std::uint32_t s, std::vector<std::uint32_t>& top, std::vector<std::uint32_t>& bottom) {
    const std::vector<std::uint32_t>& pts = points[s];
    if (level_cuts && level[s].concavity >= params.min_concavity) {
      const auto end = static_cast<std::ptrdiff_t>(level[s].end);
      top.assign(pts.begin(), pts.begin() + end);
      bottom.assign(pts.begin() + end, pts.end());
      return true;
    }
    if (!(crease_cuts && crease[s].score >= params.cut_concavity))
      return false;
    top = std::move(crease[s].top);
    std::size_t t = 0;
    for (std::uint32_t p : pts) {
      if (t < top.size() && top[t] == p)
        ++t;
      else
        bottom.push_back(p);
    }
    return true;
  }

  /// Merge-up's growth (as the local refinement's step 1, Sec. 4.3): each top point of s,
  /// highest f first, joins the child of s most of its processed neighbours are in. Returns
  /// the points none of whose neighbours is in a child: they stay in s.
  std::vector<std::uint32_t> growChildren(std::uint32_t s, const std::vector<std::uint32_t>& top) {
    const std::vector<std::uint32_t>& kids = sn.children[s];
    std::vector<std::uint32_t> stay;
    LabelVote vote;
    std::vector<std::size_t> old_size(kids.size());
    for (std::size_t k = 0; k < kids.size(); ++k)
      old_size[k] = points[kids[k]].size();
    for (std::uint32_t p : top) {
      vote.clear();
      for (std::uint32_t e = graph.offsets[p]; e < graph.offsets[p + 1]; ++e) {
        const std::uint32_t t = sn.label[graph.targets[e]];
        if (std::find(kids.begin(), kids.end(), t) != kids.end())
          vote.add(t);
      }
      const std::uint32_t to = vote.winner();
      if (to == kNone) {
        stay.push_back(p);
        continue;
      }
      sn.label[p] = to;
      points[to].push_back(p);
    }
    // A kid's points and those it gained are each in descending f: merge the two runs.
    for (std::size_t k = 0; k < kids.size(); ++k) {
      std::vector<std::uint32_t>& kid = points[kids[k]];
      std::inplace_merge(kid.begin(), kid.begin() + static_cast<std::ptrdiff_t>(old_size[k]),
                         kid.end(),
                         [this](std::uint32_t a, std::uint32_t b) { return higher(a, b); });
      fresh[kids[k]] = 0;
    }
    return stay;
  }

  /// A split of s, created at a saddle: its top joins the supernodes that terminate there;
  /// s keeps the rest and is tested again.
  void mergeUp(std::uint32_t s, const std::vector<std::uint32_t>& top,
               const std::vector<std::uint32_t>& bottom) {
    std::vector<std::uint32_t> stay = growChildren(s, top);
    if (stay.size() == top.size())
      return; // nothing moved: s stays as it is
    ++splits;
    // The points that stay and the bottom are each in descending f (after a level cut the
    // former precede the latter): merge the two runs.
    const auto stayed = static_cast<std::ptrdiff_t>(stay.size());
    stay.insert(stay.end(), bottom.begin(), bottom.end());
    std::inplace_merge(stay.begin(), stay.begin() + stayed, stay.end(),
                       [this](std::uint32_t a, std::uint32_t b) { return higher(a, b); });
    points[s] = std::move(stay);
    sn.origin[s] = points[s].front();
    queue.push_back(s);
  }

  /// A split of any other s: the top becomes a supernode that terminates at the bottom's
  /// highest point, where s is now created; both are tested again.
  void splitOff(std::uint32_t s, std::vector<std::uint32_t>& top,
                std::vector<std::uint32_t>& bottom) {
    const auto t = static_cast<std::uint32_t>(sn.size());
    ++splits;
    fresh.push_back(0);
    level.emplace_back();
    crease.emplace_back();
    sn.origin.push_back(sn.origin[s]);
    sn.at_saddle.push_back(sn.at_saddle[s]);
    sn.parent.push_back(s);
    sn.children.push_back({});
    for (std::uint32_t p : top)
      sn.label[p] = t;
    points.push_back(std::move(top));
    points[s] = std::move(bottom);
    sn.origin[s] = points[s].front();
    sn.at_saddle[s] = true;
    sn.children[s].push_back(t);
    queue.push_back(s);
    queue.push_back(t);
  }

  /// Every supernode in the queue is tested in turn, its cut found ahead (cutAhead()), until
  /// no cut qualifies; returns the number of splits.
  std::size_t run() {
    while (!queue.empty()) {
      if (!fresh[queue.front()])
        cutAhead();
      const std::uint32_t s = queue.front();
      queue.pop_front();
      fresh[s] = 0;
      std::vector<std::uint32_t> top, bottom;
      if (!cutAt(s, top, bottom))
        continue;
      if (!sn.children[s].empty())
        mergeUp(s, top, bottom);
      else
        splitOff(s, top, bottom);
    }
    return splits;
  }
};
} // namespace

Supernodes splitAtCreases(const CsrGraph& graph, const float* xyz,
                          const std::vector<float>& normals, const std::vector<float>& f,
                          const std::vector<float>& radii, const Supernodes& input,
                          const CreaseSplitParams& params, std::size_t* num_splits) {
  if (num_splits)
    *num_splits = 0;
  const bool level_cuts = params.min_concavity > 0.0;
  const bool crease_cuts = params.cut_concavity > 0.0;
  if ((!level_cuts && !crease_cuts) || graph.numVertices() == 0 || input.size() == 0)
    return input;
  const double typical = params.typical_bend > 0.0
                             ? params.typical_bend
                             : meanAbsBend(graph, xyz, normals, params.num_threads);
  if (!(typical > 0.0))
    return input;
  CreaseSplitter splitter(graph, xyz, normals, f, radii, input, params, typical);
  const std::size_t splits = splitter.run();
  if (num_splits)
    *num_splits = splits;
  if (splits == 0)
    return input;
  // Compact ids in order of each supernode's first point (by index).
  return renumberSupernodes(splitter.sn);
}

} // namespace pcl_ncut_seg
