// Splitting supernodes along concave creases (an extension of Sec. 4.3; see crease_split.h).
#include <pcl_ncut_seg/core/concavity.h>
#include <pcl_ncut_seg/core/crease_split.h>
#include <pcl_ncut_seg/core/flow_network.h>
#include <pcl_ncut_seg/core/prefetch.h>
#include <pcl_ncut_seg/core/radix_sort.h>
#include <pcl_ncut_seg/core/threads.h>

#include <algorithm>
#include <cmath>
#include <deque>

namespace pcl_ncut_seg {
namespace {
constexpr double kPi = 3.14159265358979323846;
} // namespace

Supernodes splitAtCreases(const CsrGraph& graph, const float* xyz,
                          const std::vector<float>& normals, const std::vector<float>& f,
                          const std::vector<float>& radii, const Supernodes& input,
                          const CreaseSplitParams& params, std::size_t* num_splits) {
  Supernodes sn = input;
  std::size_t splits = 0;
  if (num_splits)
    *num_splits = 0;
  const std::size_t n = graph.numVertices();
  const bool level_cuts = params.min_concavity > 0.0;
  const bool crease_cuts = params.cut_concavity > 0.0;
  if ((!level_cuts && !crease_cuts) || n == 0 || sn.size() == 0)
    return sn;

  auto bend = [&](std::uint32_t p, std::uint32_t q, float length) {
    return edgeBend(xyz, normals, p, q, length);
  };
  auto pointArea = [&](std::uint32_t p) { return kPi * radii[p] * radii[p]; }; // as Sec. 4.3
  const double typical = params.typical_bend > 0.0
                             ? params.typical_bend
                             : meanAbsBend(graph, xyz, normals, params.num_threads);
  if (!(typical > 0.0))
    return sn;
  // Summed in blocks of 4096 points, as meanAbsBend() sums the bends.
  double total_area = 0.0;
  for (std::uint32_t first = 0; first < n; first += 4096) {
    double block_area = 0.0;
    for (std::uint32_t p = first; p < std::min<std::size_t>(n, first + 4096u); ++p)
      block_area += pointArea(p);
    total_area += block_area;
  }
  const double min_area = params.area_fraction * total_area;

  // Points of each supernode in descending f.
  std::vector<std::vector<std::uint32_t>> points(sn.size());
  for (std::uint32_t p : descendingOrder(f))
    points[sn.label[p]].push_back(p);

  auto descending = [&](std::uint32_t a, std::uint32_t b) {
    return f[a] > f[b] || (f[a] == f[b] && a < b);
  };
  std::vector<char> in_top(n, 0);
  static constexpr double kSign[2] = {1.0, -1.0};
  constexpr std::size_t kAhead = 8;
  // The most concave level cut through s with min_area on each side: (concavity, number of
  // points above it); concavity -1 when s is too small. Reads only s's points and in_top of
  // s's points, so supernodes can be swept in parallel.
  auto sweep = [&](std::uint32_t s) {
    const std::vector<std::uint32_t>& pts = points[s];
    double area = 0.0;
    for (std::uint32_t p : pts)
      area += pointArea(p);
    double sum = 0.0, top_area = 0.0, best = -1.0;
    std::int64_t count = 0;
    std::size_t best_end = 0;
    if (area < 2.0 * min_area)
      return std::make_pair(best, best_end);
    for (std::size_t i = 0; i < pts.size(); ++i) {
      // Points in f order are scattered in memory: fetch the data of those a few steps ahead.
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
      top_area += pointArea(p);
      for (std::uint32_t e = graph.offsets[p]; e < graph.offsets[p + 1]; ++e) {
        const std::uint32_t q = graph.targets[e];
        if (q == p || sn.label[q] != s)
          continue;
        // sum -= c when q is in the top already, else sum += c, without a branch (the two
        // are equally likely, and -1 * c is exact).
        const double c = std::max(0.0, -bend(p, q, graph.lengths[e])) / typical;
        const int above = in_top[q];
        sum += kSign[above] * c;
        count += 1 - 2 * above;
      }
      if (i + 1 < pts.size() && f[pts[i + 1]] == f[p])
        continue; // not a level cut
      if (count > 0 && top_area >= min_area && area - top_area >= min_area) {
        const double concavity = sum / static_cast<double>(count);
        if (concavity > best) {
          best = concavity;
          best_end = i + 1;
        }
      }
    }
    for (std::uint32_t p : pts)
      in_top[p] = 0;
    return std::make_pair(best, best_end);
  };
  // The minimum crease cut through s between its top and its bottom (crease cuts): its score
  // (-1 when there is none) and its source side, the top, in descending f. Reads and
  // writes only s's entries of `local`, so supernodes can be cut in parallel.
  std::vector<std::int32_t> local(crease_cuts ? n : 0, -1);
  constexpr std::int32_t kTopSeed = -2, kBottomSeed = -3;
  auto creaseCut = [&](std::uint32_t s) {
    std::pair<double, std::vector<std::uint32_t>> result(-1.0, {});
    const std::vector<std::uint32_t>& pts = points[s];
    double area = 0.0;
    for (std::uint32_t p : pts)
      area += pointArea(p);
    if (area < 2.0 * min_area)
      return result;
    const double seed = std::max(min_area, params.cut_seed_fraction * area);
    // The top seed: the highest points up to `seed` of area; the bottom seed likewise.
    std::size_t top_end = 0, bottom_begin = pts.size();
    for (double a = 0.0; top_end < pts.size() && a < seed; ++top_end)
      a += pointArea(pts[top_end]);
    for (double a = 0.0; bottom_begin > 0 && a < seed; --bottom_begin)
      a += pointArea(pts[bottom_begin - 1]);
    if (top_end >= bottom_begin)
      return result;
    const auto m = static_cast<std::uint32_t>(bottom_begin - top_end);
    for (std::size_t i = 0; i < pts.size(); ++i)
      local[pts[i]] = i < top_end         ? kTopSeed
                      : i >= bottom_begin ? kBottomSeed
                                          : static_cast<std::int32_t>(i - top_end);
    auto concave = [&](std::uint32_t p, std::uint32_t e) {
      return std::max(0.0, -bend(p, graph.targets[e], graph.lengths[e])) / typical;
    };
    auto capacity = [&](std::uint32_t p, std::uint32_t e) {
      return static_cast<double>(graph.lengths[e]) *
             std::exp(-params.cut_crease_weight * concave(p, e));
    };
    // The network: the points between the seeds, the source (top seed) and the sink.
    const std::uint32_t source = m, sink = m + 1;
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
    const std::vector<char> source_side = net.sourceSide(source, sink);
    auto onTop = [&](std::uint32_t q) {
      return local[q] == kTopSeed || (local[q] >= 0 && source_side[local[q]]);
    };
    // The cut's score: the share of the kNN edges inside s it crosses whose concave bend is at
    // least cut_min_bend (a crease all along the cut, rather than a few deep folds).
    std::size_t concave_count = 0, count = 0;
    for (std::uint32_t p : pts) {
      if (!onTop(p))
        continue;
      result.second.push_back(p);
      for (std::uint32_t e = graph.offsets[p]; e < graph.offsets[p + 1]; ++e) {
        const std::uint32_t q = graph.targets[e];
        if (q != p && sn.label[q] == s && !onTop(q)) {
          concave_count += concave(p, e) >= params.cut_min_bend ? 1 : 0;
          ++count;
        }
      }
    }
    for (std::uint32_t p : pts)
      local[p] = -1;
    if (count > 0)
      result.first = static_cast<double>(concave_count) / static_cast<double>(count);
    return result;
  };
  // Every supernode in the queue is tested in turn. The sweeps of all those in the queue
  // whose points changed since their last sweep (all at first) are made ahead, in parallel,
  // biggest first; a sweep depends only on the points of its supernode, and a supernode whose
  // points change later is swept again, so the result does not depend on the threads.
  std::vector<std::pair<double, std::size_t>> first(sn.size());
  std::vector<std::pair<double, std::vector<std::uint32_t>>> crease_cut(sn.size());
  std::vector<char> fresh(sn.size(), 0); // first[s] is the sweep of s's current points
  const int threads = usableThreads(params.num_threads);
  std::deque<std::uint32_t> queue;
  for (std::uint32_t s = 0; s < sn.size(); ++s)
    queue.push_back(s);
  std::vector<std::uint32_t> ahead;
  while (!queue.empty()) {
    if (!fresh[queue.front()]) {
      ahead.clear();
      for (std::uint32_t s : queue)
        if (!fresh[s]) {
          fresh[s] = 1; // also keeps s out of ahead twice
          ahead.push_back(s);
        }
      std::stable_sort(ahead.begin(), ahead.end(), [&](std::uint32_t a, std::uint32_t b) {
        return points[a].size() > points[b].size();
      });
      const auto num_ahead = static_cast<std::ptrdiff_t>(ahead.size());
#pragma omp parallel for schedule(dynamic, 1) num_threads(threads)
      for (std::ptrdiff_t k = 0; k < num_ahead; ++k) {
        const std::uint32_t t = ahead[k];
        first[t] = level_cuts ? sweep(t) : std::make_pair(-1.0, std::size_t{0});
        crease_cut[t] = {-1.0, {}};
        if (crease_cuts && !(level_cuts && first[t].first >= params.min_concavity))
          crease_cut[t] = creaseCut(t);
      }
    }
    const std::uint32_t s = queue.front();
    queue.pop_front();
    const std::vector<std::uint32_t>& pts = points[s];
    const auto [best, best_end] = first[s];
    fresh[s] = 0;
    std::vector<std::uint32_t> top, bottom;
    if (level_cuts && best >= params.min_concavity) {
      top.assign(pts.begin(), pts.begin() + static_cast<std::ptrdiff_t>(best_end));
      bottom.assign(pts.begin() + static_cast<std::ptrdiff_t>(best_end), pts.end());
    } else if (crease_cuts && crease_cut[s].first >= params.cut_concavity) {
      // The source side of the crease cut is the top; both keep the descending order.
      top = std::move(crease_cut[s].second);
      std::size_t t = 0;
      for (std::uint32_t p : pts) {
        if (t < top.size() && top[t] == p)
          ++t;
        else
          bottom.push_back(p);
      }
    } else {
      continue;
    }
    if (!sn.children[s].empty()) {
      // Merge-up: the top joins the supernodes that terminate at s's saddle, grown from them
      // highest f first; a point none of whose processed neighbours is in them stays below.
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
                           kid.end(), descending);
        fresh[kids[k]] = 0;
      }
      if (stay.size() == top.size())
        continue; // nothing moved: s stays as it is
      ++splits;
      // The points that stay and the bottom are each in descending f (after a level cut the
      // former precede the latter): merge the two runs.
      const auto stayed = static_cast<std::ptrdiff_t>(stay.size());
      stay.insert(stay.end(), bottom.begin(), bottom.end());
      std::inplace_merge(stay.begin(), stay.begin() + stayed, stay.end(), descending);
      points[s] = std::move(stay);
      sn.origin[s] = points[s].front();
      queue.push_back(s);
    } else {
      // The top becomes a supernode that terminates at the bottom's highest point.
      const auto t = static_cast<std::uint32_t>(sn.size());
      ++splits;
      fresh.push_back(0);
      first.emplace_back();
      crease_cut.emplace_back();
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
  }

  if (num_splits)
    *num_splits = splits;
  if (splits == 0)
    return input;
  // Compact ids in order of each supernode's first point (by index).
  return renumberSupernodes(sn);
}

} // namespace pcl_ncut_seg
