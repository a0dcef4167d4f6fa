// Sec. 4.1's centrality on a coarse graph of representatives, carried back to every point.
#include "core/centrality/coarse_centrality.h"
#include "core/common/threads.h"
#include "core/graph/shortest_paths.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>

#ifdef _OPENMP
#include <omp.h>
#endif

namespace pcl_ncut_seg {
namespace {
constexpr float kInf = std::numeric_limits<float>::infinity();
constexpr std::uint32_t kNoSource = std::numeric_limits<std::uint32_t>::max();

int threadId() {
#ifdef _OPENMP
  return omp_get_thread_num();
#else
  return 0;
#endif
}

/// Per thread: a bounded search and its distance array (+infinity between searches). Aligned
/// to cache lines, so that threads do not write to each other's lines.
struct alignas(64) BallSearch {
  explicit BallSearch(const CsrGraph& g) : search(g), dist(g.numVertices(), kInf) {}
  BucketDijkstra search;
  std::vector<float> dist;
  std::vector<std::uint32_t> touched;
};

/// Greedy cover by balls of radius `radius`: an uncovered vertex (in `visit` order) becomes a
/// representative and covers every vertex within the radius. The balls of the next uncovered
/// vertices are searched in parallel, then accepted in visit order if their centre is still
/// uncovered, so the cover is the sequential one for any number of threads.
std::vector<std::uint32_t> coverByBalls(const CsrGraph& g, float radius,
                                        const std::vector<std::uint32_t>& visit,
                                        std::vector<BallSearch>& searches) {
  const std::size_t n = g.numVertices();
  const int threads = static_cast<int>(searches.size());
  std::vector<std::uint8_t> covered(n, 0);
  std::vector<std::uint32_t> reps, candidates;
  // The block of candidates searched together grows while under 1% of them turn out covered
  // by an earlier ball of the same block (searched in vain), and shrinks above 5%: few
  // synchronisations (each can cost a time slice when another process holds a core) for
  // little wasted work (measured at 181k and 1M points: 3-4% of the searches, 40-120 blocks
  // per cover).
  const std::size_t min_block = 32 * static_cast<std::size_t>(threads);
  const std::size_t max_block = 8192 * static_cast<std::size_t>(threads);
  std::size_t block = 128 * static_cast<std::size_t>(threads);
  // A block runs on several threads only when its searches are worth a synchronisation: on a
  // cloud little larger than the number of representatives the balls hold a few vertices,
  // and hundreds of tiny blocks would each wait at a barrier (a time slice each when another
  // process holds a core). Estimated from the vertices the previous block's searches reached;
  // 8192 visits are about 0.1 ms of work (measured: 1.95x on two threads at 1M points).
  constexpr double kMinParallelVisits = 8192.0;
  double visits_per_search = kMinParallelVisits; // the first block runs in parallel
  std::vector<std::vector<std::uint32_t>> balls;
  for (std::size_t next = 0; next < n;) {
    candidates.clear();
    for (; next < n && candidates.size() < block; ++next)
      if (!covered[visit[next]])
        candidates.push_back(visit[next]);
    const auto count = static_cast<std::ptrdiff_t>(candidates.size());
    if (balls.size() < candidates.size())
      balls.resize(candidates.size());
    const bool parallel =
        count > 1 && static_cast<double>(count) * visits_per_search >= kMinParallelVisits;
    std::size_t visits = 0;
#pragma omp parallel for num_threads(threads) schedule(dynamic, 1) if (parallel) \
    reduction(+ : visits)
    for (std::ptrdiff_t i = 0; i < count; ++i) {
      BallSearch& s = searches[threadId()];
      s.touched.clear();
      s.search.runWithin(candidates[i], s.dist.data(), radius, &s.touched);
      visits += s.touched.size();
      std::size_t inside = 0;
      for (std::uint32_t u : s.touched) {
        if (s.dist[u] <= radius)
          s.touched[inside++] = u;
        s.dist[u] = kInf;
      }
      balls[i].assign(s.touched.begin(), s.touched.begin() + inside);
    }
    if (count > 0)
      visits_per_search = static_cast<double>(visits) / static_cast<double>(count);
    std::ptrdiff_t in_vain = 0;
    for (std::ptrdiff_t i = 0; i < count; ++i) {
      if (covered[candidates[i]]) {
        ++in_vain;
        continue;
      }
      reps.push_back(candidates[i]);
      for (std::uint32_t u : balls[i])
        covered[u] = 1;
    }
    if (in_vain * 100 < count)
      block = std::min(2 * block, max_block);
    else if (in_vain * 20 > count)
      block = std::max(block / 2, min_block);
  }
  return reps;
}

/// Two labels (source, distance) per vertex, compared by distance, then source index.
struct TwoLabels {
  std::uint32_t first, second;
  float first_dist, second_dist;
};

inline bool before(float da, std::uint32_t sa, float db, std::uint32_t sb) {
  return da < db || (da == db && sa < sb);
}

/// Offer (s, d) to the labels l: keep the two best distinct sources.
inline void offer(TwoLabels& l, std::uint32_t s, float d) {
  if (s == l.first) {
    if (d < l.first_dist)
      l.first_dist = d;
  } else if (s == l.second) {
    if (d < l.second_dist) {
      l.second_dist = d;
      if (before(l.second_dist, l.second, l.first_dist, l.first)) {
        std::swap(l.first, l.second);
        std::swap(l.first_dist, l.second_dist);
      }
    }
  } else if (before(d, s, l.first_dist, l.first)) {
    l.second = l.first;
    l.second_dist = l.first_dist;
    l.first = s;
    l.first_dist = d;
  } else if (before(d, s, l.second_dist, l.second)) {
    l.second = s;
    l.second_dist = d;
  }
}

/// The two nearest sources of every vertex (graph distance, ties to the lower source index),
/// by rounds in which every vertex next to a change takes the best labels its neighbours
/// offer. A round reads the labels of the previous one only, so the result does not depend
/// on the number of threads. A vertex with fewer than two reachable sources gets kNoSource and
/// +infinity for the missing ones.
std::vector<TwoLabels> nearestTwo(const CsrGraph& g, const std::vector<std::uint32_t>& sources,
                                  int threads) {
  const std::size_t n = g.numVertices();
  std::vector<TwoLabels> label(n, TwoLabels{kNoSource, kNoSource, kInf, kInf});
  // fresh: labels changed in the last round. A vertex has taken in every other neighbour's
  // labels already, in the round after they last changed.
  std::vector<std::uint8_t> next_active(n, 0), fresh(n, 0);
  std::vector<std::uint32_t> active, last_active(sources);
  for (std::uint32_t i = 0; i < sources.size(); ++i) {
    offer(label[sources[i]], i, 0.0f);
    fresh[sources[i]] = 1;
  }
  for (std::uint32_t s : sources)
    for (std::uint32_t e = g.offsets[s]; e < g.offsets[s + 1]; ++e)
      next_active[g.targets[e]] = 1;
  std::vector<TwoLabels> updated;
  std::vector<std::uint8_t> changed;
  for (;;) {
    active.clear();
    for (std::uint32_t v = 0; v < n; ++v)
      if (next_active[v]) {
        active.push_back(v);
        next_active[v] = 0;
      }
    if (active.empty())
      break;

    updated.resize(active.size());
    changed.assign(active.size(), 0);
    const auto count = static_cast<std::ptrdiff_t>(active.size());
#pragma omp parallel for num_threads(threads) schedule(dynamic, 512)
    for (std::ptrdiff_t i = 0; i < count; ++i) {
      const std::uint32_t v = active[i];
      TwoLabels l = label[v];
      for (std::uint32_t e = g.offsets[v]; e < g.offsets[v + 1]; ++e) {
        const std::uint32_t t = g.targets[e];
        if (!fresh[t])
          continue;
        const TwoLabels& u = label[t];
        const float w = g.lengths[e];
        if (u.first != kNoSource)
          offer(l, u.first, u.first_dist + w);
        if (u.second != kNoSource)
          offer(l, u.second, u.second_dist + w);
      }
      updated[i] = l;
      changed[i] = l.first != label[v].first || l.second != label[v].second ||
                   l.first_dist != label[v].first_dist || l.second_dist != label[v].second_dist;
    }
    const auto last = static_cast<std::ptrdiff_t>(last_active.size());
#pragma omp parallel for num_threads(threads) schedule(static)
    for (std::ptrdiff_t i = 0; i < last; ++i)
      fresh[last_active[i]] = 0;
#pragma omp parallel for num_threads(threads) schedule(dynamic, 512)
    for (std::ptrdiff_t i = 0; i < count; ++i) {
      if (!changed[i])
        continue;
      const std::uint32_t v = active[i];
      label[v] = updated[i];
      fresh[v] = 1;
      for (std::uint32_t e = g.offsets[v]; e < g.offsets[v + 1]; ++e) {
#pragma omp atomic write
        next_active[g.targets[e]] = 1;
      }
    }
    last_active.swap(active);
  }
  return label;
}
/// Step 1: an uncovered vertex becomes a representative in ascending tie_rank. On a surface,
/// n points with mean edge length e cover an area of about n e^2 / 2, and balls of radius r
/// packed by the greedy cover take about 4.6 r^2 each (measured); the radius is corrected once
/// or twice if the count is off by over 25%. radius: on return, the one the cover used.
std::vector<std::uint32_t> chooseRepresentatives(const CsrGraph& g, std::size_t num_representatives,
                                                 const std::uint32_t* tie_rank,
                                                 std::vector<BallSearch>& searches,
                                                 double& radius) {
  const std::size_t n = g.numVertices();
  double sum = 0.0;
  for (float w : g.lengths)
    sum += w;
  const double mean_edge = g.lengths.empty() ? 1.0 : sum / static_cast<double>(g.lengths.size());
  radius = mean_edge *
           std::sqrt(static_cast<double>(n) / (9.2 * static_cast<double>(num_representatives)));
  std::vector<std::uint32_t> visit(n), reps;
  for (std::uint32_t v = 0; v < n; ++v)
    visit[tie_rank ? tie_rank[v] : v] = v;
  for (int attempt = 0; attempt < 3; ++attempt) {
    reps = coverByBalls(g, static_cast<float>(radius), visit, searches);
    const double ratio =
        static_cast<double>(reps.size()) / static_cast<double>(num_representatives);
    if (ratio > 0.8 && ratio < 1.25)
      break;
    radius *= std::sqrt(ratio);
  }
  return reps;
}

/// Per cell a (a representative's vertices): (b, length) for each neighbour cell b > a, sorted
/// by b, with the shortest crossing d1(u) + |uv| + d1(v) over the kNN edges (u, v) from a to b.
using HigherCells = std::vector<std::vector<std::pair<std::uint32_t, float>>>;

/// Step 3's crossings: the vertices grouped by cell, then each cell's crossings (cells in
/// parallel, each in a fixed order).
HigherCells shortestCrossings(const CsrGraph& g, const std::vector<TwoLabels>& near, std::size_t c,
                              std::vector<BallSearch>& searches, int threads) {
  const std::size_t n = g.numVertices();
  std::vector<std::uint32_t> cell_begin(c + 1, 0), cell_vertices(n);
  for (std::uint32_t u = 0; u < n; ++u)
    ++cell_begin[near[u].first + 1];
  for (std::size_t i = 0; i < c; ++i)
    cell_begin[i + 1] += cell_begin[i];
  {
    std::vector<std::uint32_t> fill(cell_begin.begin(), cell_begin.end() - 1);
    for (std::uint32_t u = 0; u < n; ++u)
      cell_vertices[fill[near[u].first]++] = u;
  }
  HigherCells higher(c);
#pragma omp parallel num_threads(threads)
  {
    // The shortest crossing to each neighbour cell b so far, in the thread's search distances
    // (n >= c floats, +infinity between searches and between cells: no more memory), and the
    // cells b met: a few per cell, sorted at the end (no sort of every crossing edge).
    float* shortest = searches[threadId()].dist.data();
    std::vector<std::uint32_t> met;
#pragma omp for schedule(dynamic, 64)
    for (std::ptrdiff_t ai = 0; ai < static_cast<std::ptrdiff_t>(c); ++ai) {
      const auto a = static_cast<std::uint32_t>(ai);
      met.clear();
      for (std::uint32_t i = cell_begin[a]; i < cell_begin[a + 1]; ++i) {
        const std::uint32_t u = cell_vertices[i];
        for (std::uint32_t e = g.offsets[u]; e < g.offsets[u + 1]; ++e) {
          const std::uint32_t v = g.targets[e];
          const std::uint32_t b = near[v].first;
          if (a < b) {
            const float length = near[u].first_dist + g.lengths[e] + near[v].first_dist;
            if (shortest[b] == kInf)
              met.push_back(b); // (again if the length is +infinity: dropped below)
            shortest[b] = std::min(shortest[b], length);
          }
        }
      }
      std::sort(met.begin(), met.end());
      auto& out = higher[a];
      for (std::size_t i = 0; i < met.size(); ++i)
        if (i == 0 || met[i] != met[i - 1])
          out.emplace_back(met[i], shortest[met[i]]);
      for (std::uint32_t b : met)
        shortest[b] = kInf;
    }
  }
  return higher;
}

/// Step 3's coarse graph: each crossing as an edge both ways.
CsrGraph coarseGraphOf(const HigherCells& higher) {
  const std::size_t c = higher.size();
  CsrGraph coarse;
  coarse.offsets.assign(c + 1, 0);
  for (std::uint32_t a = 0; a < c; ++a)
    for (const auto& [b, w] : higher[a]) {
      ++coarse.offsets[a + 1];
      ++coarse.offsets[b + 1];
    }
  for (std::size_t i = 0; i < c; ++i)
    coarse.offsets[i + 1] += coarse.offsets[i];
  coarse.targets.resize(coarse.offsets[c]);
  coarse.lengths.resize(coarse.offsets[c]);
  // Rows come out sorted: a's lower neighbours arrive in ascending order (from the loop over
  // b < a), then its higher ones in ascending order.
  std::vector<std::uint32_t> fill(coarse.offsets.begin(), coarse.offsets.end() - 1);
  for (std::uint32_t a = 0; a < c; ++a)
    for (const auto& [b, w] : higher[a]) {
      coarse.targets[fill[b]] = a;
      coarse.lengths[fill[b]++] = w;
    }
  for (std::uint32_t a = 0; a < c; ++a)
    for (const auto& [b, w] : higher[a]) {
      coarse.targets[fill[a]] = b;
      coarse.lengths[fill[a]++] = w;
    }
  return coarse;
}

/// Step 4's tie ranks: ties on the coarse graph follow the representatives' ranks.
std::vector<std::uint32_t> coarseTieRanks(const std::vector<std::uint32_t>& reps,
                                          const std::uint32_t* tie_rank) {
  std::vector<std::uint32_t> coarse_rank(reps.size()), by_rank(reps.size());
  std::iota(by_rank.begin(), by_rank.end(), 0u);
  auto rank = [&](std::uint32_t i) { return tie_rank ? tie_rank[reps[i]] : reps[i]; };
  std::sort(by_rank.begin(), by_rank.end(),
            [&](std::uint32_t a, std::uint32_t b) { return rank(a) < rank(b); });
  for (std::uint32_t i = 0; i < by_rank.size(); ++i)
    coarse_rank[by_rank[i]] = i;
  return coarse_rank;
}

/// The coarse graph's paths zigzag through the representatives, so its distances exceed the
/// kNN graph's by a few percent: the ratio (kNN over coarse) on pairs of representatives 3 to
/// 8 radii apart, from 32 of them, with bounded searches on both graphs. The sources' searches
/// run in parallel; the sums are taken in source order.
float coarseDistanceScale(const CsrGraph& coarse, const std::vector<std::uint32_t>& reps,
                          double radius, std::vector<BallSearch>& searches, int threads) {
  const std::size_t c = reps.size();
  const std::size_t step = std::max<std::size_t>(1, c / 32);
  std::vector<std::vector<std::pair<float, float>>> pairs((c + step - 1) / step);
  const auto fine_bound = static_cast<float>(8.0 * radius);
  const auto coarse_bound = static_cast<float>(12.0 * radius);
#pragma omp parallel num_threads(threads)
  {
    BallSearch& fine = searches[threadId()];
    BucketDijkstra coarse_search(coarse);
    std::vector<float> coarse_dist(c, kInf);
    std::vector<std::uint32_t> coarse_touched;
#pragma omp for schedule(dynamic, 1)
    for (std::ptrdiff_t si = 0; si < static_cast<std::ptrdiff_t>(pairs.size()); ++si) {
      const std::size_t a = static_cast<std::size_t>(si) * step;
      fine.touched.clear();
      coarse_touched.clear();
      fine.search.runWithin(reps[a], fine.dist.data(), fine_bound, &fine.touched);
      coarse_search.runWithin(static_cast<std::uint32_t>(a), coarse_dist.data(), coarse_bound,
                              &coarse_touched);
      for (std::uint32_t b : coarse_touched) {
        const float d = fine.dist[reps[b]];
        if (d >= 3.0 * radius && d <= 8.0 * radius)
          pairs[si].emplace_back(d, coarse_dist[b]);
        coarse_dist[b] = kInf;
      }
      for (std::uint32_t v : fine.touched)
        fine.dist[v] = kInf;
    }
  }
  double fine_sum = 0.0, coarse_sum = 0.0;
  for (const auto& list : pairs)
    for (const auto& [fine, coarse_d] : list) {
      fine_sum += fine;
      coarse_sum += coarse_d;
    }
  return coarse_sum > 0.0 ? static_cast<float>(fine_sum / coarse_sum) : 1.0f;
}

/// Step 5 of computeCoarseCentralities(): the coarse graph's f carried back to every vertex,
/// linearly between its two nearest representatives.
Centrality carryBack(const Centrality& cc, const std::vector<TwoLabels>& near,
                     const std::vector<std::uint32_t>& reps, float scale, int threads) {
  const std::size_t n = near.size();
  Centrality out;
  out.f.resize(n);
#pragma omp parallel for num_threads(threads) schedule(static)
  for (std::ptrdiff_t pi = 0; pi < static_cast<std::ptrdiff_t>(n); ++pi) {
    const auto p = static_cast<std::size_t>(pi);
    const float d1 = near[p].first_dist, d2 = near[p].second_dist;
    const float f1 = scale * cc.f[near[p].first];
    float f;
    if (near[p].second == kNoSource)
      f = d1; // the component's only representative is its only sample: f = g(p, r1)
    else if (d1 + d2 > 0.0f)
      f = (d2 * f1 + d1 * scale * cc.f[near[p].second]) / (d1 + d2);
    else
      f = f1;
    out.f[p] = f;
  }
  // Components: a vertex is in its representative's, and the coarse graph joins cells
  // exactly where kNN edges do. Numbered in order of their smallest vertex.
  out.num_components = cc.num_components;
  out.component.resize(n);
  {
    std::vector<std::uint32_t> number(cc.num_components, kNoSource);
    std::uint32_t next = 0;
    for (std::uint32_t p = 0; p < n; ++p) {
      std::uint32_t& id = number[cc.component[near[p].first]];
      if (id == kNoSource)
        id = next++;
      out.component[p] = id;
    }
  }
  out.samples.reserve(cc.samples.size());
  for (std::uint32_t s : cc.samples)
    out.samples.push_back(reps[s]);
  return out;
}

} // namespace

Centrality computeCoarseCentrality(const CsrGraph& graph, std::size_t num_representatives,
                                   std::size_t num_samples, unsigned num_threads,
                                   const std::uint32_t* tie_rank, const ProgressFn& progress) {
  return std::move(computeCoarseCentralities(graph, num_representatives, num_samples, num_threads,
                                             tie_rank, progress, 1)
                       .front());
}

std::vector<Centrality> computeCoarseCentralities(const CsrGraph& graph,
                                                  std::size_t num_representatives,
                                                  std::size_t num_samples, unsigned num_threads,
                                                  const std::uint32_t* tie_rank,
                                                  const ProgressFn& progress,
                                                  std::size_t num_starts) {
  const std::size_t n = graph.numVertices();
  if (!coarseGraphPays(n, num_representatives))
    return computeCentralities(graph, num_samples, num_threads, tie_rank, progress, num_starts);

  // Searches read the graph in vertex order: the caller's order decides how well they use the
  // cache (the PCL front end numbers points along a Morton curve).
  const int threads = usableThreads(num_threads);
  std::vector<BallSearch> searches;
  for (int t = 0; t < threads; ++t)
    searches.emplace_back(graph);
  double radius = 0.0;
  const std::vector<std::uint32_t> reps =
      chooseRepresentatives(graph, num_representatives, tie_rank, searches, radius); // 1.
  const std::vector<TwoLabels> near = nearestTwo(graph, reps, threads);              // 2.
  const CsrGraph coarse =
      coarseGraphOf(shortestCrossings(graph, near, reps.size(), searches, threads)); // 3.
  const std::vector<std::uint32_t> coarse_rank = coarseTieRanks(reps, tie_rank);     // 4.
  const std::vector<Centrality> coarse_starts = computeCentralities(
      coarse, num_samples, num_threads, coarse_rank.data(), progress, num_starts);
  const float scale = coarseDistanceScale(coarse, reps, radius, searches, threads);
  searches.clear();
  std::vector<Centrality> all; // 5.
  for (const Centrality& cc : coarse_starts)
    all.push_back(carryBack(cc, near, reps, scale, threads));
  return all;
}

} // namespace pcl_ncut_seg
