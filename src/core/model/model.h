/*
 * pcl_ncut_seg: the data every stage shares, the pipeline's data model. The points the
 * analysis reads (PointSet), what it measured (Analysis, one per start of eq. (1)'s sampling:
 * Analyses), what the cut measures to what the analysis must hold (CutNeeds), and the cut's
 * result (CutResult). A room of its own below the pipeline: the stages read and write these
 * types without knowing the order the pipeline (core/pipeline/pipeline.h) runs them in.
 */
#pragma once

#include "core/centrality/centrality.h"
#include "core/cut/normalized_cut.h"
#include "core/cut/supernode_graph.h"
#include "core/graph/csr_graph.h"
#include "core/supernodes/refinement.h"
#include "core/supernodes/supernodes.h"
#include <pcl_ncut_seg/analysis_report.h>

#include <array>
#include <cstdint>
#include <functional>
#include <memory>
#include <optional>
#include <vector>

namespace pcl_ncut_seg {

/** \brief Approximate normals for CAD mode: 3 floats per vertex (any orientation; NaN where
 * unknown), given the symmetric kNN graph. The PCL front end fits them with PCL's estimator
 * unless the input has normals. */
using NormalSource = std::function<std::vector<float>(const CsrGraph& graph)>;

/** \brief What analyze() reads: distinct points in the order of the graph's vertices. */
struct PointSet {
  std::vector<float> xyz;         ///< 3 floats per vertex, best centred (lengths in float)
  std::vector<std::uint32_t> knn; ///< k per vertex, nearest first; kNone pads a short row
  std::size_t k = 0;              ///< neighbours per row of knn
  /// Per vertex, its rank in the input's order (distinct): segments are numbered by their
  /// first vertex in it. Empty: the vertex order. (Ties in the centrality go by centralRanks(),
  /// core/centrality/starts.h, which the order of the points does not change.)
  std::vector<std::uint32_t> order;
  NormalSource normals; ///< CAD mode; empty: CAD mode fails (no normals)
  /// Per vertex, 1 where an open view of the surface ends (core/views/rim_merge.h); empty: a
  /// surface without a known rim.
  std::vector<std::uint8_t> rim;
  /// Where the sensor stood, in the coordinates of xyz; when there is no rim, a cloud that is
  /// one view from there gets its rim (core/views/single_view.h); a view's normals face it
  /// (orientedNormals(), core/cut/concavity.h). Empty: unknown.
  std::optional<std::array<float, 3>> sensor_origin;
};

/** \brief What the cut stages need the analysis to have measured (cutNeeds(),
 * core/pipeline/pipeline.h). */
struct CutNeeds {
  bool concavity = false; ///< Analysis::concavity (similarity.concavity on, not CAD)
  bool crease = false;    ///< Analysis::crease (boundary.band on, not CAD)
  bool rim = false;       ///< Analysis::rim_xyz, rim_normals (boundary.rim_merge on, not CAD)
  bool thickness = false; ///< Analysis::thickness (similarity.thickness on, not CAD)
};

/** \brief The expensive stage from one start of eq. (1)'s sampling: everything that depends
 * only on the points and the analysis stages' parameters (and on which extensions the cut asks
 * for, CutNeeds). */
struct Analysis {
  /// The kNN graph (CAD mode: transformed, Sec. 7); the starts' analyses share it.
  std::shared_ptr<const CsrGraph> graph;
  Centrality centrality;     ///< Sec. 4.1
  std::vector<float> radii;  ///< r(p), Sec. 4.3
  Supernodes raw_supernodes; ///< Sec. 4.2, before refinement
  Supernodes supernodes;     ///< after refinement (Sec. 4.3) and crease splits
  FeatureStats stats;        ///< of the refined supernodes
  Connectivity conn;         ///< eq. (8) over the refined supernodes
  bool cad = false;          ///< CAD mode (Sec. 7)
  Connectivity face_angles;  ///< CAD mode: angle (degrees) between touching supernodes' faces
  /// What was measured for the cut below (the CutNeeds of the parameters it was made with).
  CutNeeds measured;
  /// Per pair of touching supernodes, how concave their contact is (core/cut/concavity.h);
  /// measured.concavity.
  Connectivity concavity;
  /// Per refined supernode, its median medial radius (core/cut/thickness.h); NaN where unknown
  /// (an open view); measured.thickness.
  std::vector<float> thickness;
  /// Per directed kNN edge, its concave bend (core/cut/boundary_refinement.h); measured.crease.
  std::vector<std::uint8_t> crease;
  std::vector<std::uint32_t> order; ///< PointSet::order
  NoiseTest noise;                  ///< the graph stage's noise test (core/graph/denoise.h)
  ViewTest view;                    ///< whether the points are one view (core/views/view_origin.h)
  std::vector<std::uint8_t> rim;    ///< PointSet::rim
  /// The points and their oriented normals, when there is a rim and measured.rim (the rim
  /// merge fits planes to the sides of boundaries, core/views/rim_merge.h).
  std::vector<float> rim_xyz, rim_normals;
};

/** \brief The analyses of the starts of eq. (1)'s sampling (centrality.starts,
 * core/centrality/starts.h) that have samples of their own, each complete; one with one start
 * (the paper), CAD mode or an open view. */
struct Analyses {
  std::vector<Analysis> starts;       ///< at least one after analyze()
  std::vector<std::uint32_t> weights; ///< per analysis, how many starts have its samples
};

/** \brief The cheap stage's result. */
struct CutResult {
  WeightedGraph graph;                          ///< G_s (Sec. 5.1)
  Hierarchy hierarchy;                          ///< Sec. 5.2
  std::vector<std::uint32_t> supernode_segment; ///< per refined supernode, its segment
  std::vector<std::uint32_t> point_segment;     ///< per vertex, its segment
  std::size_t num_segments = 0;
  std::size_t start = 0; ///< the analysis that gave it: Analyses::starts[start]
};

} // namespace pcl_ncut_seg
