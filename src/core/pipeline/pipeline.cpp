#include "core/pipeline/pipeline.h"

#include "core/cad/cad.h"
#include "core/centrality/starts.h"
#include "core/common/morton.h"
#include "core/common/stopwatch.h"
#include "core/common/threads.h"
#include "core/graph/knn.h"
#include "core/graph/subsample.h"
#include "core/pipeline/analysis_stages.h"
#include "core/pipeline/cut_stages.h"
#include "core/views/single_view.h"

#include <algorithm>
#include <limits>

namespace pcl_ncut_seg {

CutNeeds cutNeeds(const Parameters& params) {
  CutNeeds needs;
  needs.concavity = !params.cad.enabled && params.similarity.concavity.has_value();
  needs.crease = !params.cad.enabled && params.boundary.band.has_value();
  needs.rim = !params.cad.enabled && params.boundary.rim_merge.has_value();
  return needs;
}

bool serves(const Analysis& analysis, const Parameters& params) {
  const CutNeeds needs = cutNeeds(params);
  return analysis.cad == params.cad.enabled && (!needs.concavity || analysis.has_concavity) &&
         (!needs.crease || analysis.has_crease) && (!needs.rim || analysis.has_rim_planes);
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

/// Secs. 4.1-4.3 and the extensions that measure the surface's bends around the refined
/// supernodes, once per start of eq. (1)'s sampling with its own samples
/// (core/centrality/starts.h); the bends are measured once. average: the graph stage found the
/// points noisy (and projected them) or drawn at random (core/graph/denoise.h). viewpoint: one
/// view's sensor (null: unknown or a whole surface), which the normals face.
Analysis surfaceAnalysis(const std::vector<float>& xyz, CsrGraph graph,
                         std::vector<std::uint8_t> rim, const Parameters& params,
                         const std::uint32_t* tie_rank, PhaseTimes& times,
                         const PhaseProgressFn& progress, bool average, const float* viewpoint) {
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
  std::vector<Analysis> each;
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
  const CutNeeds needs = cutNeeds(params);
  const bool creases = params.refinement.crease_split.has_value();
  if (creases || needs.concavity || needs.crease || needs.rim) {
    // Measured between the supernodes, like eq. (8): their time counts as refinement time.
    Stopwatch clock;
    const SurfaceBends bends =
        surfaceBends(*each[0].graph, xyz.data(), params.execution.num_threads, viewpoint);
    for (Analysis& one : each) {
      if (creases)
        creaseStage(one, xyz.data(), bends, params);
      contactStage(one, xyz.data(), bends, needs, params.execution.num_threads);
    }
    times.refinement += clock.lap();
  }
  Analysis a = std::move(each[0]);
  for (std::size_t i = 1; i < each.size(); ++i)
    a.other_starts.push_back(std::move(each[i]));
  if (starts > 1)
    a.start_weights = distinct.weight;
  return a;
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

Analysis analyze(PointSet points, const Parameters& params, PhaseTimes& times,
                 const PhaseProgressFn& progress) {
  Stopwatch clock;
  const std::size_t n = points.xyz.size() / 3;
  NoiseTest noise;
  // CAD parts meet at sharp ridges, which projecting the points onto planes would round.
  CsrGraph graph = graphStage(points.xyz, points.knn.data(), points.k, params.graph,
                              !params.cad.enabled, params.execution.num_threads, &noise);
  std::vector<std::uint32_t>().swap(points.knn); // free before the expensive stages
  const CutNeeds needs = cutNeeds(params);
  ViewTest view;
  if (!params.cad.enabled && params.graph.single_view && points.rim.empty()) {
    if (points.sensor_origin && couldBeSensor(points.xyz.data(), n, points.sensor_origin->data()))
      points.rim = singleViewRim(graph, points.xyz.data(), points.sensor_origin->data(),
                                 params.execution.num_threads);
    // No view from the given origin (or none given): perhaps one from elsewhere, the origin
    // left at 0 in another frame.
    if (points.rim.empty())
      if (auto origin = estimateViewOrigin(graph, points.xyz.data(), params.execution.num_threads,
                                           &points.rim)) {
        points.sensor_origin = origin;
        view.origin_estimated = true;
      }
  }
  if (!points.rim.empty()) {
    view.view = true;
    view.origin = *points.sensor_origin;
    view.rim_points =
        static_cast<std::size_t>(std::count(points.rim.begin(), points.rim.end(), std::uint8_t{1}));
  }
  // Ties and the sampling's start by distance from the centroid of each connected component:
  // the same for any order of the points, and a far outlier moves no other component's start.
  std::vector<std::uint32_t> component;
  connectedComponents(graph, component);
  const std::vector<std::uint32_t> rank = centralRanks(points.xyz.data(), n, component);
  const bool keep_xyz = params.cad.enabled || needs.concavity || needs.crease || needs.rim ||
                        params.refinement.crease_split.has_value();
  if (!keep_xyz)
    std::vector<float>().swap(points.xyz);
  times.knn += clock.lap();
  if (progress)
    progress("kNN", 1.0);
  Analysis a;
  if (params.cad.enabled) {
    // Sec. 7: approximate normals from the caller; their time counts as kNN time (Table 1).
    const std::vector<float> normals =
        points.normals ? points.normals(graph)
                       : std::vector<float>(3 * n, std::numeric_limits<float>::quiet_NaN());
    times.knn += clock.lap();
    a = analyzeCad(graph, points.xyz.data(), normals.data(), params, rank.data(), times, progress);
  } else {
    const float* viewpoint =
        points.sensor_origin && !points.rim.empty() ? points.sensor_origin->data() : nullptr;
    a = surfaceAnalysis(points.xyz, std::move(graph), std::move(points.rim), params, rank.data(),
                        times, progress, noise.projected || noise.irregular, viewpoint);
  }
  a.order = std::move(points.order);
  a.noise = noise;
  a.view = view;
  for (Analysis& other : a.other_starts) {
    other.order = a.order;
    other.noise = noise;
    other.view = view;
  }
  return a;
}

const Analysis& startAnalysis(const Analysis& analysis, std::size_t start) {
  return start == 0 ? analysis : analysis.other_starts.at(start - 1);
}

CutResult cut(const Analysis& analysis, const Parameters& params, PhaseTimes& times) {
  times.hierarchy = times.points = 0;
  if (analysis.other_starts.empty())
    return cutStart(analysis, params, times);
  std::vector<CutResult> results;
  results.push_back(cutStart(analysis, params, times));
  for (const Analysis& other : analysis.other_starts)
    results.push_back(cutStart(other, params, times));
  Stopwatch clock;
  std::vector<const std::vector<std::uint32_t>*> partitions;
  for (const CutResult& r : results)
    partitions.push_back(&r.point_segment);
  const std::size_t start = medoidPartition(partitions, analysis.start_weights);
  times.points += clock.lap();
  CutResult r = std::move(results[start]);
  r.start = start;
  return r;
}

void centrePoints(PreparedPoints& prepared) {
  // Coordinates relative to the centroid, in double first, so that a model far from the
  // origin keeps its float precision.
  const std::size_t m = prepared.raw.size() / 3;
  double c[3] = {0, 0, 0};
  for (std::size_t i = 0; i < m; ++i)
    for (int d = 0; d < 3; ++d)
      c[d] += prepared.raw[3 * i + d];
  for (double& v : c)
    v /= static_cast<double>(std::max<std::size_t>(m, 1));
  prepared.set.xyz.resize(3 * m);
  prepared.set.xyz.shrink_to_fit();
  for (std::size_t i = 0; i < 3 * m; ++i)
    prepared.set.xyz[i] = static_cast<float>(prepared.raw[i] - c[i % 3]);
  for (int d = 0; d < 3; ++d)
    prepared.centroid[d] = c[d];
}

PreparedPoints preparePoints(std::vector<float> xyz, const MortonBox* box) {
  PreparedPoints out;
  DistinctMortonOrder order = distinctMortonOrder(xyz.data(), xyz.size() / 3, box);
  const std::size_t m = order.point.size();
  out.raw.resize(3 * m);
  for (std::size_t v = 0; v < m; ++v)
    for (std::size_t d = 0; d < 3; ++d) // (no library call per point)
      out.raw[3 * v + d] = xyz[3 * std::size_t(order.point[v]) + d];
  std::vector<float>().swap(xyz); // before the centred copy: one copy of the points less
  centrePoints(out);
  out.point = std::move(order.point);
  out.copies = std::move(order.copies);
  out.set.order = std::move(order.rank);
  return out;
}

std::vector<std::uint32_t> segmentPoints(const float* xyz, std::size_t n,
                                         const Parameters& params) {
  if (n == 0 || !validate(params))
    return {};
  PreparedPoints prepared = prepareAtResolution(
      std::vector<float>(xyz, xyz + 3 * n),
      params.graph.max_points ? static_cast<std::size_t>(*params.graph.max_points) : 0,
      usableThreads(params.execution.num_threads));
  const std::size_t m = prepared.point.size();
  PointSet& set = prepared.set;
  set.k = std::min<std::size_t>(static_cast<std::size_t>(params.graph.k), m - 1);
  set.knn.assign(m * std::max<std::size_t>(set.k, 1), kNone);
  if (set.k > 0)
    kNearestNeighbours(prepared.raw.data(), m, set.k, usableThreads(params.execution.num_threads),
                       set.knn.data());
  std::vector<float>().swap(prepared.raw);
  PhaseTimes times;
  const Analysis analysis = analyze(std::move(set), params, times);
  const CutResult r = cut(analysis, params, times);
  std::vector<std::uint32_t> label(n);
  for (std::size_t v = 0; v < m; ++v)
    label[prepared.point[v]] = r.point_segment[v];
  for (const auto& [copy, vertex] : prepared.copies)
    label[copy] = r.point_segment[vertex];
  return label;
}

} // namespace pcl_ncut_seg
