#include "core/pipeline/analysis_stages.h"
#include "core/cut/thickness.h"
#include "core/graph/bridging.h"

#include "core/centrality/coarse_centrality.h"
#include "core/common/stopwatch.h"
#include "core/common/threads.h"
#include "core/cut/boundary_refinement.h"
#include "core/cut/concavity.h"
#include "core/graph/denoise.h"
#include "core/supernodes/crease_split.h"
#include "core/supernodes/refinement.h"
#include "core/views/rim_merge.h"

namespace pcl_ncut_seg {

CsrGraph graphStage(std::vector<float>& xyz, const std::uint32_t* knn, std::size_t k,
                    const GraphParams& params, bool may_denoise, unsigned num_threads,
                    NoiseTest* noise) {
  const std::size_t n = xyz.size() / 3;
  const int threads = usableThreads(num_threads);
  CsrGraph graph = buildSymmetricKnnGraph(xyz.data(), n, knn, k, threads);
  NoiseTest test;
  RingFits fits;
  if (may_denoise && params.irregular_sampling) {
    test.sampling_irregularity = samplingIrregularity(graph);
    test.irregular = test.sampling_irregularity >= *params.irregular_sampling;
  }
  if (may_denoise && params.denoise) {
    test.residual_growth = residualGrowth(graph, xyz.data(), num_threads, &fits);
    test.projected = isNoisy(test.residual_growth, *params.denoise);
  }
  if (test.projected) {
    xyz = projectOntoLocalPlanes(graph, xyz.data(), num_threads, &fits);
    measureLengths(graph, xyz.data()); // the same graph, its lengths between the moved points
  }
  if (noise)
    *noise = test;
  if (params.bridge_gap)
    bridgeComponents(graph, xyz.data(), *params.bridge_gap);
  return graph;
}

namespace {
void report(const PhaseProgressFn& progress, const char* phase, double fraction) {
  if (progress)
    progress(phase, fraction);
}
} // namespace

std::vector<Centrality> centralityStage(const CsrGraph& graph, const Parameters& params,
                                        const std::uint32_t* tie_rank, PhaseTimes& times,
                                        const PhaseProgressFn& progress, std::size_t num_starts,
                                        bool noisy) {
  Stopwatch clock;
  report(progress, "Cen", 0.0);
  ProgressFn fraction;
  if (progress)
    fraction = [&progress](double done) { progress("Cen", done); };
  const CentralityParams& c = params.centrality;
  const auto samples = static_cast<std::size_t>(c.samples.value_or(0));
  const unsigned threads = params.execution.num_threads;
  std::vector<Centrality> f =
      c.mode == CentralityMode::Exact
          ? computeCentralities(graph, samples, threads, tie_rank, fraction, num_starts)
          : computeCoarseCentralities(graph, kFastCentralityRepresentatives, samples, threads,
                                      tie_rank, fraction, num_starts);
  if (noisy) // the noise's own share of f, taken out at the scale it was found at
    for (Centrality& one : f)
      one.f = neighbourhoodMean(graph, one.f, threads);
  report(progress, "Cen", 1.0);
  times.centrality += clock.lap();
  return f;
}

Analysis supernodeStage(std::shared_ptr<const CsrGraph> graph, Centrality centrality,
                        const Parameters& params, PhaseTimes& times) {
  Stopwatch clock;
  Analysis a;
  a.graph = std::move(graph);
  a.centrality = std::move(centrality);
  a.raw_supernodes =
      extractSupernodes(*a.graph, a.centrality.f, params.supernodes.crossing_fraction);
  times.supernodes += clock.lap();
  return a;
}

void refinementStage(Analysis& a, const Parameters& params, PhaseTimes& times) {
  Stopwatch clock;
  const unsigned threads = params.execution.num_threads;
  a.radii = pointRadii(*a.graph, a.centrality.f, threads);
  a.supernodes =
      refineSupernodes(*a.graph, a.centrality.f, a.radii, a.raw_supernodes, params.refinement);
  a.stats = featureStats(a.supernodes, a.centrality.f, a.radii);
  a.conn = supernodeConnectivity(*a.graph, a.centrality.f, a.supernodes.label, threads);
  times.refinement += clock.lap();
}

Analysis featureStages(CsrGraph graph, Centrality centrality, const Parameters& params,
                       PhaseTimes& times, const PhaseProgressFn& progress) {
  report(progress, "Snod", 0.0);
  Analysis a = supernodeStage(std::make_shared<const CsrGraph>(std::move(graph)),
                              std::move(centrality), params, times);
  report(progress, "Snod", 1.0);
  report(progress, "LRef", 0.0);
  refinementStage(a, params, times);
  report(progress, "LRef", 1.0);
  return a;
}

SurfaceBends surfaceBends(const CsrGraph& graph, const float* xyz, unsigned num_threads,
                          const float* viewpoint, bool thickness) {
  SurfaceBends b;
  b.normals = orientedNormals(graph, xyz, num_threads, viewpoint);
  if (thickness)
    b.medial_radii = medialRadii(xyz, graph.numVertices(), b.normals, num_threads);
  b.typical_bend = meanAbsBend(graph, xyz, b.normals, num_threads);
  return b;
}

void creaseStage(Analysis& a, const float* xyz, const SurfaceBends& bends,
                 const Parameters& params) {
  CreaseSplitParams crease;
  crease.typical_bend = bends.typical_bend;
  crease.min_concavity = params.refinement.crease_split.value_or(0.0);
  crease.area_fraction = params.refinement.area_fraction;
  crease.num_threads = params.execution.num_threads;
  std::size_t splits = 0;
  a.supernodes = splitAtCreases(*a.graph, xyz, bends.normals, a.centrality.f, a.radii, a.supernodes,
                                crease, &splits);
  if (splits == 0)
    return;
  a.stats = featureStats(a.supernodes, a.centrality.f, a.radii);
  a.conn = supernodeConnectivity(*a.graph, a.centrality.f, a.supernodes.label,
                                 params.execution.num_threads);
}

void contactStage(Analysis& a, const float* xyz, const SurfaceBends& bends, const CutNeeds& needs,
                  unsigned num_threads) {
  if (needs.concavity)
    a.concavity =
        contactConcavity(*a.graph, xyz, bends.normals, a.supernodes.label, bends.typical_bend);
  if (needs.crease)
    a.crease = edgeCreases(*a.graph, xyz, bends.normals, num_threads, bends.typical_bend);
  if (needs.thickness)
    a.thickness = supernodeThickness(bends.medial_radii, a.supernodes.label, a.supernodes.size());
  if (needs.rim && !a.rim.empty()) {
    a.rim_xyz.assign(xyz, xyz + 3 * a.graph->numVertices());
    a.rim_normals = bends.normals;
  }
}

} // namespace pcl_ncut_seg
