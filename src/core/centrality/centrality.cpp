// Sec. 4.1: farthest-point samples on graph distance and the mean geodesic distance, eq. (1).
#include "core/centrality/centrality.h"
#include "core/common/threads.h"
#include "core/graph/shortest_paths.h"

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

namespace {

/// Components as contiguous ranges of positions, and what eq. (1) needs per component.
struct Layout {
  std::vector<std::uint32_t> component;  ///< per vertex
  std::size_t num_components = 0;        ///<
  std::vector<std::uint32_t> begin;      ///< component c: positions [begin[c], begin[c + 1])
  std::vector<std::uint32_t> order, pos; ///< per position its vertex; per vertex its position
  std::vector<std::size_t> count;        ///< samples per component
  std::vector<std::size_t> first_task;   ///< per component, its first sample's task
  std::vector<double> quantum;           ///< per component, a fixed-point unit (set by start 0)
  const std::uint32_t* tie_rank = nullptr;
  std::uint32_t rank(std::uint32_t v) const { return tie_rank ? tie_rank[v] : v; }
  std::int64_t fixedPoint(float d, std::uint32_t c) const { // < 2^41
    return static_cast<std::int64_t>(static_cast<double>(d) * (1.0 / quantum[c]) + 0.5);
  }
};

/// Searches read the graph in vertex order, so the caller's order decides how well they use
/// the cache (the PCL front end numbers points along a Morton curve). Here components must be
/// contiguous ranges of positions (both number components in order of their smallest vertex);
/// `permuted` receives a copy of the graph only when they are not.
Layout componentLayout(const CsrGraph& graph, std::size_t num_samples,
                       const std::uint32_t* tie_rank, CsrGraph& permuted) {
  const std::size_t n = graph.numVertices();
  Layout l;
  l.tie_rank = tie_rank;
  l.num_components = connectedComponents(graph, l.component);
  l.begin.assign(l.num_components + 1, 0);
  for (std::uint32_t v = 0; v < n; ++v)
    ++l.begin[l.component[v] + 1];
  for (std::size_t c = 0; c < l.num_components; ++c)
    l.begin[c + 1] += l.begin[c];
  l.order.resize(n);
  l.pos.resize(n);
  std::vector<std::uint32_t> fill(l.begin.begin(), l.begin.end() - 1);
  bool contiguous = true;
  for (std::uint32_t v = 0; v < n; ++v) {
    l.pos[v] = fill[l.component[v]]++;
    l.order[l.pos[v]] = v;
    contiguous = contiguous && l.pos[v] == v;
  }
  if (!contiguous)
    permuted = permuteGraph(graph, l.order);
  // Samples per component, known before any search, so that the full searches (steps 5a-b)
  // can start while later samples are still being chosen.
  l.count.resize(l.num_components);
  l.first_task.assign(l.num_components + 1, 0);
  for (std::uint32_t c = 0; c < l.num_components; ++c) {
    const std::size_t size = l.begin[c + 1] - l.begin[c];
    l.count[c] = std::min(size, num_samples > 0 ? num_samples
                                                : static_cast<std::size_t>(std::ceil(
                                                      std::sqrt(static_cast<double>(size)))));
    l.first_task[c + 1] = l.first_task[c] + l.count[c];
  }
  l.quantum.assign(l.num_components, 1.0);
  return l;
}

/// Steps 4-5c: farthest-point chains over one component at a time. h is +inf outside a chain.
class Chains {
public:
  Chains(const CsrGraph& g, const Layout& l)
      : l_(l), h_(g.numVertices(), kInf), dist_(g.numVertices(), kInf), search_(g) {}

  /// The vertex of component c farthest from vertex v (ties to the smallest rank) and its
  /// distance in ecc; kNone when there is none (a single vertex, or every distance 0).
  std::uint32_t farthestFrom(std::uint32_t c, std::uint32_t v, float& ecc) {
    touched_.clear();
    search_.run(l_.pos[v], dist_.data(), nullptr, &touched_);
    ecc = 0.0f;
    const std::uint32_t far = argmax(c, dist_, ecc);
    for (std::uint32_t p : touched_)
      dist_[p] = kInf;
    return far;
  }

  /// count[c] samples of component c from `first`, each handed to emit(i, position) as soon
  /// as it is chosen.
  template <class Emit> void run(std::uint32_t c, std::uint32_t first, Emit&& emit) {
    std::uint32_t s = first;
    for (std::size_t i = 0; i < l_.count[c]; ++i) {
      if (i > 0) { // step 4: the vertex with the largest h, ties to the smallest rank
        float best = -1.0f;
        s = argmax(c, h_, best);
      }
      emit(i, l_.pos[s]);
      if (i + 1 == l_.count[c])
        break; // h is needed only to choose the next sample
      // Step 5c: h <- min(h, g(s, .)), searching only where h can still drop.
      touched_.clear();
      search_.run(l_.pos[s], dist_.data(), h_.data(), &touched_);
      for (std::uint32_t p : touched_) {
        h_[p] = std::min(h_[p], dist_[p]);
        dist_[p] = kInf;
      }
      h_[l_.pos[s]] = 0.0f;
    }
    for (std::uint32_t p = l_.begin[c]; p < l_.begin[c + 1]; ++p)
      h_[p] = kInf;
  }

private:
  /// The largest value of x over the component's positions, ties to the smallest rank.
  std::uint32_t argmax(std::uint32_t c, const std::vector<float>& x, float& best) const {
    std::uint32_t arg = kNone;
    for (std::uint32_t p = l_.begin[c]; p < l_.begin[c + 1]; ++p)
      if (x[p] > best || (x[p] == best && arg != kNone && l_.rank(l_.order[p]) < l_.rank(arg))) {
        best = x[p];
        arg = l_.order[p];
      }
    return arg;
  }

  const Layout& l_;
  std::vector<float> h_, dist_;
  std::vector<std::uint32_t> touched_;
  BucketDijkstra search_;
};

using Task = std::pair<std::uint32_t, std::uint32_t>; ///< (position, component)

/// A full search from each of num_tasks samples on `threads` threads, the tasks taken in
/// order. On thread t: prepare(t) first; then, per task i, taskAt(i) (which may wait until
/// task i exists) gives the sample, and read(t, i, d) reads its distances d on the sample's
/// component c, which are reset to +inf afterwards. The calling thread reports progress
/// share0 + share * (tasks done) / num_tasks.
template <class Prepare, class TaskAt, class Read>
void searchFromTasks(const CsrGraph& g, const Layout& l, std::size_t num_tasks, int threads,
                     Prepare prepare, TaskAt taskAt, Read read, const ProgressFn& progress,
                     double share0, double share) {
  std::atomic<std::size_t> next{0}, done{0};
#pragma omp parallel num_threads(threads)
  {
    int t = 0;
#ifdef _OPENMP
    t = omp_get_thread_num();
#endif
    prepare(t);
    std::vector<float> d(g.numVertices(), kInf);
    BucketDijkstra full(g);
    for (std::size_t i = next++; i < num_tasks; i = next++) {
      const Task task = taskAt(i);
      full.run(task.first, d.data());
      read(t, i, d);
      for (std::uint32_t p = l.begin[task.second]; p < l.begin[task.second + 1]; ++p)
        d[p] = kInf;
      const std::size_t finished = ++done;
      if (t == 0 && progress) // the calling thread reports
        progress(share0 + share * static_cast<double>(finished) / static_cast<double>(num_tasks));
    }
  }
}

/// Start 0: its samples (tasks, in the order chosen) and, per position, the fixed-point sum of
/// the distances to them (steps 5a-b). The full searches are summed in fixed point so that
/// the sum does not depend on the order, hence not on the number of threads. The calling
/// thread chooses the samples (and sets the quantum); the others search from those already
/// chosen meanwhile.
std::vector<std::int64_t> startZeroSums(const CsrGraph& g, Layout& l, Chains& chains,
                                        std::vector<Task>& tasks, unsigned num_threads,
                                        const ProgressFn& progress, double share) {
  const std::size_t n = g.numVertices();
  const std::size_t num_tasks = l.first_task[l.num_components];
  tasks.assign(num_tasks, {0, 0});
  std::atomic<std::size_t> published{0}; // tasks[0, published) are chosen
  auto chooseSamples = [&]() {
    for (std::uint32_t c = 0; c < l.num_components; ++c) {
      // First sample: farthest from the component's smallest-rank vertex (a deterministic
      // choice for the arbitrary tie of step 4 when h is infinite everywhere).
      std::uint32_t smallest = l.order[l.begin[c]];
      for (std::uint32_t p = l.begin[c]; p < l.begin[c + 1]; ++p)
        if (l.rank(l.order[p]) < l.rank(smallest))
          smallest = l.order[p];
      float ecc = 0.0f;
      std::uint32_t first = chains.farthestFrom(c, smallest, ecc);
      if (first == kNone)
        first = smallest;
      // Any geodesic distance in the component is at most 2 * ecc (triangle inequality).
      if (ecc > 0.0f)
        l.quantum[c] = 2.0 * ecc / static_cast<double>(std::int64_t(1) << 40);
      chains.run(c, first, [&](std::size_t i, std::uint32_t position) {
        tasks[l.first_task[c] + i] = {position, c};
        published.store(l.first_task[c] + i + 1, std::memory_order_release);
      });
    }
  };
  const int threads =
      std::max(1, std::min<int>(usableThreads(num_threads), static_cast<int>(num_tasks)));
  std::vector<std::vector<std::int64_t>> partial(threads);
  searchFromTasks(
      g, l, num_tasks, threads,
      [&](int t) {
        if (t == 0)
          chooseSamples();
        partial[t].assign(n, 0);
      },
      [&](std::size_t i) {
        while (published.load(std::memory_order_acquire) <= i)
          std::this_thread::yield(); // the calling thread is still choosing sample i
        return tasks[i];
      },
      [&](int t, std::size_t i, const std::vector<float>& d) {
        const std::uint32_t c = tasks[i].second;
        for (std::uint32_t p = l.begin[c]; p < l.begin[c + 1]; ++p)
          partial[t][p] += l.fixedPoint(d[p], c);
      },
      progress, 0.0, share);
  std::vector<std::int64_t> sum(n, 0);
  for (const auto& acc : partial)
    for (std::uint32_t p = 0; p < n; ++p)
      sum[p] += acc[p];
  return sum;
}

/// Starts 1 .. num_starts - 1 (core/centrality/starts.h): start j's chain begins at start 0's j-th
/// sample of each component (its last one when it has fewer). Its sums are start 0's minus the
/// samples it lacks plus those it adds: only the samples that differ are searched, and in
/// fixed point the result is exactly the sum over its own samples. Fills samples[j] and
/// sums[j] for j >= 1.
void otherStartSums(const CsrGraph& g, const Layout& l, Chains& chains,
                    const std::vector<Task>& start0, unsigned num_threads,
                    const ProgressFn& progress, double share,
                    std::vector<std::vector<Task>>& samples,
                    std::vector<std::vector<std::int64_t>>& sums) {
  const std::size_t n = g.numVertices(), num_starts = sums.size();
  std::vector<std::int32_t> in0(n, 0), inj(n, 0); // per position, times sampled
  for (const Task& t : start0)
    ++in0[t.first];
  std::vector<Task> extra;          // the samples to search again
  std::vector<std::int32_t> weight; // extra-major, num_starts each: times added per start
  std::vector<std::uint32_t> extra_of(n, kNone);
  auto add = [&](const Task& t, std::size_t j, std::int32_t w) {
    if (extra_of[t.first] == kNone) {
      extra_of[t.first] = static_cast<std::uint32_t>(extra.size());
      extra.push_back(t);
      weight.resize(weight.size() + num_starts, 0);
    }
    weight[std::size_t(extra_of[t.first]) * num_starts + j] += w;
  };
  for (std::size_t j = 1; j < num_starts; ++j) {
    for (std::uint32_t c = 0; c < l.num_components; ++c) {
      const std::size_t i = l.first_task[c] + std::min<std::size_t>(j, l.count[c] - 1);
      chains.run(c, l.order[start0[i].first], [&](std::size_t, std::uint32_t position) {
        samples[j].emplace_back(position, c);
      });
    }
    for (const Task& t : samples[j])
      ++inj[t.first];
    for (const Task& t : samples[j])
      if (inj[t.first] != in0[t.first])
        add(t, j, inj[t.first] - in0[t.first]);
    for (const Task& t : start0)
      if (inj[t.first] == 0)
        add(t, j, -in0[t.first]);
    for (const Task& t : samples[j])
      inj[t.first] = 0;
  }
  const int threads =
      std::max(1, std::min<int>(usableThreads(num_threads), static_cast<int>(extra.size())));
  std::vector<std::vector<std::int64_t>> diff(std::size_t(threads) * num_starts);
  searchFromTasks(
      g, l, extra.size(), threads,
      [&](int t) {
        for (std::size_t j = 1; j < num_starts; ++j)
          diff[std::size_t(t) * num_starts + j].assign(n, 0);
      },
      [&](std::size_t i) { return extra[i]; },
      [&](int t, std::size_t i, const std::vector<float>& d) {
        const std::uint32_t c = extra[i].second;
        for (std::size_t j = 1; j < num_starts; ++j)
          if (const std::int32_t w = weight[i * num_starts + j]; w != 0) {
            std::vector<std::int64_t>& acc = diff[std::size_t(t) * num_starts + j];
            for (std::uint32_t p = l.begin[c]; p < l.begin[c + 1]; ++p)
              acc[p] += w * l.fixedPoint(d[p], c);
          }
      },
      progress, share, 1.0 - share);
  for (std::size_t j = 1; j < num_starts; ++j) {
    sums[j] = sums[0];
    for (int t = 0; t < threads; ++t)
      for (std::uint32_t p = 0; p < n && !diff[std::size_t(t) * num_starts + j].empty(); ++p)
        sums[j][p] += diff[std::size_t(t) * num_starts + j][p];
  }
}

} // namespace

std::vector<Centrality> computeCentralities(const CsrGraph& graph, std::size_t num_samples,
                                            unsigned num_threads, const std::uint32_t* tie_rank,
                                            const ProgressFn& progress, std::size_t num_starts) {
  const std::size_t n = graph.numVertices();
  num_starts = std::max<std::size_t>(num_starts, 1);
  std::vector<Centrality> all(num_starts);
  if (n == 0)
    return all;
  CsrGraph permuted;
  Layout l = componentLayout(graph, num_samples, tie_rank, permuted);
  const CsrGraph& g = permuted.numVertices() == n ? permuted : graph;
  Chains chains(g, l);
  const double share = num_starts > 1 ? 0.5 : 1.0; // of the progress: the rest for the others
  std::vector<std::vector<Task>> samples(num_starts);
  std::vector<std::vector<std::int64_t>> sums(num_starts);
  sums[0] = startZeroSums(g, l, chains, samples[0], num_threads, progress, share);
  if (num_starts > 1)
    otherStartSums(g, l, chains, samples[0], num_threads, progress, share, samples, sums);
  for (std::size_t j = 0; j < num_starts; ++j) {
    Centrality& cj = all[j];
    cj.num_components = l.num_components;
    cj.component = l.component;
    cj.f.resize(n);
    for (std::uint32_t v = 0; v < n; ++v) {
      const std::uint32_t c = l.component[v];
      cj.f[v] = static_cast<float>(static_cast<double>(sums[j][l.pos[v]]) * l.quantum[c] /
                                   static_cast<double>(l.count[c]));
    }
    for (const Task& t : samples[j])
      cj.samples.push_back(l.order[t.first]);
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
