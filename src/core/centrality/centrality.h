/*
 * pcl_ncut_seg: the feature-identifying function of Sec. 4.1 (centrality), eq. (1).
 */
#pragma once

#include "core/graph/csr_graph.h"

#include <cstdint>
#include <functional>
#include <vector>

namespace pcl_ncut_seg {

/** \brief Progress report: the fraction in [0, 1] of the work done. */
using ProgressFn = std::function<void(double)>;

/** \brief Output of computeCentrality(). */
struct Centrality {
  std::vector<float> f; ///< per vertex, mean geodesic distance to the samples, eq. (1)
  std::vector<std::uint32_t> samples;   ///< the farthest-point samples U, in the order chosen
  std::vector<std::uint32_t> component; ///< per vertex, its connected component
  std::size_t num_components = 0;
};

/** \brief Progress callback: the fraction of the work done, in [0, 1]. */
using ProgressFn = std::function<void(double)>;

/** \brief Approximate centrality f(p) = 1/|U| sum_{q in U} g(p, q) (eq. 1).
 *
 * Each connected component is treated as its own surface: it gets ceil(sqrt(n_c)) samples (or
 * the given number, capped at n_c), chosen by farthest-point sampling on graph distance, and f is
 * averaged over the samples of the vertex's component only. The first sample of a component is
 * the vertex farthest from its smallest-index vertex (ties: smallest index; see tie_rank), so
 * the choice is deterministic. Searches use Dial's bucket queue (BucketDijkstra, the same
 * distances as geodesicDistances()); sampling uses bounded searches; the full searches run in
 * parallel, starting while the calling thread still chooses later samples, and are summed in
 * fixed point, so f is bit-identical for any number of threads.
 *
 * \param[in] graph        the kNN graph
 * \param[in] num_samples  samples per component; 0 = ceil(sqrt(n_c))
 * \param[in] num_threads  threads for the full searches; 0 = all available
 * \param[in] tie_rank     if given, n distinct ranks: ties (the smallest vertex above) go to
 *                         the smallest rank instead of the smallest index, so that the result
 *                         does not depend on how the caller numbered the vertices
 * \param[in] progress     if set, called from the calling thread with the fraction of the full
 *                         searches done
 */
Centrality computeCentrality(const CsrGraph& graph, std::size_t num_samples, unsigned num_threads,
                             const std::uint32_t* tie_rank = nullptr,
                             const ProgressFn& progress = {});

/** \brief computeCentrality() from num_starts starts of step 4 (core/centrality/starts.h): start 0
 * is computeCentrality()'s; start j's first sample in each component is start 0's j-th sample (its
 * last when the component has fewer). Each start's f is bit-identical to a search from each of its
 * samples, but only the samples in which a start differs from start 0 are searched again (starts
 * often share most of their samples, and some come back to start 0's set). \return num_starts
 * centralities (at least one) */
std::vector<Centrality> computeCentralities(const CsrGraph& graph, std::size_t num_samples,
                                            unsigned num_threads,
                                            const std::uint32_t* tie_rank = nullptr,
                                            const ProgressFn& progress = {},
                                            std::size_t num_starts = 1);

/** \brief Single-source shortest path lengths with Boost.Graph's Dijkstra: the reference the
 * tests and benchmarks check the hand-written searches (core/graph/shortest_paths.h) against;
 * no stage calls it. Unreachable vertices get +infinity. */
std::vector<float> geodesicDistances(const CsrGraph& graph, std::uint32_t source);

} // namespace pcl_ncut_seg
