// Small segments of an open view joined to their neighbours (core/small_segments.h).
#include <pcl_ncut_seg/core/small_segments.h>

#include <pcl_ncut_seg/core/supernodes.h>

namespace pcl_ncut_seg {

std::vector<std::uint32_t> joinSmallSegments(const CsrGraph& graph,
                                             const std::vector<double>& point_area, double min_area,
                                             std::vector<std::uint32_t>& segment,
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
  std::vector<std::uint32_t> into(m); // per segment, the one it joined (itself: none)
  for (std::uint32_t s = 0; s < m; ++s)
    into[s] = s;
  std::vector<bool> alive(m, true), island(m, false);
  bool joined = false;
  for (;;) {
    std::uint32_t small = kNone;
    for (std::uint32_t s = 0; s < m; ++s)
      if (alive[s] && !island[s] && area[s] < min_area && (small == kNone || area[s] < area[small]))
        small = s;
    if (small == kNone)
      break;
    std::uint32_t best = kNone;
    for (std::uint32_t t = 0; t < m; ++t)
      if (alive[t] && t != small && shared[small * m + t] > 0 &&
          (best == kNone || shared[small * m + t] > shared[small * m + best]))
        best = t;
    if (best == kNone) {
      island[small] = true; // touches no other segment: nothing to join
      continue;
    }
    // small joins best: its area and its edges to every other segment become best's.
    alive[small] = false;
    into[small] = best;
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
  std::vector<std::uint32_t> map(m, kNone), id(m, kNone);
  std::uint32_t next = 0;
  for (std::uint32_t s = 0; s < m; ++s)
    if (alive[s])
      id[s] = next++;
  for (std::uint32_t s = 0; s < m; ++s) {
    std::uint32_t r = s;
    while (into[r] != r)
      r = into[r];
    map[s] = id[r];
  }
  for (auto& s : segment)
    s = map[s];
  num_segments = next;
  return map;
}

} // namespace pcl_ncut_seg
