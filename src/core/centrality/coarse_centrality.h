/*
 * pcl_ncut_seg: a fast approximation of the centrality of Sec. 4.1 on a coarsened graph.
 */
#pragma once

#include "core/centrality/centrality.h"

namespace pcl_ncut_seg {

/// Points of the coarse graph in the pipeline's fast centrality: f within about 1-2% of the
/// exact one's at a fraction of its searches (test_shortest_paths measures both).
constexpr std::size_t kFastCentralityRepresentatives = 20000;

/// Whether a coarse graph of about num_representatives vertices pays for n: its cover settles on
/// 0.8-1.25 times that many, so up to 1.25 times as many points it could keep them all, and its
/// searches would cost what the exact ones do, with the cover and the carrying back on top.
inline bool coarseGraphPays(std::size_t n, std::size_t num_representatives) {
  return num_representatives > 0 && n > num_representatives + num_representatives / 4;
}

/** \brief The default centrality: eq. (1) computed exactly (as computeCentrality()) on a
 * coarse graph of about num_representatives vertices, then carried back to every point.
 *
 * 1. Representatives: a greedy cover of the graph by geodesic balls of one radius, visiting the
 *    vertices in ascending tie_rank (see computeCentrality(); default the index); the radius is set
 * so that about num_representatives balls cover the graph. Representatives are at least one radius
 * apart.
 * 2. Every vertex finds its two nearest representatives r1, r2 at graph distances d1 <= d2
 *    (a two-label multi-source search; equal distances go to the earlier representative).
 * Steps 1-3 and 5 run in parallel; each gives the same result for any number of threads.
 * 3. The coarse graph joins the representatives of neighbouring cells (r1 differs across a kNN
 *    edge (u, v)) with the shortest such path, d1(u) + |uv| + d1(v).
 * 4. f is computed on the coarse graph with computeCentrality() (num_samples samples per
 *    component, 0 = ceil(sqrt) of the coarse component's size).
 * 5. f(p) = (d2 f(r1) + d1 f(r2)) / (d1 + d2): linear along the geodesic from r1 to r2, so f
 *    keeps its slope and gains no plateaus or spurious extrema at the representatives. A
 *    component with a single representative gets f(p) = d1 (its one sample's distance).
 *
 * When !coarseGraphPays(n, num_representatives) this is computeCentrality().
 * Samples are returned as vertex ids of the input graph. Deterministic for any number of
 * threads.
 */
Centrality computeCoarseCentrality(const CsrGraph& graph, std::size_t num_representatives,
                                   std::size_t num_samples, unsigned num_threads,
                                   const std::uint32_t* tie_rank = nullptr,
                                   const ProgressFn& progress = {});

/** \brief computeCoarseCentrality() from num_starts starts (computeCentralities() on the coarse
 * graph, which is built once). */
std::vector<Centrality> computeCoarseCentralities(const CsrGraph& graph,
                                                  std::size_t num_representatives,
                                                  std::size_t num_samples, unsigned num_threads,
                                                  const std::uint32_t* tie_rank = nullptr,
                                                  const ProgressFn& progress = {},
                                                  std::size_t num_starts = 1);

} // namespace pcl_ncut_seg
