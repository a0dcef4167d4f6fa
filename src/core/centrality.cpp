// Sec. 4.1: farthest-point samples on graph distance and the mean geodesic distance, eq. (1).
#include <pcl_ncut_seg/core/centrality.h>
#include <pcl_ncut_seg/core/shortest_paths.h>
#include <pcl_ncut_seg/core/threads.h>

#include <boost/graph/compressed_sparse_row_graph.hpp>
#include <boost/graph/dijkstra_shortest_paths_no_color_map.hpp>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <limits>
#include <thread>

#ifdef _OPENMP
#include <omp.h>
#endif

namespace pcl_ncut_seg {
namespace {
constexpr std::uint32_t kNone = std::numeric_limits<std::uint32_t>::max();

using BoostGraph =
    boost::compressed_sparse_row_graph<boost::directedS, boost::no_property, boost::no_property,
                                       boost::no_property, std::uint32_t, std::uint32_t>;
constexpr float kInf = std::numeric_limits<float>::infinity();

BoostGraph toBoost(const CsrGraph& graph) {
  std::vector<std::pair<std::uint32_t, std::uint32_t>> edges;
  edges.reserve(graph.numDirectedEdges());
  for (std::uint32_t v = 0; v < graph.numVertices(); ++v)
    for (std::uint32_t e = graph.offsets[v]; e < graph.offsets[v + 1]; ++e)
      edges.emplace_back(v, graph.targets[e]);
  // Rows are already sorted, so Boost's edge index equals the CSR position in `graph`.
  return BoostGraph(boost::edges_are_sorted, edges.begin(), edges.end(),
                    static_cast<std::uint32_t>(graph.numVertices()));
}

/// Dijkstra from `source`; dist must be +inf on the source's component and is left filled.
template <class WeightMap, class Visitor>
void dijkstra(const BoostGraph& g, std::uint32_t source, float* dist, WeightMap weight,
              Visitor visitor) {
  dist[source] = 0.0f;
  boost::dijkstra_shortest_paths_no_color_map_no_init(
      g, source, boost::dummy_property_map(), dist, weight, boost::get(boost::vertex_index, g),
      std::less<float>(), std::plus<float>(), kInf, 0.0f, visitor);
}

} // namespace

std::vector<float> geodesicDistances(const CsrGraph& graph, std::uint32_t source) {
  const BoostGraph g = toBoost(graph);
  std::vector<float> dist(graph.numVertices(), kInf);
  dijkstra(
      g, source, dist.data(),
      boost::make_iterator_property_map(graph.lengths.data(), boost::get(boost::edge_index, g)),
      boost::default_dijkstra_visitor());
  return dist;
}

std::vector<Centrality> computeCentralities(const CsrGraph& graph, std::size_t num_samples,
                                            unsigned num_threads, const std::uint32_t* tie_rank,
                                            const ProgressFn& progress, std::size_t num_starts) {
  const std::size_t n = graph.numVertices();
  num_starts = std::max<std::size_t>(num_starts, 1);
  std::vector<Centrality> all(num_starts);
  Centrality& out = all[0];
  out.f.assign(n, 0.0f);
  if (n == 0) {
    for (Centrality& c : all)
      c.f.clear();
    return all;
  }
  out.num_components = connectedComponents(graph, out.component);
  // Searches read the graph in vertex order, so the caller's order decides how well they use
  // the cache (the PCL front end numbers points along a Morton curve). Here components must
  // be contiguous ranges of positions: component c occupies [begin[c], begin[c + 1]) (both
  // number components in order of their smallest vertex). The graph is copied only when they
  // are not. Distances do not depend on the numbering; ties below go to the smallest rank.
  std::vector<std::uint32_t> begin(out.num_components + 1, 0);
  for (std::uint32_t v = 0; v < n; ++v)
    ++begin[out.component[v] + 1];
  for (std::size_t c = 0; c < out.num_components; ++c)
    begin[c + 1] += begin[c];
  std::vector<std::uint32_t> order(n), pos(n);
  {
    std::vector<std::uint32_t> fill(begin.begin(), begin.end() - 1);
    for (std::uint32_t v = 0; v < n; ++v) {
      pos[v] = fill[out.component[v]]++;
      order[pos[v]] = v;
    }
  }
  bool contiguous = true;
  for (std::uint32_t v = 0; v < n && contiguous; ++v)
    contiguous = pos[v] == v;
  CsrGraph permuted;
  if (!contiguous)
    permuted = permuteGraph(graph, order);
  const CsrGraph& g = contiguous ? graph : permuted;

  // Ties go to the smallest rank (the caller's, or the vertex index).
  auto rank = [tie_rank](std::uint32_t v) { return tie_rank ? tie_rank[v] : v; };
  std::vector<std::uint32_t> smallest(out.num_components, kNone); // per component
  for (std::uint32_t v = 0; v < n; ++v) {
    std::uint32_t& m = smallest[out.component[v]];
    if (m == kNone || rank(v) < rank(m))
      m = v;
  }
  // Samples per component, known before any search, so that the full searches (steps 5a-b)
  // can start while later samples are still being chosen.
  std::vector<std::size_t> count(out.num_components), first_task(out.num_components + 1, 0);
  for (std::uint32_t c = 0; c < out.num_components; ++c) {
    const std::size_t size = begin[c + 1] - begin[c];
    count[c] = std::min(size, num_samples > 0 ? num_samples
                                              : static_cast<std::size_t>(std::ceil(
                                                    std::sqrt(static_cast<double>(size)))));
    first_task[c + 1] = first_task[c] + count[c];
  }
  const std::size_t num_tasks = first_task[out.num_components];
  std::vector<std::pair<std::uint32_t, std::uint32_t>> tasks(num_tasks); // (position, component)
  // Per component, a fixed-point quantum that bounds every distance in it.
  std::vector<double> quantum(out.num_components, 1.0);
  std::atomic<std::size_t> published{0}; // tasks[0, published) are chosen

  // Steps 4-5c of one start: count[c] farthest-point samples of component c from `first`,
  // each handed to emit(i, position) as soon as it is chosen. h is +inf on the component
  // before and after.
  std::vector<float> h(n, kInf), dist(n, kInf);
  std::vector<std::uint32_t> touched;
  BucketDijkstra search(g);
  // The largest value of x over the component's positions, ties to the smallest rank.
  auto argmax = [&](std::uint32_t c, const std::vector<float>& x, float& best) {
    std::uint32_t arg = kNone;
    for (std::uint32_t p = begin[c]; p < begin[c + 1]; ++p)
      if (x[p] > best || (x[p] == best && arg != kNone && rank(order[p]) < rank(arg))) {
        best = x[p];
        arg = order[p];
      }
    return arg;
  };
  auto chain = [&](std::uint32_t c, std::uint32_t first, auto&& emit) {
    std::uint32_t s = first;
    for (std::size_t i = 0; i < count[c]; ++i) {
      if (i > 0) { // step 4: the vertex with the largest h, ties to the smallest index
        float best = -1.0f;
        s = argmax(c, h, best);
      }
      emit(i, pos[s]);
      if (i + 1 == count[c])
        break; // h is needed only to choose the next sample
      // Step 5c: h <- min(h, g(s, .)), searching only where h can still drop.
      touched.clear();
      search.run(pos[s], dist.data(), h.data(), &touched);
      for (std::uint32_t p : touched) {
        h[p] = std::min(h[p], dist[p]);
        dist[p] = kInf;
      }
      h[pos[s]] = 0.0f;
    }
    for (std::uint32_t p = begin[c]; p < begin[c + 1]; ++p)
      h[p] = kInf;
  };
  auto chooseSamples = [&]() {
    for (std::uint32_t c = 0; c < out.num_components; ++c) {
      // First sample: farthest from the component's smallest-rank vertex (a deterministic
      // choice for the arbitrary tie of step 4 when h is infinite everywhere).
      touched.clear();
      search.run(pos[smallest[c]], dist.data(), nullptr, &touched);
      float ecc = 0.0f;
      std::uint32_t first = argmax(c, dist, ecc);
      if (first == kNone) // a single vertex, or every distance 0
        first = smallest[c];
      for (std::uint32_t p : touched)
        dist[p] = kInf;
      // Any geodesic distance in the component is at most 2 * ecc (triangle inequality).
      if (ecc > 0.0f)
        quantum[c] = 2.0 * ecc / static_cast<double>(std::int64_t(1) << 40);
      chain(c, first, [&](std::size_t i, std::uint32_t position) {
        tasks[first_task[c] + i] = {position, c};
        published.store(first_task[c] + i + 1, std::memory_order_release);
      });
      // The next component's searches do not reach this one: its h can stay as it is.
    }
  };

  // Steps 5a-b: full searches from every sample, summed in fixed point so that the sum does
  // not depend on the order, hence not on the number of threads. The calling thread chooses
  // the samples first; the others search from those already chosen meanwhile.
  const int threads =
      std::max(1, std::min<int>(usableThreads(num_threads), static_cast<int>(num_tasks)));
  auto fixedPoint = [&](float d, std::uint32_t c) { // < 2^41
    return static_cast<std::int64_t>(static_cast<double>(d) / quantum[c] + 0.5);
  };
  std::vector<std::vector<std::int64_t>> partial(threads);
  std::atomic<std::size_t> next{0}, done{0};
  const double share = num_starts > 1 ? 0.5 : 1.0; // of the progress: the rest for the others
#pragma omp parallel num_threads(threads)
  {
    int t = 0;
#ifdef _OPENMP
    t = omp_get_thread_num();
#endif
    if (t == 0)
      chooseSamples();
    std::vector<std::int64_t>& acc = partial[t];
    acc.assign(n, 0);
    std::vector<float> d(n, kInf);
    BucketDijkstra full(g);
    for (std::size_t i = next++; i < num_tasks; i = next++) {
      while (published.load(std::memory_order_acquire) <= i)
        std::this_thread::yield(); // the calling thread is still choosing sample i
      const auto [sample, c] = tasks[i];
      full.run(sample, d.data());
      for (std::uint32_t p = begin[c]; p < begin[c + 1]; ++p) {
        acc[p] += fixedPoint(d[p], c);
        d[p] = kInf;
      }
      const std::size_t finished = ++done;
      if (t == 0 && progress) // the calling thread reports
        progress(share * static_cast<double>(finished) / static_cast<double>(num_tasks));
    }
  }
  std::vector<std::int64_t> sum0(n, 0);
  for (const auto& acc : partial)
    for (std::uint32_t p = 0; p < n; ++p)
      sum0[p] += acc[p];
  partial.clear();
  std::vector<std::vector<std::uint32_t>> sample_positions(num_starts);
  for (const auto& task : tasks)
    sample_positions[0].push_back(task.first);
  std::vector<std::vector<std::int64_t>> sums(num_starts);
  sums[0] = std::move(sum0);

  // Other starts (core/starts.h): start j's chain begins at start 0's j-th sample of each
  // component (its last one when it has fewer). Its sums are start 0's minus the samples it
  // lacks plus those it adds: only the samples that differ are searched, and in fixed point
  // the result is exactly the sum over its own samples.
  if (num_starts > 1) {
    std::vector<std::int32_t> in0(n, 0), inj(n, 0); // per position, times sampled
    for (std::uint32_t p : sample_positions[0])
      ++in0[p];
    std::vector<std::pair<std::uint32_t, std::uint32_t>> extra; // (position, component)
    std::vector<std::int32_t> weight;                           // extra-major, num_starts each
    std::vector<std::uint32_t> extra_of(n, kNone);
    auto add = [&](std::uint32_t p, std::size_t j, std::int32_t w) {
      if (extra_of[p] == kNone) {
        extra_of[p] = static_cast<std::uint32_t>(extra.size());
        extra.emplace_back(p, out.component[order[p]]);
        weight.resize(weight.size() + num_starts, 0);
      }
      weight[std::size_t(extra_of[p]) * num_starts + j] += w;
    };
    for (std::size_t j = 1; j < num_starts; ++j) {
      for (std::uint32_t c = 0; c < out.num_components; ++c) {
        const std::size_t i = first_task[c] + std::min<std::size_t>(j, count[c] - 1);
        chain(c, order[tasks[i].first], [&](std::size_t, std::uint32_t position) {
          sample_positions[j].push_back(position);
        });
      }
      for (std::uint32_t p : sample_positions[j])
        ++inj[p];
      for (std::uint32_t p : sample_positions[j])
        if (inj[p] != in0[p])
          add(p, j, inj[p] - in0[p]);
      for (std::uint32_t p : sample_positions[0])
        if (inj[p] == 0)
          add(p, j, -in0[p]);
      for (std::uint32_t p : sample_positions[j])
        inj[p] = 0;
    }
    const int extra_threads =
        std::max(1, std::min<int>(usableThreads(num_threads), static_cast<int>(extra.size())));
    std::vector<std::vector<std::int64_t>> diff(std::size_t(extra_threads) * num_starts);
    std::atomic<std::size_t> extra_next{0}, extra_done{0};
#pragma omp parallel num_threads(extra_threads)
    {
      int t = 0;
#ifdef _OPENMP
      t = omp_get_thread_num();
#endif
      for (std::size_t j = 1; j < num_starts; ++j)
        diff[std::size_t(t) * num_starts + j].assign(n, 0);
      std::vector<float> d(n, kInf);
      BucketDijkstra full(g);
      for (std::size_t i = extra_next++; i < extra.size(); i = extra_next++) {
        const auto [sample, c] = extra[i];
        full.run(sample, d.data());
        for (std::size_t j = 1; j < num_starts; ++j) {
          const std::int32_t w = weight[i * num_starts + j];
          if (w == 0)
            continue;
          std::vector<std::int64_t>& acc = diff[std::size_t(t) * num_starts + j];
          for (std::uint32_t p = begin[c]; p < begin[c + 1]; ++p)
            acc[p] += w * fixedPoint(d[p], c);
        }
        for (std::uint32_t p = begin[c]; p < begin[c + 1]; ++p)
          d[p] = kInf;
        const std::size_t finished = ++extra_done;
        if (t == 0 && progress)
          progress(share + (1.0 - share) * static_cast<double>(finished) /
                               static_cast<double>(extra.size()));
      }
    }
    for (std::size_t j = 1; j < num_starts; ++j) {
      sums[j] = sums[0];
      for (int t = 0; t < extra_threads; ++t) {
        const std::vector<std::int64_t>& acc = diff[std::size_t(t) * num_starts + j];
        for (std::uint32_t p = 0; p < n && !acc.empty(); ++p)
          sums[j][p] += acc[p];
      }
    }
  }

  for (std::size_t j = 0; j < num_starts; ++j) {
    Centrality& cj = all[j];
    cj.num_components = out.num_components;
    if (j > 0)
      cj.component = out.component;
    cj.f.assign(n, 0.0f);
    for (std::uint32_t v = 0; v < n; ++v) {
      const std::uint32_t c = out.component[v];
      cj.f[v] = static_cast<float>(static_cast<double>(sums[j][pos[v]]) * quantum[c] /
                                   static_cast<double>(count[c]));
    }
    cj.samples.clear();
    for (std::uint32_t p : sample_positions[j])
      cj.samples.push_back(order[p]);
  }
  if (progress)
    progress(1.0);
  return all;
}

Centrality computeCentrality(const CsrGraph& graph, std::size_t num_samples, unsigned num_threads,
                             const std::uint32_t* tie_rank, const ProgressFn& progress) {
  return std::move(
      computeCentralities(graph, num_samples, num_threads, tie_rank, progress, 1).front());
}

} // namespace pcl_ncut_seg
