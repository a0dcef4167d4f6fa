#include "core/parameters/parameter_row_builders.h"

namespace pcl_ncut_seg {
namespace {
using namespace table_rows;
using S = Stage;
using K = ValueKind;
using Rows = std::vector<ParameterInfo>;

/// The field at a path of Parameters, as number(), boolean() and choice() take it.
#define FIELD(path)                                                                                \
  [](Parameters & p) -> auto& {                                                                    \
    return p.path;                                                                                 \
  }

/// Graph (Sec. 4.1)
void graphRows(Rows& t) {
  t.push_back(number<int, int>(
      row("k", "graph.k", S::Graph, K::Integer, "K",
          "nearest neighbours per point; p and q are joined if either is among the other's k "
          "nearest (Sec. 4.1)",
          true),
      atLeast(2), FIELD(graph.k)));
  t.push_back(number<double, std::optional<double>>(
      row("bridge_gap", "graph.bridge_gap", S::Graph, K::Real, "G",
          "join components of the kNN graph that only a sampling gap separates, by their "
          "shortest point pair when it is at most G kNN radii long",
          false),
      above(0), FIELD(graph.bridge_gap), "off"));
  t.push_back(number<double, std::optional<double>>(
      row("denoise", "graph.denoise", S::Graph, K::Real, "G",
          "sensor noise: when the scatter of the points about their local planes grows less "
          "than G times from the 1-ring to the 2-ring (noise, not curvature: about 1 against "
          "4), project each point onto its 2-ring's plane first and, but on an open view, "
          "average the centrality over each point's neighbourhood once; not in CAD mode",
          false),
      above(1), FIELD(graph.denoise), "off"));
  t.push_back(number<double, std::optional<double>>(
      row("irregular_sampling", "graph.irregular_sampling", S::Graph, K::Real, "V",
          "irregular sampling: when the points' spacings vary by at least V (the coefficient of "
          "variation of each point's shortest over its mean kNN edge: about 0.45 for points "
          "drawn at random, 0.05-0.2 for points spread evenly), average the centrality over "
          "each point's neighbourhood once, but on an open view; not in CAD mode",
          false),
      above(0), FIELD(graph.irregular_sampling), "off"));
  t.push_back(number<int, std::optional<int>>(
      row("max_points", "graph.max_points", S::Graph, K::Integer, "N",
          "the analysis' resolution: a denser cloud is analysed on at most N of its points (the "
          "point nearest the centre of each cube of a grid; the same whatever their order) and "
          "every other point takes the segment of its nearest analysed point",
          false),
      atLeast(100), FIELD(graph.max_points), "off"));
  t.push_back(boolean(row("single_view", "graph.single_view", S::Graph, K::Boolean, "on|off",
                          "open views: a cloud that is one view from its sensor origin (a depth "
                          "image, organized or not, or a scanner's) is a view, its rim where the "
                          "surface leaves the sensor's sight; not in CAD mode",
                          false),
                      FIELD(graph.single_view)));
}

/// Centrality (Sec. 4.1)
void centralityRows(Rows& t) {
  t.push_back(number<int, std::optional<int>>(
      row("centrality_samples", "centrality.samples", S::Centrality, K::Integer, "S",
          "centrality samples per connected component; auto: ceil(sqrt(n)) as in the paper", true),
      atLeast(1), FIELD(centrality.samples), "auto"));
  t.push_back(choice<CentralityMode>(
      row("centrality", "centrality.mode", S::Centrality, K::Choice, "MODE",
          "exact: eq. (1) with searches over the whole kNN graph, as the paper; fast: on a "
          "coarse graph of 20,000 representatives, carried back to every point (exact up to "
          "25,000 points)",
          false),
      {"exact", "fast"}, FIELD(centrality.mode)));
  t.push_back(number<int, int>(
      row("starts", "centrality.starts", S::Centrality, K::Integer, "S",
          "farthest-point sampling of eq. (1) from S starts (the first S samples of one chain), "
          "a segmentation from each; the one closest to the others by Rand index is kept (1: "
          "one start, the paper; CAD mode and open views: one)",
          false),
      closed(1, 16), FIELD(centrality.starts)));
}

/// Supernodes (Sec. 4.2)
void supernodeRows(Rows& t) {
  t.push_back(number<float, float>(
      row("crossing_fraction", "supernodes.crossing_fraction", S::Supernodes, K::Real, "F",
          "fraction of |N(p)| below which a supernode's neighbours of p count as reached "
          "through feature-crossing edges (Sec. 4.2 (b))",
          true),
      closed(0, 1), FIELD(supernodes.crossing_fraction)));
}

/// Refinement (Sec. 4.3)
void refinementRows(Rows& t) {
  t.push_back(number<float, float>(
      row("area_fraction", "refinement.area_fraction", S::Refinement, K::Real, "F",
          "small supernodes: feature area below this fraction of the total (Sec. 4.3)", true),
      closed(0, 1), FIELD(refinement.area_fraction)));
  t.push_back(number<float, float>(
      row("height_fraction", "refinement.height_fraction", S::Refinement, K::Real, "F",
          "skinny supernodes: feature height below this fraction of the largest (Sec. 4.3)", true),
      closed(0, 1), FIELD(refinement.height_fraction)));
  t.push_back(number<double, std::optional<double>>(
      row("crease_split", "refinement.crease_split", S::Refinement, K::Real, "C",
          "crease splits: split a supernode along its most concave level cut of the "
          "centrality when that cut's mean concave bend (in mean bends per kNN edge) is at "
          "least C",
          false),
      above(0), FIELD(refinement.crease_split), "off"));
}

/// CAD (Sec. 7)
void cadRows(Rows& t) {
  t.push_back(boolean(row("cad", "cad.enabled", S::Cad, K::Switch, "",
                          "CAD mode (Sec. 7): the faces of a mechanical part, separated at its "
                          "ridges, instead of elongated parts",
                          true),
                      FIELD(cad.enabled)));
  t.push_back(number<float, float>(
      row("ridge_angle", "cad.ridge_angle", S::Cad, K::Real, "DEG",
          "CAD mode: a ridge point's normal turns by more than this to its neighbours' on "
          "average",
          true),
      leftOpen(0, 90), FIELD(cad.ridge_angle)));
}

/// Similarity (Sec. 5.1)
void similarityRows(Rows& t) {
  t.push_back(number<double, double>(
      row("beta", "similarity.beta", S::Similarity, K::Real, "B",
          "beta of eq. (7), the weight between a supernode's representative and member "
          "vertices",
          true),
      above(0), FIELD(similarity.beta)));
  t.push_back(
      number<double, double>(row("alpha1", "similarity.alpha1", S::Similarity, K::Real, "A",
                                 "alpha1 of eq. (9), the weight between member vertices", true),
                             above(0), FIELD(similarity.alpha1)));
  t.push_back(number<double, double>(
      row("alpha2", "similarity.alpha2", S::Similarity, K::Real, "A",
          "alpha2 of eq. (9), which scales the width ratio of two supernodes", true),
      above(0), FIELD(similarity.alpha2)));
  t.push_back(boolean(row("normalize_width", "similarity.normalize_width", S::Similarity,
                          K::Boolean, "on|off",
                          "divide the feature width by sqrt(total feature area), so that eq. "
                          "(7) does not depend on units",
                          false),
                      FIELD(similarity.normalize_width)));
  t.push_back(choice<Adjacency>(
      row("adjacency", "similarity.adjacency", S::Similarity, K::Choice, "WHICH",
          "which touching supernodes are joined: saddles (the paper), trees (also trees of "
          "supernodes that touch but meet at no saddle), all (every pair touching across a "
          "long enough boundary)",
          false),
      {"saddles", "trees", "all"}, FIELD(similarity.adjacency)));
  t.push_back(number<double, std::optional<double>>(
      row("concavity", "similarity.concavity", S::Similarity, K::Real, "W",
          "concave creases: the weight of eq. (9) is multiplied by exp(-W c), c how concave "
          "the pair's contact is",
          false),
      above(0), FIELD(similarity.concavity), "off"));
  t.push_back(boolean(row("thickness", "similarity.thickness", S::Similarity, K::Boolean, "on|off",
                          "thin parts: eq. (9)'s width ratio also times the ratio of the two "
                          "supernodes' thickness (medial balls), on closed surfaces without "
                          "noise",
                          false),
                      FIELD(similarity.thickness)));
  t.push_back(number<double, std::optional<double>>(
      row("flat_elongation", "similarity.flat_elongation", S::Similarity, K::Real, "E",
          "flat patches: between two supernodes with feature height < E sqrt(feature area), "
          "eq. (9) leaves out the width ratio",
          false),
      above(0), FIELD(similarity.flat_elongation), "off"));
}

/// Stopping (Sec. 5.2)
void stoppingRows(Rows& t) {
  t.push_back(choice<StoppingRule>(
      row("stopping", "stopping.rule", S::Stopping, K::Choice, "RULE",
          "threshold: bisect while the best NCut <= -threshold (the paper); short_cut: "
          "best-first splits across short boundaries; count: the -segments strongest parts, "
          "merged bottom-up from the supernodes",
          false),
      {"threshold", "short_cut", "count"}, FIELD(stopping.rule)));
  t.push_back(number<double, double>(
      row("threshold", "stopping.threshold", S::Stopping, K::Real, "T",
          "normalized-cut threshold (Sec. 5.2): no part is split at a higher NCut", true),
      atLeast(0), FIELD(stopping.threshold)));
  {
    // Asking for a number of segments is choosing the count rule.
    ParameterInfo segments = number<int, int>(
        row("segments", "stopping.segments", S::Stopping, K::Integer, "N",
            "ask for N segments (sets -stopping count): the supernodes merge, weakest "
            "boundary first, until N are left; fewer come out when there are fewer "
            "supernodes",
            false),
        atLeast(1), FIELD(stopping.segments));
    const auto set = segments.set;
    segments.set = [set](Parameters& p, const std::string& text, std::string* why) {
      if (!set(p, text, why))
        return false;
      p.stopping.rule = StoppingRule::Count;
      return true;
    };
    t.push_back(segments);
  }
  t.push_back(number<int, int>(row("max_segments", "stopping.max_segments", S::Stopping, K::Integer,
                                   "N", "short_cut: at most N segments", false),
                               atLeast(1), FIELD(stopping.max_segments)));
  t.push_back(number<double, double>(
      row("neck_bound", "stopping.neck_bound", S::Stopping, K::Real, "B",
          "short_cut: the weighted NCut below which a split is worth making (larger: more "
          "segments)",
          false),
      above(0), FIELD(stopping.neck_bound)));
}

/// Boundary
void boundaryRows(Rows& t) {
  t.push_back(number<double, std::optional<double>>(
      row("boundary_band", "boundary.band", S::Boundary, K::Real, "F",
          "boundary refinement: recut each pair of touching segments by a minimum cut within "
          "a band holding at most this fraction of either segment's area",
          false),
      leftOpen(0, 0.5), FIELD(boundary.band), "off"));
  t.push_back(number<double, std::optional<double>>(
      row("rim_merge", "boundary.rim_merge", S::Boundary, K::Real, "DEG",
          "open views (one view from the sensor origin, -single_view): merge two "
          "touching segments, one reaching the view's rim, when the planes of the boundary's "
          "two sides (each its points within half the width of a part of 1% of the object's "
          "feature area) meet at a concave angle below DEG degrees and its neck is "
          "at least sqrt(pi) (no limb's); then a segment below 1% of the object's area "
          "(twice the view's) joins its neighbour unless a limb's neck holds it; not in CAD "
          "mode",
          false),
      leftOpen(0, 180), FIELD(boundary.rim_merge), "off"));
}

/// Execution
void executionRows(Rows& t) {
  t.push_back(number<unsigned, unsigned>(row("threads", "execution.num_threads", S::Execution,
                                             K::Integer, "N",
                                             "threads; 0: the cores free at each phase (all on an "
                                             "idle machine); the result does not depend on it",
                                             false),
                                         atLeast(0), FIELD(execution.num_threads)));
}

} // namespace

std::vector<ParameterInfo> makeParameterTable() {
  Rows t;
  graphRows(t);
  centralityRows(t);
  supernodeRows(t);
  refinementRows(t);
  cadRows(t);
  similarityRows(t);
  stoppingRows(t);
  boundaryRows(t);
  executionRows(t);
  return t;
}

} // namespace pcl_ncut_seg
