#include <pcl_ncut_seg/parameter_table.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <limits>
#include <optional>
#include <sstream>
#include <type_traits>

namespace pcl_ncut_seg {

namespace {
/// The shortest "%g" text that reads back as value (by read), in plain notation where %g
/// allows it at a larger precision (90, not 9e+01).
template <typename Read> std::string shortest(double value, int max_precision, Read read) {
  char buf[64];
  const double magnitude = std::fabs(value);
  const bool plain = magnitude >= 1e-4 && magnitude < 1e15;
  for (int precision = 1; precision <= max_precision; ++precision) {
    std::snprintf(buf, sizeof buf, "%.*g", precision, value);
    if (read(buf) && !(plain && std::strchr(buf, 'e')))
      break;
  }
  return buf;
}
} // namespace

std::string formatNumber(double value) {
  return shortest(value, 17, [value](const char* s) { return std::strtod(s, nullptr) == value; });
}

std::string formatNumber(float value) {
  return shortest(value, 9, [value](const char* s) { return std::strtof(s, nullptr) == value; });
}

namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

/** \brief A numeric range and the words for it. */
struct Range {
  double lo = -kInf, hi = kInf;
  bool lo_open = false, hi_open = false;

  bool contains(double v) const {
    return std::isfinite(v) && (lo_open ? v > lo : v >= lo) && (hi_open ? v < hi : v <= hi);
  }
  std::string words(bool integer) const {
    const std::string what = integer ? "an integer" : "a number";
    const std::string l = formatNumber(lo), h = formatNumber(hi);
    if (hi == kInf)
      return what + (lo_open ? " > " : " >= ") + l;
    return what + " in " + (lo_open ? "(" : "[") + l + ", " + h + (hi_open ? ")" : "]");
  }
};
Range atLeast(double lo) {
  return {lo, kInf, false, false};
}
Range above(double lo) {
  return {lo, kInf, true, false};
}
Range closed(double lo, double hi) {
  return {lo, hi, false, false};
}
Range leftOpen(double lo, double hi) {
  return {lo, hi, true, false};
}

bool fail(std::string* why, const ParameterInfo& row, const std::string& got) {
  if (why)
    *why = row.name + " must be " + row.range + ", got " + got;
  return false;
}

/** \brief The text as a number, or nullopt: decimal only (no hexadecimal, no spaces, no
 * "inf" or "nan"), an integer as optional sign and digits. */
std::optional<double> parseNumber(const std::string& text, bool integer) {
  const char* allowed = integer ? "+-0123456789" : "+-0123456789.eE";
  if (text.empty() || text.find_first_not_of(allowed) != std::string::npos)
    return std::nullopt;
  char* end = nullptr;
  const double v = std::strtod(text.c_str(), &end); // (an underflow reads as a denormal)
  if (*end != '\0' || !std::isfinite(v))
    return std::nullopt;
  return v;
}

template <typename T> std::string numberText(T v) {
  if constexpr (std::is_integral_v<T>)
    return std::to_string(v);
  else
    return formatNumber(v);
}

/** \brief Common fields of a row. */
ParameterInfo row(const char* name, const char* field, Stage stage, ValueKind kind,
                  const char* value_name, const char* help, bool paper,
                  std::vector<std::string> aliases = {}) {
  ParameterInfo r;
  r.name = name;
  r.field = field;
  r.stage = stage;
  r.kind = kind;
  r.value_name = value_name;
  r.help = help;
  r.paper = paper;
  r.aliases = std::move(aliases);
  return r;
}

/** \brief A number field of type T (int, unsigned, float, double), or an optional one when
 * off_word is given (nullopt reads and prints as off_word). Access returns the field. */
template <typename T, typename Field, typename Access>
ParameterInfo number(ParameterInfo r, Range range, Access access, const char* off_word = "") {
  constexpr bool kInteger = std::is_integral_v<T>;
  constexpr bool kOptional = !std::is_same_v<Field, T>;
  r.kind = kInteger ? ValueKind::Integer : ValueKind::Real;
  r.lo = range.lo;
  r.hi = range.hi;
  r.lo_open = range.lo_open;
  r.hi_open = range.hi_open;
  r.off_word = off_word;
  r.range = range.words(kInteger) + (kOptional ? std::string(" or ") + off_word : "");
  // In range, whole for an integer, and representable by the field's type (no undefined cast).
  const auto valid = [range](double v) {
    return range.contains(v) && (!kInteger || v == std::floor(v)) &&
           v >= static_cast<double>(std::numeric_limits<T>::lowest()) &&
           v <= static_cast<double>(std::numeric_limits<T>::max());
  };
  r.get = [access, off = r.off_word](const Parameters& p) -> std::string {
    const Field& f = access(const_cast<Parameters&>(p));
    if constexpr (kOptional)
      return f ? numberText<T>(*f) : off;
    else
      return numberText<T>(f);
  };
  r.set = [r, access, valid](Parameters& p, const std::string& text, std::string* why) {
    if constexpr (kOptional)
      if (text == r.off_word) {
        access(p) = std::nullopt;
        return true;
      }
    const std::optional<double> v = parseNumber(text, kInteger);
    if (!v || !valid(*v) || !valid(static_cast<double>(static_cast<T>(*v))))
      return fail(why, r, "'" + text + "'");
    access(p) = static_cast<T>(*v);
    return true;
  };
  r.check = [r, access, valid](const Parameters& p, std::string* why) {
    const Field& f = access(const_cast<Parameters&>(p));
    if constexpr (kOptional) {
      if (!f)
        return true;
      return valid(static_cast<double>(*f)) || fail(why, r, numberText<T>(*f));
    } else {
      return valid(static_cast<double>(f)) || fail(why, r, numberText<T>(f));
    }
  };
  return r;
}

/** \brief A bool field: "on" or "off" (a switch: on when given). */
template <typename Access> ParameterInfo boolean(ParameterInfo r, Access access) {
  r.range = "on or off";
  r.get = [access](const Parameters& p) {
    return access(const_cast<Parameters&>(p)) ? std::string("on") : std::string("off");
  };
  r.set = [r, access](Parameters& p, const std::string& text, std::string* why) {
    if (text == "on" || (text.empty() && r.kind == ValueKind::Switch))
      access(p) = true;
    else if (text == "off")
      access(p) = false;
    else
      return fail(why, r, "'" + text + "'");
    return true;
  };
  r.check = [](const Parameters&, std::string*) { return true; };
  return r;
}

/** \brief An enum field: one of the words, in the enum's order. */
template <typename E, typename Access>
ParameterInfo choice(ParameterInfo r, std::vector<std::string> words, Access access) {
  r.kind = ValueKind::Choice;
  r.choices = words;
  std::string range = "one of ";
  for (std::size_t i = 0; i < words.size(); ++i)
    range += (i ? ", " : "") + words[i];
  r.range = range;
  r.get = [words, access](const Parameters& p) {
    const auto i = static_cast<std::size_t>(access(const_cast<Parameters&>(p)));
    return i < words.size() ? words[i] : std::to_string(i);
  };
  r.set = [r, words, access](Parameters& p, const std::string& text, std::string* why) {
    for (std::size_t i = 0; i < words.size(); ++i)
      if (text == words[i]) {
        access(p) = static_cast<E>(i);
        return true;
      }
    return fail(why, r, "'" + text + "'");
  };
  r.check = [r, words, access](const Parameters& p, std::string* why) {
    const auto i = static_cast<std::size_t>(access(const_cast<Parameters&>(p)));
    return i < words.size() || fail(why, r, std::to_string(i));
  };
  return r;
}

#define FIELD(path)                                                                                \
  [](Parameters & p) -> auto& {                                                                    \
    return p.path;                                                                                 \
  }

std::vector<ParameterInfo> makeTable();

} // namespace

const std::vector<ParameterInfo>& parameterTable() {
  static const std::vector<ParameterInfo> table = makeTable();
  return table;
}

const ParameterInfo* findParameter(const std::string& name) {
  for (const ParameterInfo& r : parameterTable()) {
    if (r.name == name)
      return &r;
    for (const std::string& a : r.aliases)
      if (a == name)
        return &r;
  }
  return nullptr;
}

const std::vector<Shorthand>& parameterShorthands() {
  static const std::vector<Shorthand> shorthands = {
      {"exact", "centrality", "exact", "the same as -centrality exact"},
  };
  return shorthands;
}

bool setParameter(Parameters& params, const std::string& name, const std::string& text,
                  std::string* why) {
  const ParameterInfo* r = findParameter(name);
  if (!r) {
    if (why)
      *why = "unknown parameter '" + name + "'";
    return false;
  }
  return r->set(params, text, why);
}

std::string parameterValue(const Parameters& params, const std::string& name) {
  const ParameterInfo* r = findParameter(name);
  return r ? r->get(params) : std::string();
}

std::string parameterMarkdown() {
  const Parameters defaults, paper = Parameters::paper();
  std::ostringstream md;
  md << "| Stage | Flag / keyword | Field | Default | Paper | Values | Meaning |\n"
     << "|---|---|---|---|---|---|---|\n";
  for (const ParameterInfo& r : parameterTable()) {
    std::string help = r.help;
    for (std::size_t at = help.find('|'); at != std::string::npos; at = help.find('|', at + 2))
      help.replace(at, 1, "\\|");
    md << "| " << stageName(r.stage) << " | `-" << r.name << "` | `" << r.field << "` | "
       << r.get(defaults) << " | " << r.get(paper) << " | " << r.range << " | " << help
       << (r.paper ? "" : " *(extension)*") << " |\n";
  }
  return md.str();
}

namespace {

std::vector<ParameterInfo> makeTable() {
  using S = Stage;
  using K = ValueKind;
  std::vector<ParameterInfo> t;
  // Graph (Sec. 4.1)
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
          false, {"bridge"}),
      above(0), FIELD(graph.bridge_gap), "off"));
  t.push_back(number<double, std::optional<double>>(
      row("denoise", "graph.denoise", S::Graph, K::Real, "G",
          "sensor noise: when the scatter of the points about their local planes grows less "
          "than G times from the 1-ring to the 2-ring (noise, not curvature: about 1 against "
          "4), project each point onto its 2-ring's plane first; not in CAD mode",
          false),
      above(1), FIELD(graph.denoise), "off"));
  t.push_back(number<int, std::optional<int>>(
      row("max_points", "graph.max_points", S::Graph, K::Integer, "N",
          "the analysis' resolution: a denser cloud is analysed on at most N of its points (the "
          "point nearest the centre of each cube of a grid; the same whatever their order) and "
          "every other point takes the segment of its nearest analysed point",
          false),
      atLeast(100), FIELD(graph.max_points), "off"));
  // Centrality (Sec. 4.1)
  t.push_back(number<int, std::optional<int>>(
      row("centrality_samples", "centrality.samples", S::Centrality, K::Integer, "S",
          "centrality samples per connected component; auto: ceil(sqrt(n)) as in the paper", true,
          {"cen_samples"}),
      atLeast(1), FIELD(centrality.samples), "auto"));
  t.push_back(choice<CentralityMode>(
      row("centrality", "centrality.mode", S::Centrality, K::Choice, "MODE",
          "exact: eq. (1) with searches over the whole kNN graph, as the paper; fast: on a "
          "coarse graph of representatives, carried back to every point",
          false),
      {"exact", "fast"}, FIELD(centrality.mode)));
  t.push_back(number<int, int>(
      row("representatives", "centrality.representatives", S::Centrality, K::Integer, "R",
          "fast centrality: points of the coarse graph (clouds of at most R points are "
          "computed exactly)",
          false),
      atLeast(100), FIELD(centrality.representatives)));
  t.push_back(number<int, int>(
      row("starts", "centrality.starts", S::Centrality, K::Integer, "S",
          "farthest-point sampling of eq. (1) from S starts (the first S samples of one chain), "
          "a segmentation from each; the one closest to the others by Rand index is kept (1: "
          "one start, the paper; CAD mode and open views: one)",
          false),
      closed(1, 16), FIELD(centrality.starts)));
  // Supernodes (Sec. 4.2)
  t.push_back(number<float, float>(
      row("crossing_fraction", "supernodes.crossing_fraction", S::Supernodes, K::Real, "F",
          "fraction of |N(p)| below which a supernode's neighbours of p count as reached "
          "through feature-crossing edges (Sec. 4.2 (b))",
          true, {"crossing"}),
      closed(0, 1), FIELD(supernodes.crossing_fraction)));
  // Refinement (Sec. 4.3)
  t.push_back(number<float, float>(
      row("area_fraction", "refinement.area_fraction", S::Refinement, K::Real, "F",
          "small supernodes: feature area below this fraction of the total (Sec. 4.3)", true,
          {"area"}),
      closed(0, 1), FIELD(refinement.area_fraction)));
  t.push_back(number<float, float>(
      row("height_fraction", "refinement.height_fraction", S::Refinement, K::Real, "F",
          "skinny supernodes: feature height below this fraction of the largest (Sec. 4.3)", true,
          {"height"}),
      closed(0, 1), FIELD(refinement.height_fraction)));
  t.push_back(number<double, std::optional<double>>(
      row("crease_split", "refinement.crease_split", S::Refinement, K::Real, "C",
          "crease splits: split a supernode along its most concave level cut of the "
          "centrality when that cut's mean concave bend (in mean bends per kNN edge) is at "
          "least C",
          false, {"crease"}),
      above(0), FIELD(refinement.crease_split), "off"));
  t.push_back(number<double, std::optional<double>>(
      row("crease_cut", "refinement.crease_cut", S::Refinement, K::Real, "S",
          "crease cuts: split a supernode that no level cut splits along its minimum cut "
          "weighted by concave bend when a share of at least S of the edges it crosses are "
          "concave",
          false, {"creasecut"}),
      leftOpen(0, 1), FIELD(refinement.crease_cut), "off"));
  // CAD (Sec. 7)
  t.push_back(boolean(row("cad", "cad.enabled", S::Cad, K::Switch, "",
                          "CAD mode (Sec. 7): the faces of a mechanical part, separated at its "
                          "ridges, instead of elongated parts",
                          true),
                      FIELD(cad.enabled)));
  t.push_back(
      number<int, int>(row("cad_smoothing", "cad.smoothing_iterations", S::Cad, K::Integer, "N",
                           "CAD mode: Laplacian smoothing steps of the approximate normals", true),
                       atLeast(0), FIELD(cad.smoothing_iterations)));
  t.push_back(number<float, float>(
      row("ridge_angle", "cad.ridge_angle", S::Cad, K::Real, "DEG",
          "CAD mode: a ridge point's normal turns by more than this to its neighbours' on "
          "average",
          true),
      leftOpen(0, 90), FIELD(cad.ridge_angle)));
  t.push_back(number<float, float>(
      row("ridge_shrink", "cad.shrink", S::Cad, K::Real, "F",
          "CAD mode: length factor of edges between points equidistant from a ridge", true),
      above(0), FIELD(cad.shrink)));
  t.push_back(number<float, float>(
      row("ridge_stretch", "cad.stretch", S::Cad, K::Real, "F",
          "CAD mode: length factor of edges pointing straight away from a ridge", true),
      above(0), FIELD(cad.stretch)));
  // Similarity (Sec. 5.1)
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
          "supernodes that touch but meet at no saddle), all (every touching pair, subject to "
          "-adjacent_share)",
          false),
      {"saddles", "trees", "all"}, FIELD(similarity.adjacency)));
  t.push_back(number<double, double>(
      row("adjacent_share", "similarity.adjacent_share", S::Similarity, K::Real, "S",
          "adjacency all: a pair that meets at no saddle is joined when its contact is at "
          "least this share of the smaller total contact of the two",
          false, {"share"}),
      closed(0, 1), FIELD(similarity.adjacent_share)));
  t.push_back(number<double, std::optional<double>>(
      row("concavity", "similarity.concavity", S::Similarity, K::Real, "W",
          "concave creases: the weight of eq. (9) is multiplied by exp(-W c), c how concave "
          "the pair's contact is",
          false, {"concavity_weight"}),
      above(0), FIELD(similarity.concavity), "off"));
  t.push_back(number<double, std::optional<double>>(
      row("flat_elongation", "similarity.flat_elongation", S::Similarity, K::Real, "E",
          "flat patches: between two supernodes with feature height < E sqrt(feature area), "
          "eq. (9) leaves out the width ratio",
          false, {"flat"}),
      above(0), FIELD(similarity.flat_elongation), "off"));
  t.push_back(number<float, float>(
      row("face_angle", "similarity.face_angle", S::Similarity, K::Real, "DEG",
          "CAD mode: angle scale of the face-orientation similarity exp(-(angle / DEG)^2)", false),
      leftOpen(0, 90), FIELD(similarity.face_angle)));
  // Stopping (Sec. 5.2)
  t.push_back(choice<StoppingRule>(
      row("stopping", "stopping.rule", S::Stopping, K::Choice, "RULE",
          "threshold: bisect while the best NCut <= -threshold (the paper); largest_gap: "
          "best-first splits up to the largest jump in NCut; short_cut: best-first splits "
          "across short boundaries; count: -segments parts",
          false),
      {"threshold", "largest_gap", "short_cut", "count"}, FIELD(stopping.rule)));
  t.push_back(number<double, double>(
      row("threshold", "stopping.threshold", S::Stopping, K::Real, "T",
          "normalized-cut threshold (Sec. 5.2): no part is split at a higher NCut", true),
      atLeast(0), FIELD(stopping.threshold)));
  {
    // Asking for a number of segments is choosing the count rule.
    ParameterInfo segments = number<int, int>(
        row("segments", "stopping.segments", S::Stopping, K::Integer, "N",
            "ask for N segments (sets -stopping count); fewer come out when no part can be "
            "split",
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
  t.push_back(
      number<int, int>(row("splits", "stopping.num_splits", S::Stopping, K::Integer, "N",
                           "uniform split values tried on each eigenvector (Sec. 5.2)", true),
                       atLeast(1), FIELD(stopping.num_splits)));
  t.push_back(number<double, std::optional<double>>(
      row("min_segment_fraction", "stopping.min_segment_fraction", S::Stopping, K::Real, "F",
          "threshold rule: a part is bisected only if each side keeps this fraction of the "
          "feature area",
          false, {"min_fraction"}),
      leftOpen(0, 0.5), FIELD(stopping.min_segment_fraction), "off"));
  t.push_back(
      number<int, int>(row("max_segments", "stopping.max_segments", S::Stopping, K::Integer, "N",
                           "largest_gap, short_cut: at most N segments", false, {"maxseg"}),
                       atLeast(1), FIELD(stopping.max_segments)));
  t.push_back(number<double, double>(
      row("gap_floor", "stopping.gap_floor", S::Stopping, K::Real, "F",
          "largest_gap, short_cut: NCut values below F count as F", false, {"gapfloor"}),
      above(0), FIELD(stopping.gap_floor)));
  t.push_back(number<double, double>(
      row("neck_exponent", "stopping.neck_exponent", S::Stopping, K::Real, "W",
          "short_cut: a split's NCut is weighted by neck^W, neck = its boundary's length over "
          "the square root of the smaller side's area",
          false, {"neck"}),
      above(0), FIELD(stopping.neck_exponent)));
  t.push_back(number<double, double>(
      row("neck_bound", "stopping.neck_bound", S::Stopping, K::Real, "B",
          "short_cut: the weighted NCut below which a split is worth making (larger: more "
          "segments)",
          false, {"neckbound"}),
      above(0), FIELD(stopping.neck_bound)));
  // Boundary
  t.push_back(number<double, std::optional<double>>(
      row("boundary_band", "boundary.band", S::Boundary, K::Real, "F",
          "boundary refinement: recut each pair of touching segments by a minimum cut within "
          "a band holding at most this fraction of either segment's area",
          false, {"band"}),
      leftOpen(0, 0.5), FIELD(boundary.band), "off"));
  t.push_back(number<double, double>(
      row("boundary_crease", "boundary.crease_weight", S::Boundary, K::Real, "W",
          "boundary refinement: a kNN edge's cut cost is its length times exp(-W c), c its "
          "concave bend (0: the shortest boundary)",
          false, {"bandcrease"}),
      atLeast(0), FIELD(boundary.crease_weight)));
  t.push_back(number<double, std::optional<double>>(
      row("rim_merge", "boundary.rim_merge", S::Boundary, K::Real, "DEG",
          "open views (an organized cloud, or one view from the sensor origin): merge two "
          "touching segments, one reaching the view's rim, when the planes of the boundary's "
          "two sides (3 rings each) meet at a concave angle below DEG degrees and its neck is "
          "at least sqrt(pi) (no limb's); not in CAD mode",
          false),
      leftOpen(0, 180), FIELD(boundary.rim_merge), "off"));
  t.push_back(number<double, std::optional<double>>(
      row("view_small_segment", "boundary.view_small_segment", S::Boundary, K::Real, "F",
          "open views (as rim_merge): a segment whose area is below F of the object's (taken "
          "as twice the view's: a view shows at most half of a closed surface) joins the "
          "touching segment it shares most kNN edges with; not in CAD mode",
          false),
      leftOpen(0, 0.5), FIELD(boundary.view_small_segment), "off"));
  // Execution
  t.push_back(number<unsigned, unsigned>(
      row("threads", "execution.num_threads", S::Execution, K::Integer, "N",
          "threads; 0: all cores; the result does not depend on it", false),
      atLeast(0), FIELD(execution.num_threads)));
  return t;
}

} // namespace
} // namespace pcl_ncut_seg
