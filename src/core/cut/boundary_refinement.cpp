// Point-level boundary refinement after the hierarchy (an extension of Sec. 5.2; Katz and Tal
// 2003's fuzzy cuts over the kNN graph).
#include "core/cut/boundary_refinement.h"
#include "core/common/threads.h"
#include "core/cut/concavity.h"
#include "core/cut/flow_network.h"
#include "core/graph/shortest_paths.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <map>
#include <utility>

namespace pcl_ncut_seg {

std::vector<std::uint8_t> edgeCreases(const CsrGraph& graph, const float* xyz,
                                      const std::vector<float>& normals, unsigned num_threads,
                                      double typical_bend) {
  const std::size_t n = graph.numVertices();
  std::vector<std::uint8_t> crease(graph.numDirectedEdges(), 0);
  const double typical =
      typical_bend > 0.0 ? typical_bend : meanAbsBend(graph, xyz, normals, num_threads);
  if (!(typical > 0.0))
    return crease;
    // Each edge on its own: the same for any thread count.
#pragma omp parallel for schedule(static, 4096) num_threads(usableThreads(num_threads))
  for (std::ptrdiff_t p = 0; p < static_cast<std::ptrdiff_t>(n); ++p)
    for (std::uint32_t e = graph.offsets[p]; e < graph.offsets[p + 1]; ++e) {
      const double c = std::max(0.0, -edgeBend(xyz, normals, static_cast<std::size_t>(p),
                                               graph.targets[e], graph.lengths[e])) /
                       typical;
      crease[e] = static_cast<std::uint8_t>(std::min(255.0, std::round(16.0 * c)));
    }
  return crease;
}

namespace {

/// Connected components of each segment in the graph: per vertex its component (numbered in
/// order of their smallest vertex); returns their number.
std::uint32_t segmentComponents(const CsrGraph& graph, const std::vector<std::uint32_t>& segment,
                                std::vector<std::uint32_t>& component) {
  const std::size_t n = graph.numVertices();
  constexpr std::uint32_t kUnset = std::numeric_limits<std::uint32_t>::max();
  component.assign(n, kUnset);
  std::uint32_t count = 0;
  std::vector<std::uint32_t> stack;
  for (std::uint32_t root = 0; root < n; ++root) {
    if (component[root] != kUnset)
      continue;
    component[root] = count;
    stack.assign(1, root);
    while (!stack.empty()) {
      const std::uint32_t u = stack.back();
      stack.pop_back();
      for (std::uint32_t e = graph.offsets[u]; e < graph.offsets[u + 1]; ++e) {
        const std::uint32_t v = graph.targets[e];
        if (component[v] == kUnset && segment[v] == segment[root]) {
          component[v] = count;
          stack.push_back(v);
        }
      }
    }
    ++count;
  }
  return count;
}

/// Per segment, its number of connected components.
std::vector<std::size_t> componentsPerSegment(const std::vector<std::uint32_t>& segment,
                                              const std::vector<std::uint32_t>& component,
                                              std::uint32_t num_components,
                                              std::size_t num_segments) {
  std::vector<std::uint32_t> segment_of(num_components);
  for (std::size_t p = 0; p < segment.size(); ++p)
    segment_of[component[p]] = segment[p];
  std::vector<std::size_t> count(num_segments, 0);
  for (std::uint32_t c = 0; c < num_components; ++c)
    ++count[segment_of[c]];
  return count;
}

/// A point's area up to the factor pi, which none of the comparisons here needs.
double squaredRadius(const std::vector<float>& radii, std::uint32_t p) {
  return static_cast<double>(radii[p]) * static_cast<double>(radii[p]);
}

/// The frontier of a segmentation (points with a neighbour in another segment) and the pairs
/// of touching segments, kept up to date as recuts move points.
class Frontier {
public:
  Frontier(const CsrGraph& graph, const std::vector<std::uint32_t>& segment)
      : graph_(graph), segment_(segment), in_(graph.numVertices(), 0) {
    for (std::uint32_t p = 0; p < graph.numVertices(); ++p)
      for (std::uint32_t e = graph.offsets[p]; e < graph.offsets[p + 1]; ++e) {
        const std::uint32_t q = graph.targets[e];
        if (segment[q] == segment[p])
          continue;
        if (!in_[p]) {
          in_[p] = 1;
          points_.push_back(p);
        }
        if (segment[p] < segment[q])
          pairs_.emplace_back(segment[p], segment[q]);
      }
    std::sort(pairs_.begin(), pairs_.end());
    pairs_.erase(std::unique(pairs_.begin(), pairs_.end()), pairs_.end());
  }

  /// In order of ids, then as points joined it.
  const std::vector<std::uint32_t>& points() const { return points_; }
  /// The touching segments before any recut, ascending.
  const std::vector<std::pair<std::uint32_t, std::uint32_t>>& pairs() const { return pairs_; }

  /// After a recut: only the changed points and their neighbours can leave or join (the list
  /// keeps its order, then the new ones).
  void update(const std::vector<std::uint32_t>& changed_points) {
    bool left = false;
    for (std::uint32_t p : changed_points)
      for (std::uint32_t e = graph_.offsets[p]; e <= graph_.offsets[p + 1]; ++e) {
        const std::uint32_t q = e < graph_.offsets[p + 1] ? graph_.targets[e] : p;
        if (in_[q] == 1 && !onFrontier(q)) {
          in_[q] = 0;
          left = true;
        }
      }
    if (left) {
      std::size_t kept = 0;
      for (std::uint32_t p : points_)
        if (in_[p])
          points_[kept++] = p;
      points_.resize(kept);
    }
    for (std::uint32_t p : changed_points)
      for (std::uint32_t e = graph_.offsets[p]; e <= graph_.offsets[p + 1]; ++e) {
        const std::uint32_t q = e < graph_.offsets[p + 1] ? graph_.targets[e] : p;
        if (!in_[q] && onFrontier(q)) {
          in_[q] = 1;
          points_.push_back(q);
        }
      }
  }

private:
  bool onFrontier(std::uint32_t p) const {
    for (std::uint32_t e = graph_.offsets[p]; e < graph_.offsets[p + 1]; ++e)
      if (segment_[graph_.targets[e]] != segment_[p])
        return true;
    return false;
  }

  const CsrGraph& graph_;
  const std::vector<std::uint32_t>& segment_;
  std::vector<char> in_;
  std::vector<std::uint32_t> points_;
  std::vector<std::pair<std::uint32_t, std::uint32_t>> pairs_;
};

/// The band (fuzzy region) of two touching segments: each side's points in order of geodesic
/// distance from their boundary, while they hold at most the band fraction of the side's area.
class BandSearch {
public:
  BandSearch(const CsrGraph& graph, const std::vector<float>& radii,
             const std::vector<std::uint32_t>& segment, double band)
      : graph_(graph), radii_(radii), segment_(segment), band_(band),
        dist_(graph.numVertices(), kFar) {}

  /// The band of a and b: the settled points of both sides closer than the final bound, by id;
  /// empty when a side has no area to bound it by.
  std::vector<std::uint32_t> bandOf(std::uint32_t a, std::uint32_t b,
                                    const std::vector<double>& seg_area,
                                    const std::vector<std::uint32_t>& frontier) {
    if (!(seg_area[a] > 0.0) || !(seg_area[b] > 0.0))
      return {};
    // The side with less area first: its distance bound also bounds the other side's search.
    std::uint32_t sides[2] = {a, b};
    if (seg_area[b] < seg_area[a])
      std::swap(sides[0], sides[1]);
    std::vector<std::uint32_t> settled[2];
    touched_.clear();
    float bound = kFar;
    for (int s = 0; s < 2; ++s)
      growSide(sides[s], sides[1 - s], band_ * seg_area[sides[s]], frontier, bound, settled[s]);
    std::vector<std::uint32_t> band;
    for (int s = 0; s < 2; ++s)
      for (std::uint32_t p : settled[s])
        if (dist_[p] < bound)
          band.push_back(p);
    for (std::uint32_t p : touched_)
      dist_[p] = kFar;
    std::sort(band.begin(), band.end());
    return band;
  }

private:
  static constexpr float kFar = std::numeric_limits<float>::infinity();

  /// x's side of the band with y: x's points on the boundary start at half their shortest edge
  /// across it; points are settled while they hold at most cap of x's area and are closer than
  /// bound, which the first point left out lowers (neither side's band may reach past it).
  void growSide(std::uint32_t x, std::uint32_t y, double cap,
                const std::vector<std::uint32_t>& frontier, float& bound,
                std::vector<std::uint32_t>& settled) {
    const std::size_t first_seed = touched_.size();
    for (std::uint32_t p : frontier) {
      if (segment_[p] != x)
        continue;
      for (std::uint32_t e = graph_.offsets[p]; e < graph_.offsets[p + 1]; ++e)
        if (segment_[graph_.targets[e]] == y && 0.5f * graph_.lengths[e] < dist_[p]) {
          if (dist_[p] == kFar)
            touched_.push_back(p);
          dist_[p] = 0.5f * graph_.lengths[e];
        }
    }
    const std::vector<std::uint32_t> seeds(touched_.begin() + first_seed, touched_.end());
    double held = 0.0;
    auto settle = [&](std::uint32_t p, float d) {
      if (d >= bound || held + squaredRadius(radii_, p) > cap) {
        bound = std::min(bound, d); // neither side's band may reach this far
        return Settle::kStop;
      }
      held += squaredRadius(radii_, p);
      settled.push_back(p);
      return Settle::kExpand;
    };
    auto inside = [&](std::uint32_t, std::uint32_t q, float) { return segment_[q] == x; };
    multiSourceDijkstra(graph_, seeds, dist_.data(), inside, settle, nullptr, &touched_);
  }

  const CsrGraph& graph_;
  const std::vector<float>& radii_;
  const std::vector<std::uint32_t>& segment_;
  const double band_;
  std::vector<float> dist_; ///< distance from the boundary; kFar outside a search
  std::vector<std::uint32_t> touched_;
};

/// The recuts of refineBoundaries(): the segments' areas and sizes, the frontier and the band
/// search, and per pair the minimum cut over the band.
class BoundaryRecut {
public:
  BoundaryRecut(const CsrGraph& graph, const std::vector<float>& radii,
                const std::vector<std::uint8_t>& crease, const BoundaryParams& params,
                std::vector<std::uint32_t>& segment, std::size_t num_segments)
      : graph_(graph), radii_(radii), crease_(crease), segment_(segment),
        use_crease_(!crease.empty() && crease.size() == graph.numDirectedEdges()),
        seg_area_(num_segments, 0.0), seg_count_(num_segments, 0), frontier_(graph, segment),
        search_(graph, radii, segment, *params.band), local_(graph.numVertices(), -1) {
    for (std::size_t c = 0; c < factor_.size(); ++c)
      factor_[c] =
          use_crease_ ? std::exp(-kBoundaryCreaseWeight * static_cast<double>(c) / 16.0) : 1.0;
    for (std::uint32_t p = 0; p < graph.numVertices(); ++p) {
      seg_area_[segment[p]] += squaredRadius(radii, p);
      ++seg_count_[segment[p]];
    }
  }

  /// The pairs of touching segments in order of ids (as they touch before any recut).
  const std::vector<std::pair<std::uint32_t, std::uint32_t>>& pairs() const {
    return frontier_.pairs();
  }

  /// Recut the boundary of a and b with a minimum cut over their band.
  void recut(std::uint32_t a, std::uint32_t b) {
    const std::vector<std::uint32_t> band = search_.bandOf(a, b, seg_area_, frontier_.points());
    if (band.empty())
      return;
    const auto m = static_cast<std::uint32_t>(band.size());
    for (std::uint32_t i = 0; i < m; ++i)
      local_[band[i]] = static_cast<std::int32_t>(i);
    FlowNetwork net = bandNetwork(band, a, b);
    for (std::uint32_t p : band)
      local_[p] = -1;
    const std::vector<char> source_side = net.sourceSide(m, m + 1);
    frontier_.update(applyCut(band, source_side, a, b));
  }

private:
  /// Edge e's capacity in the minimum cut: its length, lowered across a concave crease.
  double capacity(std::uint32_t e) const {
    return static_cast<double>(graph_.lengths[e]) * (use_crease_ ? factor_[crease_[e]] : 1.0);
  }

  /// The network of the band (local_ holds each point's index): its m points, the source m
  /// (a outside the band) and the sink m + 1 (b outside the band); points of other segments
  /// take no part.
  FlowNetwork bandNetwork(const std::vector<std::uint32_t>& band, std::uint32_t a,
                          std::uint32_t b) const {
    const auto m = static_cast<std::uint32_t>(band.size());
    FlowNetwork net;
    net.reset(m);
    for (std::uint32_t i = 0; i < m; ++i) {
      const std::uint32_t p = band[i];
      for (std::uint32_t e = graph_.offsets[p]; e < graph_.offsets[p + 1]; ++e) {
        const std::uint32_t q = graph_.targets[e];
        if (local_[q] >= 0)
          ++net.first[i + 1];
        else if (segment_[q] == a)
          net.to_source[i] += capacity(e);
        else if (segment_[q] == b)
          net.to_sink[i] += capacity(e);
      }
    }
    net.allocateArcs();
    for (std::uint32_t i = 0; i < m; ++i) {
      const std::uint32_t p = band[i];
      for (std::uint32_t e = graph_.offsets[p]; e < graph_.offsets[p + 1]; ++e) {
        const std::uint32_t q = graph_.targets[e];
        if (local_[q] >= 0 && q > p)
          net.addPair(i, static_cast<std::uint32_t>(local_[q]), capacity(e), capacity(e));
      }
      net.addTerminalArcs(i);
    }
    return net;
  }

  /// The band's points take the side of the cut they are on (source: a, sink: b), unless
  /// nothing moves or a segment would empty. Returns the points that changed segment.
  std::vector<std::uint32_t> applyCut(const std::vector<std::uint32_t>& band,
                                      const std::vector<char>& source_side, std::uint32_t a,
                                      std::uint32_t b) {
    const auto m = static_cast<std::uint32_t>(band.size());
    std::size_t moved = 0;
    std::int64_t to_a = 0; // points a gains
    std::vector<std::uint32_t> label(m);
    for (std::uint32_t i = 0; i < m; ++i) {
      label[i] = source_side[i] ? a : b;
      if (label[i] != segment_[band[i]]) {
        ++moved;
        to_a += label[i] == a ? 1 : -1;
      }
    }
    // (The points outside the band keep each segment non-empty; this guards zero areas.)
    if (moved == 0 || static_cast<std::int64_t>(seg_count_[a]) + to_a <= 0 ||
        static_cast<std::int64_t>(seg_count_[b]) - to_a <= 0)
      return {};
    seg_count_[a] = static_cast<std::size_t>(static_cast<std::int64_t>(seg_count_[a]) + to_a);
    seg_count_[b] = static_cast<std::size_t>(static_cast<std::int64_t>(seg_count_[b]) - to_a);
    std::vector<std::uint32_t> changed_points;
    for (std::uint32_t i = 0; i < m; ++i)
      if (label[i] != segment_[band[i]]) {
        seg_area_[segment_[band[i]]] -= squaredRadius(radii_, band[i]);
        seg_area_[label[i]] += squaredRadius(radii_, band[i]);
        segment_[band[i]] = label[i];
        changed_points.push_back(band[i]);
      }
    return changed_points;
  }

  const CsrGraph& graph_;
  const std::vector<float>& radii_;
  const std::vector<std::uint8_t>& crease_;
  std::vector<std::uint32_t>& segment_;
  const bool use_crease_;
  std::array<double, 256> factor_; ///< per crease byte, exp(-kBoundaryCreaseWeight c)
  std::vector<double> seg_area_;
  std::vector<std::size_t> seg_count_;
  Frontier frontier_;
  BandSearch search_;
  std::vector<std::int32_t> local_; ///< -1, or during a recut the point's index in the band
};

/// Per component (of segmentComponents()), whether it is stray: in a segment with more
/// components than `before`, all but the segment's before[x] largest by area (ties: smallest
/// id).
std::vector<char>
strayComponents(const std::vector<float>& radii, const std::vector<std::uint32_t>& segment,
                const std::vector<std::uint32_t>& component, std::uint32_t num_components,
                const std::vector<std::size_t>& count, const std::vector<std::size_t>& before) {
  std::vector<double> comp_area(num_components, 0.0);
  std::vector<std::uint32_t> comp_segment(num_components);
  for (std::uint32_t p = 0; p < segment.size(); ++p) {
    comp_area[component[p]] += squaredRadius(radii, p);
    comp_segment[component[p]] = segment[p];
  }
  std::vector<std::vector<std::uint32_t>> of_segment(before.size());
  for (std::uint32_t c = 0; c < num_components; ++c)
    if (count[comp_segment[c]] > before[comp_segment[c]])
      of_segment[comp_segment[c]].push_back(c);
  std::vector<char> stray(num_components, 0);
  for (std::size_t x = 0; x < before.size(); ++x) {
    auto& list = of_segment[x];
    std::stable_sort(list.begin(), list.end(),
                     [&](std::uint32_t a, std::uint32_t b) { return comp_area[a] > comp_area[b]; });
    for (std::size_t i = before[x]; i < list.size(); ++i)
      stray[list[i]] = 1;
  }
  return stray;
}

/// Each stray component joins the other segment it shares the most kNN edges with (ties:
/// smallest id); one that touches none stays.
void moveStrays(const CsrGraph& graph, const std::vector<std::uint32_t>& component,
                const std::vector<char>& stray, std::vector<std::uint32_t>& segment) {
  const std::size_t n = graph.numVertices();
  std::map<std::pair<std::uint32_t, std::uint32_t>, std::size_t> contact;
  for (std::uint32_t p = 0; p < n; ++p)
    if (stray[component[p]])
      for (std::uint32_t e = graph.offsets[p]; e < graph.offsets[p + 1]; ++e) {
        const std::uint32_t q = graph.targets[e];
        if (segment[q] != segment[p])
          ++contact[{component[p], segment[q]}];
      }
  std::vector<std::uint32_t> target(stray.size(), std::numeric_limits<std::uint32_t>::max());
  std::vector<std::size_t> best(stray.size(), 0);
  for (const auto& [key, c] : contact)
    if (c > best[key.first]) {
      best[key.first] = c;
      target[key.first] = key.second;
    }
  for (std::uint32_t p = 0; p < n; ++p)
    if (stray[component[p]] && target[component[p]] != std::numeric_limits<std::uint32_t>::max())
      segment[p] = target[component[p]];
}

/// A recut may cut a piece off a segment (when its points outside the band were connected
/// only through the band): such a piece joins the neighbouring segment it shares the most
/// kNN edges with, so that no segment has more components than in `original` and none
/// empties (each keeps its largest components).
void reattachPieces(const CsrGraph& graph, const std::vector<float>& radii,
                    const std::vector<std::uint32_t>& original, std::vector<std::uint32_t>& segment,
                    std::size_t num_segments) {
  std::vector<std::uint32_t> component;
  std::vector<std::size_t> components_before; // of the original segments, when needed
  for (int round = 0; round < 8; ++round) {
    const std::uint32_t num_components = segmentComponents(graph, segment, component);
    const std::vector<std::size_t> count =
        componentsPerSegment(segment, component, num_components, num_segments);
    if (num_components == num_segments)
      break; // each segment is connected
    if (components_before.empty()) {
      std::vector<std::uint32_t> original_component;
      components_before = componentsPerSegment(
          original, original_component, segmentComponents(graph, original, original_component),
          num_segments);
    }
    bool extra = false;
    for (std::size_t x = 0; x < num_segments; ++x)
      extra = extra || count[x] > components_before[x];
    if (!extra)
      break;
    moveStrays(graph, component,
               strayComponents(radii, segment, component, num_components, count, components_before),
               segment);
  }
}

} // namespace

std::size_t refineBoundaries(const CsrGraph& graph, const std::vector<float>& radii,
                             const std::vector<std::uint8_t>& crease, const BoundaryParams& params,
                             std::vector<std::uint32_t>& segment, std::size_t num_segments) {
  const std::size_t n = graph.numVertices();
  if (!params.band || !(*params.band > 0.0) || num_segments < 2 || n == 0 || segment.size() != n ||
      radii.size() != n)
    return 0;
  const std::vector<std::uint32_t> original = segment;
  {
    // Each pair of touching segments in order of ids (the pairs as they touch before).
    BoundaryRecut recuts(graph, radii, crease, params, segment, num_segments);
    for (const auto& [a, b] : recuts.pairs())
      recuts.recut(a, b);
  }
  reattachPieces(graph, radii, original, segment, num_segments);
  std::size_t changed = 0;
  for (std::size_t p = 0; p < n; ++p)
    changed += segment[p] != original[p];
  return changed;
}

} // namespace pcl_ncut_seg
