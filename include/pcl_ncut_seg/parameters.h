/*
 * pcl_ncut_seg: every parameter of the segmentation, grouped by the stage of the pipeline that
 * reads it, each declared once here with its default. The table of names, ranges and help text
 * (parameter_table.h) describes every field; validation, the tools' flags, their help, the
 * README's table and the range tests all read it.
 *
 * The paper's parameters (Yamazaki et al., "Segmenting Point-sampled Surfaces") come first in
 * each group; the project's extensions follow them. Parameters::paper() is the paper to the
 * letter; Parameters{} the project's defaults. An extension that can be off is a
 * std::optional: std::nullopt is off, not a zero.
 */
#pragma once

#include <optional>
#include <string>

namespace pcl_ncut_seg {

/** \brief The stages of the pipeline, in order. Analysis stages make up the expensive stage
 * (computed once per input); a change of one of their parameters invalidates it. Cut stages
 * are cheap to repeat on a kept analysis. */
enum class Stage {
  Graph,      ///< kNN graph (Sec. 4.1) and bridging of its components
  Centrality, ///< f(p), eq. (1) (Sec. 4.1)
  Supernodes, ///< gradient flow with saddles (Sec. 4.2)
  Refinement, ///< local refinement (Sec. 4.3) and crease splits
  Cad,        ///< CAD mode's ridge graph (Sec. 7)
  Similarity, ///< the supernode graph's weights (Sec. 5.1)
  Stopping,   ///< the hierarchy of bisections and when it stops (Sec. 5.2)
  Boundary,   ///< point-level boundary refinement
  Execution   ///< how the work runs (threads); never changes the result
};

/** \brief True for the stages of the expensive analysis (Graph to Cad). */
inline bool isAnalysisStage(Stage stage) {
  return stage <= Stage::Cad;
}

/** \brief The stage's name, as the README and the help group parameters ("graph", ...). */
const char* stageName(Stage stage);

/** \brief How the centrality of Sec. 4.1 is computed. */
enum class CentralityMode {
  Exact, ///< as the paper: ceil(sqrt(n)) samples, searches over the whole kNN graph
  Fast   ///< eq. (1) on a coarse graph of representatives, carried back to every point
};

/** \brief Which pairs of touching supernodes the supernode graph joins (Sec. 5.1). */
enum class Adjacency {
  Saddles, ///< the paper: member vertices m_i - m_j only where s_i and s_j meet at a saddle
  Trees,   ///< also join the trees of member vertices that touch in the kNN graph
  All      ///< every pair of supernodes that touch in the kNN graph (implies Trees)
};

/** \brief When the recursive bisection of Sec. 5.2 stops. */
enum class StoppingRule {
  Threshold, ///< the paper: bisect a part while its best NCut is at most the threshold
  ShortCut,  ///< best-first splits weighted by how short their boundary is (core/cut/short_cut.h)
  Count      ///< best-first splits until a given number of segments
};

/** \brief Sec. 4.1: the kNN graph. */
struct GraphParams {
  int k = 10; ///< nearest neighbours per point; the graph joins p and q if either is the other's
  /// Extension: join components of the graph that only a sampling gap separates, by their
  /// shortest point pair when it is at most this many kNN radii long. Off: the paper.
  std::optional<double> bridge_gap = 3.0;
  /// Extension (core/graph/denoise.h): when the residual growth of the points' local plane fits is
  /// below this bound (noise, not curvature, scatters them), each point is projected onto the
  /// plane of its 2-ring before anything is measured; nullopt: never. Not in CAD mode.
  std::optional<double> denoise = 2.0;
  /// Extension (core/graph/denoise.h): when the sampling irregularity of the points is
  /// at least this (0.3: points drawn at random, not spread evenly), the centrality of a whole
  /// surface is averaged over each point's neighbourhood once, as on a noisy one. nullopt:
  /// never (the paper). Not in CAD mode.
  std::optional<double> irregular_sampling = 0.3;
  /// Extension (core/graph/subsample.h): a denser cloud is analysed on an even subset of at most
  /// this many of its points (one per cube of a grid), and every other point takes the segment of
  /// its nearest analysed point. Off: every point.
  std::optional<int> max_points = 60000;
  /// Extension (core/views/single_view.h): a cloud that is one view from its sensor origin (a depth
  /// image, organized or not, or a scanner's) is an open view with the rim the test finds.
  /// Off: a surface without a rim.
  bool single_view = true;
};

/** \brief Sec. 4.1: the centrality f of eq. (1). */
struct CentralityParams {
  /// Samples per connected component; nullopt: ceil(sqrt(n_c)) as in the paper.
  std::optional<int> samples;
  /// Extension: Fast computes eq. (1) on a coarse graph (f within about 1-2% of Exact's).
  CentralityMode mode = CentralityMode::Fast;
  /// Extension (core/centrality/starts.h): step 4's arbitrary first sample taken this many times
  /// (the first samples of one farthest-point chain), a segmentation from each, and the one closest
  /// to the others kept. 1: one start, the paper. Not in CAD mode, nor on an open view (a
  /// cloud with a rim, core/views/rim_merge.h), which gets one start.
  int starts = 5;
};

/** \brief Sec. 4.2: supernodes. */
struct SupernodeParams {
  /// Fraction of |N(p)| below which a supernode's neighbours of p count as reached through
  /// feature-crossing edges (Sec. 4.2 (b)).
  float crossing_fraction = 0.3f;
};

/** \brief Sec. 4.3: local refinement; extension: crease splits. */
struct RefinementParams {
  float area_fraction = 0.01f;   ///< small: f_a below this fraction of the total (footnote 4)
  float height_fraction = 0.01f; ///< skinny: f_h below this fraction of the largest (footnote 5)
  /// Extension: split a supernode along its most concave level cut of f when that cut's mean
  /// concave bend (in units of the model's mean bend per kNN edge) is at least this. Off: the
  /// paper.
  std::optional<double> crease_split = 0.75;
};

/** \brief Sec. 7: CAD mode, the faces of a mechanical part separated at its ridges. */
struct CadParams {
  bool enabled = false;     ///< CAD mode instead of elongated parts
  float ridge_angle = 5.0f; ///< degrees: mean normal turn to the neighbours on a ridge point
};

/** \brief Sec. 5.1: the weights of the supernode graph G_s. */
struct SimilarityParams {
  double beta = 2.0;   ///< eq. (7)
  double alpha1 = 2.0; ///< eq. (9)
  double alpha2 = 0.5; ///< eq. (9): alpha_ij = alpha2 min(f_w) / max(f_w)
  /// Extension: the feature width divided by sqrt(total feature area), so that eq. (7) is
  /// unit-free (false: the paper).
  bool normalize_width = true;
  /// Extension: which touching supernodes are joined (Saddles: the paper).
  Adjacency adjacency = Adjacency::All;
  /// Extension: the weight of eq. (9) times exp(-w c), c the concavity of the pair's contact.
  std::optional<double> concavity = 3.0;
  /// Extension (core/cut/thickness.h): eq. (9)'s alpha_ij also times the ratio of the two
  /// supernodes' thickness (their medial balls' radii), as it is times their widths' ratio: a
  /// fin or a wing is thinner than the body it grows from. Closed surfaces without noise only
  /// (a view has no far side; noise blurs a thin part's two sides). Off: the paper.
  bool thickness = true;
  /// Extension: flat supernodes (f_h < e sqrt(f_a)) leave the width ratio out of eq. (9).
  std::optional<double> flat_elongation = 0.1;
};

/** \brief Sec. 5.2: the hierarchy of bisections and its stopping rule. */
struct StoppingParams {
  StoppingRule rule = StoppingRule::ShortCut; ///< extension (Threshold: the paper)
  double threshold = 0.1;   ///< no part is split at a higher NCut (every rule but Count)
  int segments = 2;         ///< Count: the number of segments asked for
  int max_segments = 20;    ///< ShortCut: at most this many segments
  double neck_bound = 0.25; ///< ShortCut: the weighted NCut below which a split is worth it
};

/** \brief Extension: point-level boundaries by minimum cuts between touching segments. */
struct BoundaryParams {
  /// The band around each common boundary holds at most this fraction of either segment's
  /// area. Off: boundaries are supernode boundaries (the paper).
  std::optional<double> band = 0.2;
  /// Extension (core/views/rim_merge.h), open views only: two touching segments, one of which
  /// reaches the view's rim, are merged when the planes of the boundary's two sides (each its
  /// points within half the width of the smallest part, 1% of the object's feature area, of
  /// the other side) meet at a concave angle below this many degrees (PCL's LCCP calls 10
  /// degrees convex) and the boundary is no limb's neck; then a segment smaller than the paper's
  /// small part (1% of the object's area, twice the view's) joins the neighbour it shares most
  /// kNN edges with, unless a limb's neck holds it (core/views/small_segments.h). Off: the paper.
  std::optional<double> rim_merge = 10.0;
};

/** \brief How the work runs; the result never depends on it. */
struct ExecutionParams {
  unsigned num_threads = 0; ///< 0: the cores free at each phase (all on an idle machine)
};

/** \brief All parameters, by stage. */
struct Parameters {
  GraphParams graph;
  CentralityParams centrality;
  SupernodeParams supernodes;
  RefinementParams refinement;
  CadParams cad;
  SimilarityParams similarity;
  StoppingParams stopping;
  BoundaryParams boundary;
  ExecutionParams execution;

  /** \brief The project's defaults (the same as Parameters{}). */
  static Parameters defaults() { return Parameters(); }
  /** \brief The paper to the letter: every extension off, exact centrality, the threshold
   * rule. Execution settings keep their defaults. */
  static Parameters paper();
};

/** \brief The parameters valid? On false, why names the first bad one ("k must be an integer
 * >= 2, got 1"). */
bool validate(const Parameters& params, std::string* why = nullptr);

/** \brief True when params differ from other in a field of an analysis stage. */
bool analysisDiffers(const Parameters& params, const Parameters& other);

} // namespace pcl_ncut_seg
