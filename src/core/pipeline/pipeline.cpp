// The orchestrator: the stages of core/pipeline/pipeline.h, in its order.
#include "core/pipeline/pipeline.h"

#include "core/cad/cad.h"
#include "core/centrality/starts.h"
#include "core/common/stopwatch.h"
#include "core/pipeline/analysis_stages.h"
#include "core/pipeline/cut_stages.h"
#include "core/views/single_view.h"
#include "core/views/view_origin.h"

#include <algorithm>
#include <limits>

namespace pcl_ncut_seg {

CutNeeds cutNeeds(const Parameters& params) {
  CutNeeds needs;
  needs.concavity = !params.cad.enabled && params.similarity.concavity.has_value();
  needs.crease = !params.cad.enabled && params.boundary.band.has_value();
  needs.rim = !params.cad.enabled && params.boundary.rim_merge.has_value();
  needs.thickness = !params.cad.enabled && params.similarity.thickness;
  return needs;
}

bool serves(const Analysis& analysis, const Parameters& params) {
  const CutNeeds needs = cutNeeds(params);
  const CutNeeds& measured = analysis.measured;
  return analysis.cad == params.cad.enabled && (!needs.concavity || measured.concavity) &&
         (!needs.crease || measured.crease) && (!needs.rim || measured.rim) &&
         (!needs.thickness || measured.thickness);
}

namespace {
/// The starts whose samples no earlier start has, and per such start how many starts have
/// its samples (the same samples give the same f, hence the same analysis).
struct DistinctStarts {
  std::vector<std::size_t> start;
  std::vector<std::uint32_t> weight;
};
DistinctStarts distinctStarts(const std::vector<Centrality>& f) {
  std::vector<std::vector<std::uint32_t>> sets;
  for (const Centrality& c : f) {
    sets.push_back(c.samples);
    std::sort(sets.back().begin(), sets.back().end());
  }
  DistinctStarts d;
  for (std::size_t j = 0; j < f.size(); ++j) {
    const auto first =
        static_cast<std::size_t>(std::find(sets.begin(), sets.end(), sets[j]) - sets.begin());
    if (first == j) {
      d.start.push_back(j);
      d.weight.push_back(0);
    }
    const auto at = std::find(d.start.begin(), d.start.end(), first) - d.start.begin();
    ++d.weight[static_cast<std::size_t>(at)];
  }
  return d;
}

/// The graph stage and the view test: the kNN graph (its knn freed), the noise test, and the
/// rim of a cloud that is one view (points.rim, points.sensor_origin).
struct Surface {
  CsrGraph graph;
  NoiseTest noise;
  ViewTest view;
};
Surface graphAndView(PointSet& points, const Parameters& params) {
  Surface s;
  const std::size_t n = points.xyz.size() / 3;
  // CAD parts meet at sharp ridges, which projecting the points onto planes would round.
  s.graph = graphStage(points.xyz, points.knn.data(), points.k, params.graph, !params.cad.enabled,
                       params.execution.num_threads, &s.noise);
  std::vector<std::uint32_t>().swap(points.knn); // free before the expensive stages
  if (!params.cad.enabled && params.graph.single_view && points.rim.empty()) {
    if (points.sensor_origin && couldBeSensor(points.xyz.data(), n, points.sensor_origin->data()))
      points.rim = singleViewRim(s.graph, points.xyz.data(), points.sensor_origin->data(),
                                 params.execution.num_threads);
    // No view from the given origin (or none given): perhaps one from elsewhere, the origin
    // left at 0 in another frame.
    if (points.rim.empty())
      if (auto origin = estimateViewOrigin(s.graph, points.xyz.data(), params.execution.num_threads,
                                           &points.rim)) {
        points.sensor_origin = origin;
        s.view.origin_estimated = true;
      }
  }
  if (!points.rim.empty()) {
    s.view.view = true;
    s.view.origin = *points.sensor_origin;
    s.view.rim_points =
        static_cast<std::size_t>(std::count(points.rim.begin(), points.rim.end(), std::uint8_t{1}));
  }
  return s;
}

/// The extensions that measure the surface's bends around the refined supernodes of each
/// start; the bends are measured once. viewpoint: one view's sensor, which the normals face;
/// noisy: the graph stage projected the points (NoiseTest::projected).
void bendStages(std::vector<Analysis>& each, const std::vector<float>& xyz,
                const Parameters& params, const float* viewpoint, bool noisy, PhaseTimes& times) {
  const CutNeeds needs = cutNeeds(params);
  const bool creases = params.refinement.crease_split.has_value();
  if (!creases && !needs.concavity && !needs.crease && !needs.rim && !needs.thickness)
    return;
  // Measured between the supernodes, like eq. (8): their time counts as refinement time.
  Stopwatch clock;
  // Thickness needs the surface's far side (an open view has none) and its two sides further
  // apart than the noise (on a noisy cloud a thin part's sides are a few noise widths apart).
  const bool thickness = needs.thickness && each[0].rim.empty() && !noisy;
  const SurfaceBends bends =
      surfaceBends(*each[0].graph, xyz.data(), params.execution.num_threads, viewpoint, thickness);
  for (Analysis& one : each) {
    if (creases)
      creaseStage(one, xyz.data(), bends, params);
    contactStage(one, xyz.data(), bends, needs, params.execution.num_threads);
  }
  times.refinement += clock.lap();
}

/// Secs. 4.1-4.3 and the bends' extensions, once per start of eq. (1)'s sampling with its own
/// samples (core/centrality/starts.h). noise: the graph stage's test; f is averaged when it
/// found the points noisy (and projected them) or drawn at random (core/graph/denoise.h), and
/// a noisy cloud's supernodes get no thickness. viewpoint: one view's sensor
/// (null: unknown or a whole surface), which the normals face.
Analyses surfaceAnalysis(const std::vector<float>& xyz, CsrGraph graph,
                         std::vector<std::uint8_t> rim, const Parameters& params,
                         const std::uint32_t* tie_rank, PhaseTimes& times,
                         const PhaseProgressFn& progress, const NoiseTest& noise,
                         const float* viewpoint) {
  const bool average = noise.projected || noise.irregular;
  // A noisy whole surface, or one drawn at random, has its centrality averaged over
  // neighbourhoods (core/graph/denoise.h), a view not: a depth sensor's noise runs along its rays,
  // mostly along the normals that the projection takes it out along (docs/sampling.md).
  // One view (it has a rim): one start. Its parts are decided more by the rim stages than by
  // the start, and a depth camera's frame rate counts (docs/views.md).
  const auto starts =
      rim.empty() ? static_cast<std::size_t>(std::max(1, params.centrality.starts)) : 1;
  std::vector<Centrality> f =
      centralityStage(graph, params, tie_rank, times, progress, starts, average && rim.empty());
  const DistinctStarts distinct = distinctStarts(f);
  // Phase by phase over the starts, so that progress reports each phase once.
  const std::size_t num = distinct.start.size();
  const auto share = [num](std::size_t done) {
    return static_cast<double>(done) / static_cast<double>(num);
  };
  const auto shared = std::make_shared<const CsrGraph>(std::move(graph));
  Analyses out;
  std::vector<Analysis>& each = out.starts;
  if (progress)
    progress("Snod", 0.0);
  for (std::size_t i = 0; i < num; ++i) {
    each.push_back(supernodeStage(shared, std::move(f[distinct.start[i]]), params, times));
    each.back().rim = i + 1 == num ? std::move(rim) : rim; // the last takes it, the others copy
    if (progress)
      progress("Snod", share(i + 1));
  }
  if (progress)
    progress("LRef", 0.0);
  for (std::size_t i = 0; i < num; ++i) {
    refinementStage(each[i], params, times);
    if (progress)
      progress("LRef", share(i + 1));
  }
  bendStages(each, xyz, params, viewpoint, noise.projected, times);
  out.weights = distinct.weight;
  return out;
}

/// CAD mode (Sec. 7), the analysis in place of surfaceAnalysis(): the CAD graph, Secs.
/// 4.1-4.3 on it from one start, then the faces. The graph's transformation counts as kNN
/// time, the faces as refinement time (Table 1).
Analyses cadAnalysis(const CsrGraph& graph, const float* xyz, const float* normals,
                     const Parameters& params, const std::uint32_t* tie_rank, PhaseTimes& times,
                     const PhaseProgressFn& progress) {
  Stopwatch clock;
  CadGraph cad = cadGraph(graph, normals, params.cad.ridge_angle);
  times.knn += clock.lap();
  std::vector<Centrality> f = centralityStage(cad.graph, params, tie_rank, times, progress);
  Analyses out;
  out.starts.push_back(
      featureStages(std::move(cad.graph), std::move(f[0]), params, times, progress));
  clock.lap();
  cadFaces(out.starts[0], graph, xyz, cad.ridge, params.refinement.area_fraction);
  times.refinement += clock.lap();
  out.weights = {1};
  return out;
}

/// The cut stages on one start's analysis.
CutResult cutStart(const Analysis& analysis, const Parameters& params, PhaseTimes& times) {
  CutResult r;
  Stopwatch clock;
  r.graph = similarityStage(analysis, params.similarity);
  r.hierarchy = hierarchyStage(analysis, r.graph, params.stopping);
  times.hierarchy += clock.lap();
  labelPoints(analysis, r);
  boundaryStage(analysis, params.boundary, r);
  rimStage(analysis, params.boundary, r);
  numberSegments(analysis.order, r);
  times.points += clock.lap();
  return r;
}
} // namespace

Analyses analyze(PointSet points, const Parameters& params, PhaseTimes& times,
                 const PhaseProgressFn& progress) {
  Stopwatch clock;
  const std::size_t n = points.xyz.size() / 3;
  Surface surface = graphAndView(points, params);
  // Ties and the sampling's start by distance from the centroid of each connected component:
  // the same for any order of the points, and a far outlier moves no other component's start.
  std::vector<std::uint32_t> component;
  connectedComponents(surface.graph, component);
  const std::vector<std::uint32_t> rank = centralRanks(points.xyz.data(), n, component);
  const CutNeeds needs = cutNeeds(params);
  const bool keep_xyz = params.cad.enabled || needs.concavity || needs.crease || needs.rim ||
                        needs.thickness || params.refinement.crease_split.has_value();
  if (!keep_xyz)
    std::vector<float>().swap(points.xyz);
  times.knn += clock.lap();
  if (progress)
    progress("kNN", 1.0);
  Analyses out;
  if (params.cad.enabled) {
    // Sec. 7: approximate normals from the caller; their time counts as kNN time (Table 1).
    const std::vector<float> normals =
        points.normals ? points.normals(surface.graph)
                       : std::vector<float>(3 * n, std::numeric_limits<float>::quiet_NaN());
    times.knn += clock.lap();
    out = cadAnalysis(surface.graph, points.xyz.data(), normals.data(), params, rank.data(), times,
                      progress);
  } else {
    const float* viewpoint =
        points.sensor_origin && !points.rim.empty() ? points.sensor_origin->data() : nullptr;
    out = surfaceAnalysis(points.xyz, std::move(surface.graph), std::move(points.rim), params,
                          rank.data(), times, progress, surface.noise, viewpoint);
  }
  for (std::size_t i = out.starts.size(); i-- > 0;) { // the first takes the order, the others copy
    Analysis& a = out.starts[i];
    a.order = i == 0 ? std::move(points.order) : points.order;
    a.noise = surface.noise;
    a.view = surface.view;
    a.measured = needs;
  }
  return out;
}

CutResult cut(const Analyses& analyses, const Parameters& params, PhaseTimes& times) {
  times.hierarchy = times.points = 0;
  if (analyses.starts.size() == 1)
    return cutStart(analyses.starts[0], params, times);
  std::vector<CutResult> results;
  for (const Analysis& one : analyses.starts)
    results.push_back(cutStart(one, params, times));
  Stopwatch clock;
  std::vector<const std::vector<std::uint32_t>*> partitions;
  for (const CutResult& r : results)
    partitions.push_back(&r.point_segment);
  const std::size_t start = medoidPartition(partitions, analyses.weights);
  times.points += clock.lap();
  CutResult r = std::move(results[start]);
  r.start = start;
  return r;
}

} // namespace pcl_ncut_seg
