// Sec. 4.1's centrality on a coarse graph of representatives, carried back to every point.
#include <pcl_ncut_seg/core/coarse_centrality.h>
#include <pcl_ncut_seg/core/shortest_paths.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>

namespace pcl_ncut_seg {
namespace {
constexpr float kInf = std::numeric_limits<float>::infinity();
constexpr std::uint32_t kNoSource = std::numeric_limits<std::uint32_t>::max();

/// Greedy cover by balls of radius `radius`: an uncovered vertex (in `visit` order) becomes a
/// representative and covers every vertex within the radius.
std::vector<std::uint32_t> coverByBalls(const CsrGraph& g, float radius,
                                        const std::vector<std::uint32_t>& visit,
                                        BucketDijkstra& search, std::vector<float>& dist,
                                        std::vector<float>& bound) {
  const std::size_t n = g.numVertices();
  std::vector<bool> covered(n, false);
  std::vector<std::uint32_t> reps, touched;
  std::fill(bound.begin(), bound.end(), radius);
  for (std::uint32_t v : visit) {
    if (covered[v])
      continue;
    reps.push_back(v);
    touched.clear();
    search.run(v, dist.data(), bound.data(), &touched);
    for (std::uint32_t u : touched) {
      if (dist[u] <= radius)
        covered[u] = true;
      dist[u] = kInf;
    }
  }
  return reps;
}
} // namespace

Centrality computeCoarseCentrality(const CsrGraph& graph, std::size_t num_representatives,
                                   std::size_t num_samples, unsigned num_threads,
                                   const std::uint32_t* tie_rank, const ProgressFn& progress) {
  const std::size_t n = graph.numVertices();
  if (num_representatives == 0 || n <= num_representatives)
    return computeCentrality(graph, num_samples, num_threads, tie_rank, progress);

  const CsrGraph& g = graph;

  // Searches read the graph in vertex order: the caller's order decides how well they use the
  // cache (the PCL front end numbers points along a Morton curve).
  // 1. Representatives. On a surface, n points with mean edge length e cover an area of about
  //    n e^2 / 2, and balls of radius r packed by the greedy cover take about 4.6 r^2 each
  //    (measured); the radius is corrected once or twice if the count is off by over 25%.
  double sum = 0.0;
  for (float w : g.lengths)
    sum += w;
  const double mean_edge = g.lengths.empty() ? 1.0 : sum / static_cast<double>(g.lengths.size());
  double radius = mean_edge * std::sqrt(static_cast<double>(n) /
                                        (9.2 * static_cast<double>(num_representatives)));
  std::vector<float> dist(n, kInf), bound(n);
  BucketDijkstra search(g);
  std::vector<std::uint32_t> visit(n), reps;
  for (std::uint32_t v = 0; v < n; ++v)
    visit[tie_rank ? tie_rank[v] : v] = v;
  for (int attempt = 0; attempt < 3; ++attempt) {
    reps = coverByBalls(g, static_cast<float>(radius), visit, search, dist, bound);
    const double ratio =
        static_cast<double>(reps.size()) / static_cast<double>(num_representatives);
    if (ratio > 0.8 && ratio < 1.25)
      break;
    radius *= std::sqrt(ratio);
  }
  dist = std::vector<float>();
  bound = std::vector<float>();
  visit = std::vector<std::uint32_t>();

  // 2. The two nearest representatives of every vertex.
  const NearestSources near = nearestTwoSources(g, reps);

  // 3. The coarse graph: the shortest kNN path between neighbouring cells.
  std::vector<std::tuple<std::uint32_t, std::uint32_t, float>> edges;
  for (std::uint32_t u = 0; u < n; ++u)
    for (std::uint32_t e = g.offsets[u]; e < g.offsets[u + 1]; ++e) {
      const std::uint32_t v = g.targets[e];
      const std::uint32_t a = near.at[u].first, b = near.at[v].first;
      if (a < b)
        edges.emplace_back(a, b, near.at[u].first_dist + g.lengths[e] + near.at[v].first_dist);
    }
  std::sort(edges.begin(), edges.end());
  const std::size_t c = reps.size();
  CsrGraph coarse;
  coarse.offsets.assign(c + 1, 0);
  std::vector<std::tuple<std::uint32_t, std::uint32_t, float>> unique;
  for (std::size_t i = 0; i < edges.size(); ++i)
    if (i == 0 || std::get<0>(edges[i]) != std::get<0>(edges[i - 1]) ||
        std::get<1>(edges[i]) != std::get<1>(edges[i - 1])) // the shortest comes first
      unique.push_back(edges[i]);
  edges = {};
  for (const auto& [a, b, w] : unique) {
    ++coarse.offsets[a + 1];
    ++coarse.offsets[b + 1];
  }
  for (std::size_t i = 0; i < c; ++i)
    coarse.offsets[i + 1] += coarse.offsets[i];
  coarse.targets.resize(coarse.offsets[c]);
  coarse.lengths.resize(coarse.offsets[c]);
  std::vector<std::uint32_t> fill(coarse.offsets.begin(), coarse.offsets.end() - 1);
  for (const auto& [a, b, w] : unique) {
    coarse.targets[fill[a]] = b;
    coarse.lengths[fill[a]++] = w;
    coarse.targets[fill[b]] = a;
    coarse.lengths[fill[b]++] = w;
  }
  unique = {};
  std::vector<std::pair<std::uint32_t, float>> row;
  for (std::size_t i = 0; i < c; ++i) {
    row.clear();
    for (std::uint32_t e = coarse.offsets[i]; e < coarse.offsets[i + 1]; ++e)
      row.emplace_back(coarse.targets[e], coarse.lengths[e]);
    std::sort(row.begin(), row.end());
    std::uint32_t e = coarse.offsets[i];
    for (const auto& [t, w] : row) {
      coarse.targets[e] = t;
      coarse.lengths[e++] = w;
    }
  }

  // 4. Eq. (1) on the coarse graph.
  // Ties on the coarse graph follow the representatives' ranks.
  std::vector<std::uint32_t> coarse_rank(reps.size());
  {
    std::vector<std::uint32_t> by_rank(reps.size());
    std::iota(by_rank.begin(), by_rank.end(), 0u);
    auto rank = [&](std::uint32_t i) { return tie_rank ? tie_rank[reps[i]] : reps[i]; };
    std::sort(by_rank.begin(), by_rank.end(),
              [&](std::uint32_t a, std::uint32_t b) { return rank(a) < rank(b); });
    for (std::uint32_t i = 0; i < by_rank.size(); ++i)
      coarse_rank[by_rank[i]] = i;
  }
  const Centrality cc =
      computeCentrality(coarse, num_samples, num_threads, coarse_rank.data(), progress);

  // The coarse graph's paths zigzag through the representatives, so its distances exceed the
  // kNN graph's by a few percent. Measure the ratio on pairs of representatives 3 to 8 radii
  // apart, from 32 of them, with bounded searches on both graphs, and scale f by it.
  double fine_sum = 0.0, coarse_sum = 0.0;
  {
    std::vector<float> fine_dist(n, kInf), fine_bound(n, static_cast<float>(8.0 * radius));
    std::vector<float> coarse_dist(c, kInf), coarse_bound(c, static_cast<float>(12.0 * radius));
    BucketDijkstra coarse_search(coarse);
    std::vector<std::uint32_t> fine_touched, coarse_touched;
    const std::size_t step = std::max<std::size_t>(1, c / 32);
    for (std::size_t a = 0; a < c; a += step) {
      fine_touched.clear();
      coarse_touched.clear();
      search.run(reps[a], fine_dist.data(), fine_bound.data(), &fine_touched);
      coarse_search.run(static_cast<std::uint32_t>(a), coarse_dist.data(), coarse_bound.data(),
                        &coarse_touched);
      for (std::uint32_t b : coarse_touched) {
        const float fine = fine_dist[reps[b]];
        if (fine >= 3.0 * radius && fine <= 8.0 * radius) {
          fine_sum += fine;
          coarse_sum += coarse_dist[b];
        }
        coarse_dist[b] = kInf;
      }
      for (std::uint32_t v : fine_touched)
        fine_dist[v] = kInf;
    }
  }
  const float scale = coarse_sum > 0.0 ? static_cast<float>(fine_sum / coarse_sum) : 1.0f;

  // 5. Back to every vertex, linearly between its two nearest representatives.
  Centrality out;
  out.f.resize(n);
  for (std::uint32_t p = 0; p < n; ++p) {
    const float d1 = near.at[p].first_dist, d2 = near.at[p].second_dist;
    const float f1 = scale * cc.f[near.at[p].first];
    float f;
    if (near.at[p].second == kNoSource)
      f = d1; // the component's only representative is its only sample: f = g(p, r1)
    else if (d1 + d2 > 0.0f)
      f = (d2 * f1 + d1 * scale * cc.f[near.at[p].second]) / (d1 + d2);
    else
      f = f1;
    out.f[p] = f;
  }
  out.num_components = connectedComponents(graph, out.component);
  out.samples.reserve(cc.samples.size());
  for (std::uint32_t s : cc.samples)
    out.samples.push_back(reps[s]);
  return out;
}

} // namespace pcl_ncut_seg
