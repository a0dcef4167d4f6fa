#include <pcl_ncut_seg/core/pipeline.h>

#include <pcl_ncut_seg/core/cad.h>
#include <pcl_ncut_seg/core/short_cut.h>

#include <chrono>
#include <memory>

namespace pcl_ncut_seg {
namespace {
class Stopwatch {
public:
  double lap() {
    const auto now = std::chrono::steady_clock::now();
    const double s = std::chrono::duration<double>(now - start_).count();
    start_ = now;
    return s;
  }

private:
  std::chrono::steady_clock::time_point start_ = std::chrono::steady_clock::now();
};
} // namespace

Analysis analyze(CsrGraph graph, const AnalysisParams& params, PhaseTimes& times) {
  Analysis a;
  a.graph = std::move(graph);
  const auto report = [&params](const char* phase, double fraction) {
    if (params.progress)
      params.progress(phase, fraction);
  };
  ProgressFn centrality_progress;
  if (params.progress)
    centrality_progress = [&params](double fraction) { params.progress("Cen", fraction); };
  Stopwatch clock;
  report("Cen", 0.0);
  const std::uint32_t* rank = params.tie_rank.empty() ? nullptr : params.tie_rank.data();
  a.centrality = params.centrality_mode == CentralityMode::Exact
                     ? computeCentrality(a.graph, params.num_samples, params.num_threads, rank,
                                         centrality_progress)
                     : computeCoarseCentrality(a.graph, params.num_representatives,
                                               params.num_samples, params.num_threads, rank,
                                               centrality_progress);
  report("Cen", 1.0);
  times.centrality = clock.lap();
  report("Snod", 0.0);
  a.raw_supernodes = extractSupernodes(a.graph, a.centrality.f, params.crossing_fraction);
  report("Snod", 1.0);
  times.supernodes = clock.lap();
  report("LRef", 0.0);
  a.radii = pointRadii(a.graph, a.centrality.f, params.num_threads);
  a.supernodes =
      refineSupernodes(a.graph, a.centrality.f, a.radii, a.raw_supernodes, params.refinement);
  a.stats = featureStats(a.supernodes, a.centrality.f, a.radii);
  a.conn = supernodeConnectivity(a.graph, a.centrality.f, a.supernodes.label,
                                 params.num_threads);
  report("LRef", 1.0);
  times.refinement = clock.lap();
  return a;
}

CutResult cut(const Analysis& analysis, const SimilarityParams& similarity, const CutParams& params,
              PhaseTimes& times) {
  CutResult r;
  Stopwatch clock;
  const std::size_t l = analysis.supernodes.size();
  r.graph = analysis.cad ? buildCadSupernodeGraph(analysis.supernodes, analysis.stats,
                                                  analysis.conn, analysis.face_angles, similarity,
                                                  analysis.face_angle)
                         : buildSupernodeGraph(analysis.supernodes, analysis.stats, analysis.conn,
                                               similarity, &analysis.concavity);
  SplitNeckFn split_neck;
  std::unique_ptr<NeckMeasure> necks;
  if (params.num_segments <= 0 && params.largest_gap && params.neck_exponent > 0.0) {
    // The short-cut rule measures each split's boundary on the kNN graph (core/short_cut.h).
    necks = std::make_unique<NeckMeasure>(analysis.graph, analysis.supernodes.label, l);
    split_neck = [&necks, l](const std::vector<std::uint32_t>& v1,
                             const std::vector<std::uint32_t>& v2) {
      std::vector<std::int8_t> side(l, -1);
      for (std::uint32_t v : v1)
        if (v >= l)
          side[v - l] = 0; // member vertex m_i = l + i stands for supernode i (footnote 6)
      for (std::uint32_t v : v2)
        if (v >= l)
          side[v - l] = 1;
      return necks->neck(side);
    };
  }
  r.hierarchy = buildHierarchy(r.graph, l, params, split_neck);
  times.hierarchy = clock.lap();

  // Each supernode follows its member vertex m_i (footnote 6); each point its supernode.
  std::vector<std::uint32_t> leaf_of(l, kNone);
  const std::vector<int> leaves = r.hierarchy.leaves();
  for (std::size_t k = 0; k < leaves.size(); ++k)
    for (std::uint32_t v : r.hierarchy.nodes[leaves[k]].vertices)
      if (v >= l)
        leaf_of[v - l] = static_cast<std::uint32_t>(k);
  std::vector<std::uint32_t> segment_of_leaf(leaves.size(), kNone);
  const std::vector<std::uint32_t>& label = analysis.supernodes.label;
  r.point_segment.resize(label.size());
  for (std::size_t p = 0; p < label.size(); ++p) {
    std::uint32_t& seg = segment_of_leaf[leaf_of[label[p]]];
    if (seg == kNone)
      seg = static_cast<std::uint32_t>(r.num_segments++);
    r.point_segment[p] = seg;
  }
  r.supernode_segment.resize(l);
  for (std::size_t s = 0; s < l; ++s)
    r.supernode_segment[s] = segment_of_leaf[leaf_of[s]];
  times.points = clock.lap();
  return r;
}

} // namespace pcl_ncut_seg
