/*
 * pcl_ncut_seg: the two stages of the segmentation over plain arrays.
 *   analyze(): kNN graph -> centrality (4.1) -> supernodes (4.2) -> refinement (4.3),
 *              computed once per input;
 *   cut():     supernode graph (5.1) -> hierarchy (5.2) -> point segments, cheap to repeat.
 */
#pragma once

#include <pcl_ncut_seg/core/centrality.h>
#include <pcl_ncut_seg/core/coarse_centrality.h>
#include <pcl_ncut_seg/core/csr_graph.h>
#include <pcl_ncut_seg/core/normalized_cut.h>
#include <pcl_ncut_seg/core/refinement.h>
#include <pcl_ncut_seg/core/supernode_graph.h>
#include <pcl_ncut_seg/core/supernodes.h>

#include <cstdint>
#include <functional>
#include <vector>

namespace pcl_ncut_seg {

/** \brief Wall time of each phase in seconds, in the paper's Table 1 columns. */
struct PhaseTimes {
  double knn = 0, centrality = 0, supernodes = 0, refinement = 0, hierarchy = 0, points = 0;
  double total() const { return knn + centrality + supernodes + refinement + hierarchy + points; }
};

/** \brief How the centrality of Sec. 4.1 is computed. */
enum class CentralityMode {
  Exact, ///< as the paper: ceil(sqrt(n)) samples, searches over the whole kNN graph
  Fast   ///< eq. (1) on a coarse graph of representatives, carried back to every point
};

struct AnalysisParams {
  CentralityMode centrality_mode = CentralityMode::Fast;
  std::size_t num_representatives = 20000; ///< Fast mode: size of the coarse graph
  std::size_t num_samples = 0;    ///< per component; 0 = ceil(sqrt(n_c))
  float crossing_fraction = 0.3f; ///< Sec. 4.2 (b)
  RefinementParams refinement;
  unsigned num_threads = 0; ///< 0 = all available
  /// If set, called with a phase ("Cen", "Snod", "LRef") and 0 at its start, 1 at its end,
  /// and with the fraction done in between where known (from the calling thread only).
  std::function<void(const char* phase, double fraction)> progress;
  /// Per vertex, distinct ranks for ties in the centrality (empty: the vertex index); the PCL
  /// front end passes the input order, so results do not depend on its Morton numbering.
  std::vector<std::uint32_t> tie_rank;
};

/** \brief The expensive stage: everything that depends only on the points, k and the
 * parameters above. */
struct Analysis {
  CsrGraph graph;
  Centrality centrality;
  std::vector<float> radii;  ///< r(p), Sec. 4.3
  Supernodes raw_supernodes; ///< Sec. 4.2, before refinement
  Supernodes supernodes;     ///< after refinement (Sec. 4.3)
  FeatureStats stats;        ///< of the refined supernodes
  Connectivity conn;         ///< eq. (8) over the refined supernodes
  bool cad = false;          ///< CAD mode (Sec. 7): built by analyzeCad() in core/cad.h
  Connectivity face_angles;  ///< CAD mode: angle (degrees) between touching supernodes' faces
  double face_angle = 15.0;  ///< CAD mode: angle scale of the face similarity
  /// Per pair of touching supernodes, how concave their contact is (core/concavity.h); empty
  /// unless SimilarityParams::concavity_weight is used.
  Connectivity concavity;
  /// Per directed kNN edge, its concave bend for the boundary refinement
  /// (core/boundary_refinement.h); empty unless BoundaryParams::band_fraction is used.
  std::vector<std::uint8_t> crease;
};

/** \brief Run Secs. 4.1-4.3 on a prepared kNN graph. Times go to times.centrality etc. */
Analysis analyze(CsrGraph graph, const AnalysisParams& params, PhaseTimes& times);

/** \brief The cheap stage's result. */
struct CutResult {
  WeightedGraph graph;                          ///< G_s (Sec. 5.1)
  Hierarchy hierarchy;                          ///< Sec. 5.2
  std::vector<std::uint32_t> supernode_segment; ///< per refined supernode, its segment
  std::vector<std::uint32_t> point_segment;     ///< per point, its segment
  std::size_t num_segments = 0;
};

/** \brief Run Sec. 5 on an analysis. Segments are numbered in order of their smallest point. */
CutResult cut(const Analysis& analysis, const SimilarityParams& similarity, const CutParams& params,
              PhaseTimes& times);

} // namespace pcl_ncut_seg
