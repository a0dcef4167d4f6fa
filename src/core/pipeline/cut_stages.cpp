#include "core/pipeline/cut_stages.h"

#include "core/cad/cad.h"
#include "core/cut/boundary_refinement.h"
#include "core/cut/part_merge.h"
#include "core/cut/short_cut.h"
#include "core/supernodes/refinement.h"
#include "core/views/rim_merge.h"
#include "core/views/small_segments.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <memory>

namespace pcl_ncut_seg {

WeightedGraph similarityStage(const Analysis& a, const SimilarityParams& params) {
  if (a.cad)
    return buildCadSupernodeGraph(a.supernodes, a.stats, a.conn, a.face_angles, params);
  return buildSupernodeGraph(a.supernodes, a.stats, a.conn, params, &a.concavity,
                             a.thickness.empty() ? nullptr : &a.thickness);
}

namespace {
/// The sides of a split of the supernodes: 0 for `side0`'s, 1 for `side1`'s, -1 elsewhere.
/// Both hold supernode ids, or with `of_gs` vertex ids of G_s (only members m_i = l + i count,
/// footnote 6).
std::vector<std::int8_t> sidesOf(std::size_t l, const std::vector<std::uint32_t>& side0,
                                 const std::vector<std::uint32_t>& side1, bool of_gs) {
  std::vector<std::int8_t> side(l, -1);
  for (int t = 0; t < 2; ++t)
    for (std::uint32_t v : t == 0 ? side0 : side1)
      if (!of_gs)
        side[v] = static_cast<std::int8_t>(t);
      else if (v >= l)
        side[v - l] = static_cast<std::int8_t>(t);
  return side;
}
} // namespace

Hierarchy hierarchyStage(const Analysis& a, const WeightedGraph& graph,
                         const StoppingParams& params) {
  const std::size_t l = a.supernodes.size();
  if (params.rule == StoppingRule::Threshold)
    return buildHierarchy(graph, l, params);
  // The short-cut rule and the count rule measure boundaries on the kNN graph
  // (core/cut/short_cut.h), on a noisy cloud after a vote that takes the noise out of them.
  const NeckMeasure necks(*a.graph, a.supernodes.label, l, a.noise.projected);
  if (params.rule == StoppingRule::Count) {
    // The N strongest boundaries of the finest level (core/cut/part_merge.h). The bound shifts
    // every worth alike: an order needs none.
    const BoundaryWorthFn worth = [&necks, l](const std::vector<std::uint32_t>& s0,
                                              const std::vector<std::uint32_t>& s1, double ncut) {
      const double neck = necks.neck(sidesOf(l, s0, s1, false));
      return splitWorth(ncut, neck, kNeckExponent, 1.0, kNeckFloor);
    };
    return mergeParts(graph, l, worth, params.segments);
  }
  const SplitNeckFn split_neck = [&necks, l](const std::vector<std::uint32_t>& v1,
                                             const std::vector<std::uint32_t>& v2) {
    return necks.neck(sidesOf(l, v1, v2, true));
  };
  return buildHierarchy(graph, l, params, split_neck);
}

void labelPoints(const Analysis& a, CutResult& r) {
  const std::size_t l = a.supernodes.size();
  std::vector<std::uint32_t> leaf_of(l, kNone);
  const std::vector<int> leaves = r.hierarchy.leaves();
  for (std::size_t k = 0; k < leaves.size(); ++k)
    for (std::uint32_t v : r.hierarchy.nodes[leaves[k]].vertices)
      if (v >= l)
        leaf_of[v - l] = static_cast<std::uint32_t>(k);
  std::vector<std::uint32_t> segment_of_leaf(leaves.size(), kNone);
  const std::vector<std::uint32_t>& label = a.supernodes.label;
  r.num_segments = 0;
  r.point_segment.resize(label.size());
  for (std::size_t p = 0; p < label.size(); ++p) {
    std::uint32_t& seg = segment_of_leaf[leaf_of[label[p]]];
    if (seg == kNone)
      seg = static_cast<std::uint32_t>(r.num_segments++);
    r.point_segment[p] = seg;
  }
  r.supernode_segment.resize(l);
  for (std::size_t s = 0; s < l; ++s)
    r.supernode_segment[s] = segment_of_leaf[leaf_of[s]];
}

void boundaryStage(const Analysis& a, const BoundaryParams& params, CutResult& r) {
  if (a.cad || !params.band)
    return;
  refineBoundaries(*a.graph, a.radii, a.crease, params, r.point_segment, r.num_segments);
}

namespace {
/// The view's feature area: the points' discs pi r(p)^2 (Sec. 4.3) summed.
double viewArea(const std::vector<float>& radii) {
  double total = 0.0;
  for (float r : radii)
    total += pointArea(r);
  return total;
}
// The paper's small (Sec. 4.3): a part of 1% of the object's area.
constexpr double kSmallPart = 0.01;

/// The paper's small part of a view's object, in feature area: the object's area is at least
/// twice the view's (a view shows at most half of a closed surface).
double smallPartArea(const std::vector<float>& radii) {
  return kSmallPart * 2.0 * viewArea(radii);
}

/// Half the width of the smallest part the paper keeps, in feature area (the discs overlap:
/// wider than the part's true half-width).
double halfWidth(double small_part_area) {
  return 0.5 * std::sqrt(small_part_area);
}
} // namespace

double rimBandWidth(const std::vector<float>& radii) {
  return halfWidth(smallPartArea(radii));
}

void rimStage(const Analysis& a, const BoundaryParams& params, CutResult& r) {
  if (a.cad || !params.rim_merge || a.rim.empty() || a.rim_xyz.empty())
    return;
  const double small_part = smallPartArea(a.radii);
  const std::vector<std::uint32_t> map =
      mergeAcrossRim(*a.graph, a.rim, a.rim_xyz, a.rim_normals, *params.rim_merge,
                     halfWidth(small_part), r.point_segment, r.num_segments);
  for (auto& s : r.supernode_segment)
    if (s < map.size())
      s = map[s];
  // A piece the rim or an occlusion left of a part: smaller than the paper's small part of the
  // object (whose area is at least twice the view's) and held by no limb's neck.
  std::vector<double> area(a.radii.size());
  for (std::size_t p = 0; p < area.size(); ++p)
    area[p] = pointArea(a.radii[p]);
  const std::vector<std::uint32_t> joined =
      joinSmallSegments(*a.graph, area, small_part, kLimbNeck, r.point_segment, r.num_segments);
  for (auto& s : r.supernode_segment)
    if (s < joined.size())
      s = joined[s];
}

void numberSegments(const std::vector<std::uint32_t>& order, CutResult& r) {
  std::vector<std::uint32_t> first(r.num_segments, std::numeric_limits<std::uint32_t>::max());
  for (std::size_t v = 0; v < r.point_segment.size(); ++v) {
    std::uint32_t& m = first[r.point_segment[v]];
    m = std::min(m, order.empty() ? static_cast<std::uint32_t>(v) : order[v]);
  }
  std::vector<std::uint32_t> by_first(r.num_segments), rank(r.num_segments);
  for (std::uint32_t s = 0; s < by_first.size(); ++s)
    by_first[s] = s;
  std::sort(by_first.begin(), by_first.end(),
            [&](std::uint32_t a, std::uint32_t b) { return first[a] < first[b]; });
  for (std::uint32_t i = 0; i < by_first.size(); ++i)
    rank[by_first[i]] = i;
  for (auto& s : r.point_segment)
    s = rank[s];
  for (auto& s : r.supernode_segment)
    if (s < rank.size())
      s = rank[s];
}

} // namespace pcl_ncut_seg
