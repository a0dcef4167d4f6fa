// Small segments of an open view joined to their neighbours (core/views/small_segments.h).
#include "core/views/small_segments.h"

#include "core/cut/short_cut.h"
#include "core/supernodes/supernodes.h"

#include <numeric>

namespace pcl_ncut_seg {

std::vector<std::uint32_t> joinSmallSegments(const CsrGraph& graph,
                                             const std::vector<double>& point_area, double min_area,
                                             double min_neck, std::vector<std::uint32_t>& segment,
                                             std::size_t& num_segments) {
  const std::size_t n = segment.size(), m = num_segments;
  if (m < 2 || point_area.size() != n || graph.numVertices() != n)
    return {};
  // Areas and, per pair of segments, the kNN edges between them: one pass over the graph.
  std::vector<double> area(m, 0.0);
  std::vector<std::size_t> shared(m * m, 0);
  for (std::uint32_t p = 0; p < n; ++p) {
    const std::uint32_t s = segment[p];
    area[s] += point_area[p];
    for (std::uint32_t e = graph.offsets[p]; e < graph.offsets[p + 1]; ++e) {
      const std::uint32_t t = segment[graph.targets[e]];
      if (t != s)
        ++shared[s * m + t];
    }
  }
  const NeckMeasure necks(graph, segment, m, false);
  std::vector<std::uint32_t> group(m); // per input segment, the one it has joined (or itself)
  std::iota(group.begin(), group.end(), 0u);
  std::vector<bool> island(m, false);
  bool joined = false;
  for (;;) {
    std::uint32_t small = kNone;
    for (std::uint32_t s = 0; s < m; ++s)
      if (group[s] == s && !island[s] && area[s] < min_area &&
          (small == kNone || area[s] < area[small]))
        small = s;
    if (small == kNone)
      break;
    std::uint32_t best = kNone;
    for (std::uint32_t t = 0; t < m; ++t)
      if (group[t] == t && t != small && shared[small * m + t] > 0 &&
          (best == kNone || shared[small * m + t] > shared[small * m + best]))
        best = t;
    if (best == kNone) {
      island[small] = true; // touches no other segment: nothing to join
      continue;
    }
    if (min_neck > 0.0) {
      std::vector<std::int8_t> side(m, -1);
      for (std::uint32_t s = 0; s < m; ++s)
        side[s] = group[s] == small ? 0 : group[s] == best ? 1 : -1;
      if (necks.neck(side) < min_neck) {
        island[small] = true; // a limb's neck: a part, however small
        continue;
      }
    }
    // small joins best: its area and its edges to every other segment become best's.
    for (auto& g : group)
      if (g == small)
        g = best;
    area[best] += area[small];
    for (std::uint32_t t = 0; t < m; ++t) {
      if (t == best || t == small)
        continue;
      shared[best * m + t] += shared[small * m + t];
      shared[t * m + best] += shared[t * m + small];
    }
    shared[best * m + small] = shared[small * m + best] = 0;
    joined = true;
  }
  if (!joined)
    return {};
  return joinGroups(group, segment, num_segments);
}

} // namespace pcl_ncut_seg
