// Splitting supernodes along concave creases (an extension of Sec. 4.3; see crease_split.h).
#include "core/supernodes/crease_split.h"
#include "core/common/prefetch.h"
#include "core/common/radix_sort.h"
#include "core/common/threads.h"
#include "core/cut/concavity.h"
#include "core/supernodes/refinement.h"

#include <algorithm>
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

/// splitAtCreases(): takes the supernodes to test from a queue, sweeps each one's level cuts of
/// f for the most concave crease, and splits it there (its top up into its children, or off as
/// a supernode of its own) until no cut qualifies.
struct CreaseSplitter {
  const CsrGraph& graph;
  const float* xyz;
  const std::vector<float>& normals;
  const std::vector<float>& f;
  const std::vector<float>& radii;
  const CreaseSplitParams& params;
  const double typical;  ///< the mean |bend|: the unit of concavity
  const double min_area; ///< each side of a split keeps this much (Sec. 4.3's small area)
  Supernodes sn;
  std::vector<std::vector<std::uint32_t>> points; ///< per supernode, in descending f
  std::vector<char> in_top;        ///< per point: in the top of the level cut being swept
  std::vector<LevelCut> level;     ///< per supernode, its last sweep's level cut
  std::vector<char> fresh;         ///< per supernode: level is of its current points
  std::deque<std::uint32_t> queue; ///< the supernodes to test
  std::size_t splits = 0;

  CreaseSplitter(const CsrGraph& graph, const float* xyz, const std::vector<float>& normals,
                 const std::vector<float>& f, const std::vector<float>& radii,
                 const Supernodes& input, const CreaseSplitParams& params, double typical)
      : graph(graph), xyz(xyz), normals(normals), f(f), radii(radii), params(params),
        typical(typical), min_area(params.area_fraction * totalArea(radii, graph.numVertices())),
        sn(input), points(pointsByF(input, f)), in_top(graph.numVertices(), 0), level(input.size()),
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
      level[t] = levelCut(t);
    }
  }

  /// The top and the bottom (each in descending f) of the level cut that splits s; false when
  /// it does not qualify.
  bool cutAt(std::uint32_t s, std::vector<std::uint32_t>& top, std::vector<std::uint32_t>& bottom) {
    if (!(level[s].concavity >= params.min_concavity))
      return false;
    const std::vector<std::uint32_t>& pts = points[s];
    const auto end = static_cast<std::ptrdiff_t>(level[s].end);
    top.assign(pts.begin(), pts.begin() + end);
    bottom.assign(pts.begin() + end, pts.end());
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
  if (!(params.min_concavity > 0.0) || graph.numVertices() == 0 || input.size() == 0)
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
