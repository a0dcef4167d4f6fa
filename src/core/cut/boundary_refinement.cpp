// Point-level boundary refinement after the hierarchy (an extension of Sec. 5.2; Katz and Tal
// 2003's fuzzy cuts over the kNN graph).
#include "core/cut/boundary_refinement.h"
#include "core/common/threads.h"
#include "core/cut/concavity.h"
#include "core/cut/flow_network.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <functional>
#include <limits>
#include <map>
#include <queue>
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

/// The recuts of refineBoundaries() in steps: the segments' areas and sizes, the frontier
/// (points with a neighbour in another segment) and the band search's arrays.
struct BoundaryRecut {
  const CsrGraph& graph;
  const std::vector<float>& radii;
  const std::vector<std::uint8_t>& crease;
  const BoundaryParams& params;
  std::vector<std::uint32_t>& segment;
  const bool use_crease;
  std::array<double, 256> factor; ///< per crease byte, exp(-kBoundaryCreaseWeight c)
  std::vector<double> seg_area;
  std::vector<std::size_t> seg_count;
  std::vector<std::uint32_t> frontier; ///< in order of ids, then as points joined it
  std::vector<char> in_frontier;
  std::vector<std::pair<std::uint32_t, std::uint32_t>> pairs; ///< touching segments, ascending
  static constexpr float kFar = std::numeric_limits<float>::infinity();
  std::vector<float> dist;         ///< band search: distance from the boundary, kFar between
  std::vector<std::int32_t> local; ///< -1; in a band search -2: settled; >= 0: index in the band
  using Item = std::pair<float, std::uint32_t>; ///< (distance, vertex): ties by vertex id

  BoundaryRecut(const CsrGraph& graph, const std::vector<float>& radii,
                const std::vector<std::uint8_t>& crease, const BoundaryParams& params,
                std::vector<std::uint32_t>& segment, std::size_t num_segments)
      : graph(graph), radii(radii), crease(crease), params(params), segment(segment),
        use_crease(!crease.empty() && crease.size() == graph.numDirectedEdges()),
        seg_area(num_segments, 0.0), seg_count(num_segments, 0) {
    for (std::size_t c = 0; c < factor.size(); ++c)
      factor[c] =
          use_crease ? std::exp(-kBoundaryCreaseWeight * static_cast<double>(c) / 16.0) : 1.0;
    const std::size_t n = graph.numVertices();
    for (std::uint32_t p = 0; p < n; ++p) {
      seg_area[segment[p]] += squaredRadius(radii, p);
      ++seg_count[segment[p]];
    }
    findFrontier();
    dist.assign(n, kFar);
    local.assign(n, -1);
  }

  /// Edge e's capacity in the minimum cut: its length, lowered across a concave crease.
  double capacity(std::uint32_t e) const {
    return static_cast<double>(graph.lengths[e]) * (use_crease ? factor[crease[e]] : 1.0);
  }

  /// p has a neighbour in another segment.
  bool onFrontier(std::uint32_t p) const {
    for (std::uint32_t e = graph.offsets[p]; e < graph.offsets[p + 1]; ++e)
      if (segment[graph.targets[e]] != segment[p])
        return true;
    return false;
  }

  /// The frontier, and the pairs of touching segments in order of ids.
  void findFrontier() {
    const std::size_t n = graph.numVertices();
    in_frontier.assign(n, 0);
    for (std::uint32_t p = 0; p < n; ++p)
      for (std::uint32_t e = graph.offsets[p]; e < graph.offsets[p + 1]; ++e) {
        const std::uint32_t q = graph.targets[e];
        if (segment[q] == segment[p])
          continue;
        if (!in_frontier[p]) {
          in_frontier[p] = 1;
          frontier.push_back(p);
        }
        if (segment[p] < segment[q])
          pairs.emplace_back(segment[p], segment[q]);
      }
    std::sort(pairs.begin(), pairs.end());
    pairs.erase(std::unique(pairs.begin(), pairs.end()), pairs.end());
  }

  /// Seeds of the geodesic distance from the boundary between x and y on x's side: x's points
  /// on it start at half their shortest edge across it (added to touched).
  void seedSide(std::uint32_t x, std::uint32_t y, std::vector<std::uint32_t>& touched) {
    for (std::uint32_t p : frontier) {
      if (segment[p] != x)
        continue;
      for (std::uint32_t e = graph.offsets[p]; e < graph.offsets[p + 1]; ++e)
        if (segment[graph.targets[e]] == y && 0.5f * graph.lengths[e] < dist[p]) {
          if (dist[p] == kFar)
            touched.push_back(p);
          dist[p] = 0.5f * graph.lengths[e];
        }
    }
  }

  /// x's side of the band with y: x's points in order of distance from the boundary, settled
  /// while they hold at most the band fraction of x's area and are closer than bound, which the
  /// first point left out lowers (neither side's band may reach past it).
  void growSide(std::uint32_t x, std::uint32_t y, float& bound, std::vector<std::uint32_t>& settled,
                std::vector<std::uint32_t>& touched) {
    const std::size_t first_seed = touched.size();
    seedSide(x, y, touched);
    std::priority_queue<Item, std::vector<Item>, std::greater<Item>> queue;
    for (std::size_t i = first_seed; i < touched.size(); ++i)
      queue.emplace(dist[touched[i]], touched[i]);
    const double cap = *params.band * seg_area[x];
    double held = 0.0;
    while (!queue.empty()) {
      const auto [d, p] = queue.top();
      queue.pop();
      if (d > dist[p] || local[p] == -2)
        continue;
      if (d >= bound || held + squaredRadius(radii, p) > cap) {
        bound = std::min(bound, d); // neither side's band may reach this far
        break;
      }
      local[p] = -2;
      held += squaredRadius(radii, p);
      settled.push_back(p);
      for (std::uint32_t e = graph.offsets[p]; e < graph.offsets[p + 1]; ++e) {
        const std::uint32_t q = graph.targets[e];
        const float dq = d + graph.lengths[e];
        if (segment[q] == x && local[q] != -2 && dq < dist[q]) {
          if (dist[q] == kFar)
            touched.push_back(q);
          dist[q] = dq;
          queue.emplace(dq, q);
        }
      }
    }
  }

  /// The band (fuzzy region) of a and b: the settled points of both sides closer than the
  /// final bound, by id; empty when a side has no area to bound it by.
  std::vector<std::uint32_t> bandOf(std::uint32_t a, std::uint32_t b) {
    if (!(seg_area[a] > 0.0) || !(seg_area[b] > 0.0))
      return {};
    // The side with less area first: its distance bound also bounds the other side's search.
    std::uint32_t sides[2] = {a, b};
    if (seg_area[b] < seg_area[a])
      std::swap(sides[0], sides[1]);
    std::vector<std::uint32_t> settled[2], touched;
    float bound = kFar;
    for (int s = 0; s < 2; ++s)
      growSide(sides[s], sides[1 - s], bound, settled[s], touched);
    std::vector<std::uint32_t> band;
    for (int s = 0; s < 2; ++s)
      for (std::uint32_t p : settled[s]) {
        if (dist[p] < bound)
          band.push_back(p);
        local[p] = -1;
      }
    for (std::uint32_t p : touched)
      dist[p] = kFar;
    std::sort(band.begin(), band.end());
    return band;
  }

  /// The network of the band (local holds each point's index): its m points, the source m
  /// (a outside the band) and the sink m + 1 (b outside the band); points of other segments
  /// take no part.
  FlowNetwork bandNetwork(const std::vector<std::uint32_t>& band, std::uint32_t a,
                          std::uint32_t b) const {
    const auto m = static_cast<std::uint32_t>(band.size());
    FlowNetwork net;
    net.reset(m);
    for (std::uint32_t i = 0; i < m; ++i) {
      const std::uint32_t p = band[i];
      for (std::uint32_t e = graph.offsets[p]; e < graph.offsets[p + 1]; ++e) {
        const std::uint32_t q = graph.targets[e];
        if (local[q] >= 0)
          ++net.first[i + 1];
        else if (segment[q] == a)
          net.to_source[i] += capacity(e);
        else if (segment[q] == b)
          net.to_sink[i] += capacity(e);
      }
    }
    net.allocateArcs();
    for (std::uint32_t i = 0; i < m; ++i) {
      const std::uint32_t p = band[i];
      for (std::uint32_t e = graph.offsets[p]; e < graph.offsets[p + 1]; ++e) {
        const std::uint32_t q = graph.targets[e];
        if (local[q] >= 0 && q > p)
          net.addPair(i, static_cast<std::uint32_t>(local[q]), capacity(e), capacity(e));
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
      if (label[i] != segment[band[i]]) {
        ++moved;
        to_a += label[i] == a ? 1 : -1;
      }
    }
    // (The points outside the band keep each segment non-empty; this guards zero areas.)
    if (moved == 0 || static_cast<std::int64_t>(seg_count[a]) + to_a <= 0 ||
        static_cast<std::int64_t>(seg_count[b]) - to_a <= 0)
      return {};
    seg_count[a] = static_cast<std::size_t>(static_cast<std::int64_t>(seg_count[a]) + to_a);
    seg_count[b] = static_cast<std::size_t>(static_cast<std::int64_t>(seg_count[b]) - to_a);
    std::vector<std::uint32_t> changed_points;
    for (std::uint32_t i = 0; i < m; ++i)
      if (label[i] != segment[band[i]]) {
        seg_area[segment[band[i]]] -= squaredRadius(radii, band[i]);
        seg_area[label[i]] += squaredRadius(radii, band[i]);
        segment[band[i]] = label[i];
        changed_points.push_back(band[i]);
      }
    return changed_points;
  }

  /// The frontier after a recut: only the changed points and their neighbours can leave or
  /// join it (the list keeps its order, then the new ones).
  void updateFrontier(const std::vector<std::uint32_t>& changed_points) {
    bool left = false;
    for (std::uint32_t p : changed_points)
      for (std::uint32_t e = graph.offsets[p]; e <= graph.offsets[p + 1]; ++e) {
        const std::uint32_t q = e < graph.offsets[p + 1] ? graph.targets[e] : p;
        if (in_frontier[q] == 1 && !onFrontier(q)) {
          in_frontier[q] = 0;
          left = true;
        }
      }
    if (left) {
      std::size_t kept = 0;
      for (std::uint32_t p : frontier)
        if (in_frontier[p])
          frontier[kept++] = p;
      frontier.resize(kept);
    }
    for (std::uint32_t p : changed_points)
      for (std::uint32_t e = graph.offsets[p]; e <= graph.offsets[p + 1]; ++e) {
        const std::uint32_t q = e < graph.offsets[p + 1] ? graph.targets[e] : p;
        if (!in_frontier[q] && onFrontier(q)) {
          in_frontier[q] = 1;
          frontier.push_back(q);
        }
      }
  }

  /// Recut the boundary of a and b with a minimum cut over their band.
  void recut(std::uint32_t a, std::uint32_t b) {
    const std::vector<std::uint32_t> band = bandOf(a, b);
    if (band.empty())
      return;
    const auto m = static_cast<std::uint32_t>(band.size());
    for (std::uint32_t i = 0; i < m; ++i)
      local[band[i]] = static_cast<std::int32_t>(i);
    FlowNetwork net = bandNetwork(band, a, b);
    for (std::uint32_t p : band)
      local[p] = -1;
    const std::vector<char> source_side = net.sourceSide(m, m + 1);
    updateFrontier(applyCut(band, source_side, a, b));
  }
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
    for (const auto& [a, b] : recuts.pairs)
      recuts.recut(a, b);
  }
  reattachPieces(graph, radii, original, segment, num_segments);
  std::size_t changed = 0;
  for (std::size_t p = 0; p < n; ++p)
    changed += segment[p] != original[p];
  return changed;
}

} // namespace pcl_ncut_seg
