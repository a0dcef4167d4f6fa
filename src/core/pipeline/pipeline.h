/*
 * pcl_ncut_seg: the whole segmentation over plain arrays, in two stages (the paper's order).
 * Every stage, in the order it runs; [paper] is the paper's (section, equation), [ext] an
 * extension with the parameter that switches it (results/report.md says what each buys).
 *
 * Before the analysis (the PCL front end, or segmentPoints()):
 *   [ext]   max_points          an even subset of a dense cloud is analysed
 * (core/graph/subsample.h) analyze(), the expensive stage, once per input (analysis_stages.h):
 *   [paper] kNN graph           Sec. 4.1
 *   [ext]   denoise             noise detected and projected out (core/graph/denoise.h)
 *   [ext]   irregular_sampling  random sampling detected; f averaged (core/graph/denoise.h)
 *   [ext]   bridge_gap          components joined across sampling gaps (core/graph/bridging.h)
 *   [ext]   single_view         a view's rim from its sensor origin, or from a sensor
 *                               position read off the points (core/views/single_view.h,
 *                               core/views/view_origin.h)
 *   [paper] centrality f        Sec. 4.1, eq. (1); [ext] centrality=fast on a coarse graph
 *                               (core/centrality/coarse_centrality.h), [ext] starts
 * (core/centrality/starts.h) [paper] supernodes          Sec. 4.2, gradient flow with saddles
 *   [paper] local refinement    Sec. 4.3
 *   [ext]   crease_split        supernodes split at concave creases
 * (core/supernodes/crease_split.h) [ext]   contact concavity   measured for concavity and
 * boundary_band (core/cut/concavity.h) [paper] CAD mode            Sec. 7, the ridge graph first,
 * instead of the above (core/cad/cad.h) cut(), the cheap stage, repeatable on a kept analysis
 * (cut_stages.h), per start: [paper] similarity          Sec. 5.1, eqs. (7)-(9); [ext]
 * normalize_width, adjacency, concavity, flat_elongation (core/cut/supernode_graph.h) [paper]
 * hierarchy           Sec. 5.2, threshold rule; [ext] stopping=short_cut (core/cut/short_cut.h),
 * count [paper] point segments      footnote 6 [ext]   boundary_band       point-level boundaries
 * by minimum cuts (core/cut/boundary_refinement.h) [ext]   rim_merge           open views: pieces
 * the rim cut off merged (core/views/rim_merge.h), then pieces below the paper's small part
 * (core/views/small_segments.h) [ext]   starts              the medoid of the starts' segmentations
 * (core/centrality/starts.h) segmentPoints() does everything from a point array, as the PCL front
 * end does from a cloud.
 */
#pragma once

#include "core/centrality/centrality.h"
#include "core/common/morton.h"
#include "core/cut/normalized_cut.h"
#include "core/cut/supernode_graph.h"
#include "core/graph/csr_graph.h"
#include "core/graph/denoise.h"
#include "core/supernodes/supernodes.h"
#include "core/views/view_origin.h"
#include <pcl_ncut_seg/parameters.h>

#include <array>
#include <cstdint>
#include <functional>
#include <memory>
#include <optional>
#include <vector>

namespace pcl_ncut_seg {

/** \brief Wall time of each phase in seconds, in the paper's Table 1 columns. */
struct PhaseTimes {
  double knn = 0, centrality = 0, supernodes = 0, refinement = 0, hierarchy = 0, points = 0;
  double total() const { return knn + centrality + supernodes + refinement + hierarchy + points; }
};

/** \brief Progress: a phase of Table 1 ("kNN", "Cen", "Snod", "LRef", "HSeg") and 0 at its
 * start, 1 at its end, the fraction done in between where known; from the calling thread. */
using PhaseProgressFn = std::function<void(const char* phase, double fraction)>;

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

/** \brief The expensive stage: everything that depends only on the points and the analysis
 * stages' parameters (and on which extensions the cut asks for, cutNeeds()). */
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
  /// Per pair of touching supernodes, how concave their contact is (core/cut/concavity.h); kept
  /// when the cut's similarity uses it.
  Connectivity concavity;
  bool has_concavity = false;
  /// Per directed kNN edge, its concave bend (core/cut/boundary_refinement.h); kept when the
  /// cut's boundary refinement uses it.
  std::vector<std::uint8_t> crease;
  bool has_crease = false;
  std::vector<std::uint32_t> order; ///< PointSet::order
  NoiseTest noise;                  ///< the graph stage's noise test (core/graph/denoise.h)
  ViewTest view;                    ///< whether the points are one view (core/views/view_origin.h)
  std::vector<std::uint8_t> rim;    ///< PointSet::rim
  /// The points and their oriented normals, kept when there is a rim and the cut's rim merge
  /// fits planes to the sides of boundaries (core/views/rim_merge.h).
  std::vector<float> rim_xyz, rim_normals;
  bool has_rim_planes = false;
  /// centrality.starts > 1 (core/centrality/starts.h): the analyses from the other starts of eq.
  /// (1)'s sampling that have samples of their own, each complete; this one is start 0.
  std::vector<Analysis> other_starts;
  /// With other starts: per analysis (this one first), how many starts have its samples.
  std::vector<std::uint32_t> start_weights;
};
/** \brief The analysis of a start with samples of its own: 0 is analysis itself, s > 0 its
 * other_starts[s - 1]. */
const Analysis& startAnalysis(const Analysis& analysis, std::size_t start);

/** \brief What the cut stages need the analysis to have measured. */
struct CutNeeds {
  bool concavity = false; ///< Analysis::concavity (similarity.concavity on, not CAD)
  bool crease = false;    ///< Analysis::crease (boundary.band on, not CAD)
  bool rim = false;       ///< Analysis::rim_xyz, rim_normals (boundary.rim_merge on, not CAD)
};
CutNeeds cutNeeds(const Parameters& params);

/** \brief Does the analysis hold what a cut with these parameters needs? */
bool serves(const Analysis& analysis, const Parameters& params);

/** \brief Run every analysis stage in order. The graph's time (and CAD normals') counts as
 * times.knn, as in Table 1. params must be valid (validate()).
 * \param[in] points  consumed: its arrays are freed as soon as no stage needs them */
Analysis analyze(PointSet points, const Parameters& params, PhaseTimes& times,
                 const PhaseProgressFn& progress = nullptr);

/** \brief The cheap stage's result. */
struct CutResult {
  WeightedGraph graph;                          ///< G_s (Sec. 5.1)
  Hierarchy hierarchy;                          ///< Sec. 5.2
  std::vector<std::uint32_t> supernode_segment; ///< per refined supernode, its segment
  std::vector<std::uint32_t> point_segment;     ///< per vertex, its segment
  std::size_t num_segments = 0;
  std::size_t start = 0; ///< the analysis that gave it (startAnalysis(); core/centrality/starts.h)
};

/** \brief Run every cut stage in order on an analysis that serves() the parameters. Segments
 * are numbered in order of their first vertex in Analysis::order. With other starts, each start
 * is cut and the medoid of their segmentations is returned (core/centrality/starts.h). */
CutResult cut(const Analysis& analysis, const Parameters& params, PhaseTimes& times);

/** \brief Points prepared for analyze(): the distinct positions of an array of points in
 * Morton order (every phase then reads its neighbours from nearby memory), centred. */
struct PreparedPoints {
  PointSet set;                     ///< without knn
  std::vector<std::uint32_t> point; ///< per vertex, the index of its (first) input point
  /// (index of a point at an earlier point's position, its vertex)
  std::vector<std::pair<std::uint32_t, std::uint32_t>> copies;
  std::vector<float> raw;         ///< the input's x, y, z in vertex order (not centred)
  double centroid[3] = {0, 0, 0}; ///< set.xyz = raw - centroid
};

/** \brief Set set.xyz to raw relative to the centroid of raw (summed in double, so that a model
 * far from the origin keeps its float precision), and centroid to it. */
void centrePoints(PreparedPoints& prepared);

/** \brief Order, deduplicate and centre points (3 floats each, finite). The centroid is
 * taken in double, so that a model far from the origin keeps its float precision.
 * \param[in] xyz  consumed (freed before the centred copy is made)
 * \param[in] box  the Morton grid's cube (default: the points' own; see mortonCodes()) */
PreparedPoints preparePoints(std::vector<float> xyz, const MortonBox* box = nullptr);

/** \brief The whole pipeline on n finite points (3 floats each) with FLANN's kd-tree for the
 * kNN graph: per point its segment in [0, t), the segments numbered by their first point.
 * The labels extract() of the PCL class gives for the same points and parameters. */
std::vector<std::uint32_t> segmentPoints(const float* xyz, std::size_t n, const Parameters& params);

} // namespace pcl_ncut_seg
