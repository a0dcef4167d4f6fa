/*
 * pcl_ncut_seg: the stages of the expensive analysis, each a named step over plain arrays,
 * run in this order by analyze() (core/pipeline/pipeline.h). Each states what it reads and writes.
 */
#pragma once

#include "core/graph/denoise.h"
#include "core/model/model.h"
#include <pcl_ncut_seg/analysis_report.h>
#include <pcl_ncut_seg/parameters.h>

#include <memory>

namespace pcl_ncut_seg {

/** \brief Graph stage (Sec. 4.1): the symmetric kNN graph with Euclidean lengths; when
 * graph.denoise is set, may_denoise holds and the cloud counts as noisy (core/graph/denoise.h), the
 * points projected onto their local planes and the graph's lengths measured again; then
 * bridges across sampling gaps between its components (graph.bridge_gap). When
 * graph.irregular_sampling is set and may_denoise holds, the sampling irregularity is measured
 * first (samplingIrregularity()).
 * \param[in,out] xyz  3 floats per vertex; projected when the cloud was noisy
 * \param[in] knn      k per vertex (kNone pads a row)
 * \param[out] noise   when given, the noise test's outcome */
CsrGraph graphStage(std::vector<float>& xyz, const std::uint32_t* knn, std::size_t k,
                    const GraphParams& params, bool may_denoise, unsigned num_threads,
                    NoiseTest* noise = nullptr);

/** \brief Centrality stage (Sec. 4.1): f of eq. (1) from each of num_starts starts of the
 * farthest-point sampling (computeCentralities(), or the coarse graph's in Fast mode), on a
 * noisy or randomly drawn cloud then taken through neighbourhoodMean() (core/graph/denoise.h).
 * Time is added to times.centrality.
 * \param[in] tie_rank  per vertex, distinct ranks for ties in f (nullptr: the vertex index)
 * \param[in] noisy     a whole surface whose points the graph stage projected or found
 *                      drawn at random (NoiseTest::projected, irregular; not an open view) */
std::vector<Centrality> centralityStage(const CsrGraph& graph, const Parameters& params,
                                        const std::uint32_t* tie_rank, PhaseTimes& times,
                                        const PhaseProgressFn& progress, std::size_t num_starts = 1,
                                        bool noisy = false);
/** \brief Supernode stage (Sec. 4.2) on a graph and its f: the supernodes of the gradient
 * flow. Sets graph, centrality and raw_supernodes; time is added to times.supernodes. */
Analysis supernodeStage(std::shared_ptr<const CsrGraph> graph, Centrality centrality,
                        const Parameters& params, PhaseTimes& times);
/** \brief Refinement stage (Sec. 4.3) after supernodeStage(): the radii r(p), local
 * refinement, feature statistics and eq. (8). Time is added to times.refinement. */
void refinementStage(Analysis& analysis, const Parameters& params, PhaseTimes& times);
/** \brief supernodeStage() then refinementStage(), each reported as a phase ("Snod", "LRef"). */
Analysis featureStages(CsrGraph graph, Centrality centrality, const Parameters& params,
                       PhaseTimes& times, const PhaseProgressFn& progress);
/** \brief Oriented normals and the model's mean bend per kNN edge, for the crease and
 * concavity stages (core/cut/concavity.h). */
struct SurfaceBends {
  std::vector<float> normals;      ///< 3 floats per vertex, oriented consistently
  double typical_bend = 0.0;       ///< meanAbsBend()
  std::vector<float> medial_radii; ///< per vertex, medialRadii() (core/cut/thickness.h); thickness
};
/** \param[in] thickness  also the medial radii (of a closed surface without noise: the
 *                        supernodes of an open view or a noisy cloud get no thickness) */
SurfaceBends surfaceBends(const CsrGraph& graph, const float* xyz, unsigned num_threads,
                          const float* viewpoint = nullptr, bool thickness = false);

/** \brief Crease stage (extension): split refined supernodes along concave creases
 * (refinement.crease_split; core/supernodes/crease_split.h), then measure their features
 * and eq. (8) again. */
void creaseStage(Analysis& analysis, const float* xyz, const SurfaceBends& bends,
                 const Parameters& params);

/** \brief Contact stage (extension): what the cut needs from the surface: the concavity of
 * each contact between supernodes, the concave bend of each kNN edge and each supernode's
 * thickness (from bends.medial_radii), as needs asks; the caller records them in
 * Analysis::measured. */
void contactStage(Analysis& analysis, const float* xyz, const SurfaceBends& bends,
                  const CutNeeds& needs, unsigned num_threads);

} // namespace pcl_ncut_seg
