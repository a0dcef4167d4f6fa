#include <pcl_ncut_seg/core/rim_merge.h>

#include <pcl_ncut_seg/core/concavity.h>
#include <pcl_ncut_seg/core/short_cut.h>
#include <pcl_ncut_seg/core/supernodes.h>
#include <pcl_ncut_seg/core/threads.h>

#include <algorithm>
#include <cmath>
#include <numeric>

namespace pcl_ncut_seg {

std::vector<std::uint8_t> organizedRim(const std::vector<std::uint32_t>& vertex_pixel,
                                       const std::vector<float>& range,
                                       const std::vector<std::uint32_t>& pixel_vertex,
                                       std::size_t width, std::size_t height) {
  std::vector<std::uint8_t> rim(vertex_pixel.size(), 0);
  for (std::size_t v = 0; v < vertex_pixel.size(); ++v) {
    const std::size_t px = vertex_pixel[v], row = px / width, col = px % width;
    const float r = range[px];
    const auto open = [&](std::size_t q) {
      return pixel_vertex[q] == kNone || std::abs(range[q] - r) > 0.02f * r;
    };
    rim[v] = row == 0 || col == 0 || row + 1 == height || col + 1 == width || open(px - 1) ||
             open(px + 1) || open(px - width) || open(px + width);
  }
  return rim;
}

std::vector<float> ringAveragedNormals(const CsrGraph& graph, const std::vector<float>& normals,
                                       int times, unsigned num_threads) {
  const auto n = static_cast<std::ptrdiff_t>(graph.numVertices());
  std::vector<float> in = normals, out(3 * std::size_t(n), 0.0f);
  for (int t = 0; t < times; ++t) {
    // Each vertex on its own: the same for any thread count.
#pragma omp parallel for schedule(static, 4096) num_threads(usableThreads(num_threads))
    for (std::ptrdiff_t ip = 0; ip < n; ++ip) {
      const auto p = static_cast<std::size_t>(ip);
      double sum[3] = {in[3 * p], in[3 * p + 1], in[3 * p + 2]};
      for (std::uint32_t e = graph.offsets[p]; e < graph.offsets[p + 1]; ++e)
        for (int d = 0; d < 3; ++d)
          sum[d] += in[3 * std::size_t(graph.targets[e]) + d];
      const double len = std::sqrt(sum[0] * sum[0] + sum[1] * sum[1] + sum[2] * sum[2]);
      for (int d = 0; d < 3; ++d)
        out[3 * p + d] = len > 0.0 ? static_cast<float>(sum[d] / len) : 0.0f;
    }
    in.swap(out);
  }
  return in;
}

std::vector<std::int8_t> signedEdgeBends(const CsrGraph& graph, const float* xyz,
                                         const std::vector<float>& normals, unsigned num_threads) {
  std::vector<std::int8_t> bend(graph.numDirectedEdges(), 0);
  const double typical = meanAbsBend(graph, xyz, normals, num_threads);
  if (!(typical > 0.0))
    return bend;
#pragma omp parallel for schedule(static, 4096) num_threads(usableThreads(num_threads))
  for (std::ptrdiff_t ip = 0; ip < static_cast<std::ptrdiff_t>(graph.numVertices()); ++ip) {
    const auto p = static_cast<std::size_t>(ip);
    for (std::uint32_t e = graph.offsets[p]; e < graph.offsets[p + 1]; ++e) {
      const double c = -edgeBend(xyz, normals, p, graph.targets[e], graph.lengths[e]) / typical;
      bend[e] = static_cast<std::int8_t>(std::clamp(std::round(16.0 * c), -127.0, 127.0));
    }
  }
  return bend;
}

namespace {
// The neck (core/short_cut.h) of a limb as long as it is wide, cut at its base: a tube of
// radius a and length 2a has 2 pi a / sqrt(2 pi a 2a) = sqrt(pi). A piece chipped off at the
// rim has a wider one (a half disc: sqrt(2 pi)); a limb a narrower one.
const double kLimbNeck = std::sqrt(3.14159265358979323846);

struct Boundary {
  double edges = 0, concave = 0;
};
} // namespace

std::vector<std::uint32_t> mergeAcrossRim(const CsrGraph& graph,
                                          const std::vector<std::uint8_t>& rim,
                                          const std::vector<std::int8_t>& crease,
                                          double max_concavity, std::vector<std::uint32_t>& segment,
                                          std::size_t& num_segments) {
  const std::size_t n = graph.numVertices(), t = num_segments;
  if (rim.size() != n || crease.size() != graph.numDirectedEdges() || t < 2)
    return {};
  // One pass over the graph: per pair of input segments their boundary, per segment whether it
  // reaches the rim; a merged segment's boundaries are sums of these.
  std::vector<std::uint8_t> on_rim(t, 0);
  std::vector<Boundary> between(t * t);
  for (std::uint32_t p = 0; p < n; ++p) {
    on_rim[segment[p]] |= rim[p];
    for (std::uint32_t e = graph.offsets[p]; e < graph.offsets[p + 1]; ++e) {
      const std::uint32_t a = segment[p], b = segment[graph.targets[e]];
      if (a != b) {
        between[a * t + b].edges += 1;
        between[a * t + b].concave += crease[e] / 16.0;
      }
    }
  }
  const NeckMeasure necks(graph, segment, t);
  std::vector<std::uint32_t> group(t); // per input segment, its merged segment (a root id)
  std::iota(group.begin(), group.end(), 0u);
  bool merged = false;
  for (;;) {
    std::vector<Boundary> pair(t * t);
    for (std::size_t a = 0; a < t; ++a)
      for (std::size_t b = 0; b < t; ++b)
        if (group[a] < group[b]) {
          Boundary& sum = pair[group[a] * t + group[b]];
          for (const Boundary& bd : {between[a * t + b], between[b * t + a]}) {
            sum.edges += bd.edges;
            sum.concave += bd.concave;
          }
        }
    std::uint32_t best_a = kNone, best_b = kNone;
    double best_c = max_concavity;
    for (std::uint32_t a = 0; a < t; ++a)
      for (std::uint32_t b = a + 1; b < t; ++b) {
        const Boundary& bd = pair[a * t + b];
        if (bd.edges == 0 || !(on_rim[a] || on_rim[b]) || !(bd.concave / bd.edges < best_c))
          continue;
        std::vector<std::int8_t> side(t, -1);
        for (std::size_t s = 0; s < t; ++s)
          side[s] = group[s] == a ? 0 : group[s] == b ? 1 : -1;
        if (necks.neck(side) < kLimbNeck)
          continue;
        best_c = bd.concave / bd.edges;
        best_a = a;
        best_b = b;
      }
    if (best_a == kNone)
      break;
    merged = true;
    for (auto& g : group)
      if (g == best_b)
        g = best_a;
    on_rim[best_a] |= on_rim[best_b];
  }
  if (!merged)
    return {};
  // Compact ids in order of the smallest input segment of each merged one.
  std::vector<std::uint32_t> id(t, kNone), map(t);
  std::uint32_t count = 0;
  for (std::size_t s = 0; s < t; ++s) {
    if (id[group[s]] == kNone)
      id[group[s]] = count++;
    map[s] = id[group[s]];
  }
  for (auto& s : segment)
    s = map[s];
  num_segments = count;
  return map;
}

} // namespace pcl_ncut_seg
