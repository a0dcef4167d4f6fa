/*
 * pcl_ncut_seg: the stages of the expensive analysis, each a named step over plain arrays,
 * run in this order by analyze() (core/pipeline.h). Each states what it reads and writes.
 */
#pragma once

#include <pcl_ncut_seg/core/pipeline.h>

namespace pcl_ncut_seg {

/** \brief Graph stage (Sec. 4.1): the symmetric kNN graph with Euclidean lengths, and
 * bridges across sampling gaps between its components (graph.bridge_gap).
 * \param[in] xyz  3 floats per vertex
 * \param[in] knn  k per vertex (kNone pads a row) */
CsrGraph graphStage(const float* xyz, std::size_t n, const std::uint32_t* knn, std::size_t k,
                    const GraphParams& params, unsigned num_threads);

/** \brief Noise stage (extension, core/denoise.h): when graph.denoise is set and the cloud
 * counts as noisy, projects xyz onto the points' 2-ring planes and rebuilds the graph from
 * the same knn (graphStage). Returns whether it did.
 * \param[in,out] xyz    3 floats per vertex
 * \param[in,out] graph  graphStage() of xyz and knn */
bool denoiseStage(std::vector<float>& xyz, const std::uint32_t* knn, std::size_t k,
                  const GraphParams& params, unsigned num_threads, CsrGraph& graph);

/** \brief Secs. 4.1-4.3 on a graph: the centrality f (eq. 1), the supernodes of its gradient
 * flow (4.2), the radii r(p), local refinement (4.3), feature statistics and eq. (8).
 * Times go to times.centrality, .supernodes, .refinement.
 * \param[in] tie_rank  per vertex, distinct ranks for ties in f (nullptr: the vertex index) */
Analysis featureStages(CsrGraph graph, const Parameters& params, const std::uint32_t* tie_rank,
                       PhaseTimes& times, const PhaseProgressFn& progress);

/** \brief Oriented normals and the model's mean bend per kNN edge, for the crease and
 * concavity stages (core/concavity.h). */
struct SurfaceBends {
  std::vector<float> normals; ///< 3 floats per vertex, oriented consistently
  double typical_bend = 0.0;  ///< meanAbsBend()
};
SurfaceBends surfaceBends(const CsrGraph& graph, const float* xyz, unsigned num_threads);

/** \brief Crease stage (extension): split refined supernodes along concave creases
 * (refinement.crease_split, .crease_cut; core/crease_split.h), then measure their features
 * and eq. (8) again. */
void creaseStage(Analysis& analysis, const float* xyz, const SurfaceBends& bends,
                 const Parameters& params);

/** \brief Contact stage (extension): what the cut needs from the surface: the concavity of
 * each contact between supernodes and the concave bend of each kNN edge (cutNeeds()). */
void contactStage(Analysis& analysis, const float* xyz, const SurfaceBends& bends,
                  const CutNeeds& needs, unsigned num_threads);

} // namespace pcl_ncut_seg
