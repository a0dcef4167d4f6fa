#include <pcl_ncut_seg/core/rim_merge.h>

#include <pcl_ncut_seg/core/concavity.h>
#include <pcl_ncut_seg/core/short_cut.h>
#include <pcl_ncut_seg/core/supernodes.h>

#include <algorithm>
#include <cmath>
#include <map>
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
                                       int times) {
  const std::size_t n = graph.numVertices();
  std::vector<float> in = normals, out(3 * n, 0.0f);
  for (int t = 0; t < times; ++t) {
    for (std::size_t p = 0; p < n; ++p) {
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
                                         const std::vector<float>& normals) {
  std::vector<std::int8_t> bend(graph.numDirectedEdges(), 0);
  const double typical = meanAbsBend(graph, xyz, normals, 1);
  if (!(typical > 0.0))
    return bend;
  for (std::size_t p = 0; p < graph.numVertices(); ++p)
    for (std::uint32_t e = graph.offsets[p]; e < graph.offsets[p + 1]; ++e) {
      const double c = -edgeBend(xyz, normals, p, graph.targets[e], graph.lengths[e]) / typical;
      bend[e] = static_cast<std::int8_t>(std::clamp(std::round(16.0 * c), -127.0, 127.0));
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
  std::vector<std::uint32_t> map(t);
  std::iota(map.begin(), map.end(), 0u);
  std::size_t count = t;
  bool merged = false;
  for (;;) {
    std::vector<std::uint8_t> on_rim(count, 0);
    std::map<std::pair<std::uint32_t, std::uint32_t>, Boundary> pairs;
    for (std::uint32_t p = 0; p < n; ++p) {
      on_rim[segment[p]] |= rim[p];
      for (std::uint32_t e = graph.offsets[p]; e < graph.offsets[p + 1]; ++e) {
        const std::uint32_t a = segment[p], b = segment[graph.targets[e]];
        if (a == b)
          continue;
        Boundary& bd = pairs[{std::min(a, b), std::max(a, b)}];
        bd.edges += 1;
        bd.concave += crease[e] / 16.0;
      }
    }
    const NeckMeasure necks(graph, segment, count);
    std::pair<std::uint32_t, std::uint32_t> best{kNone, kNone};
    double best_c = max_concavity;
    for (const auto& [ab, bd] : pairs) {
      const double c = bd.concave / bd.edges;
      if (!(on_rim[ab.first] || on_rim[ab.second]) || c >= best_c)
        continue;
      std::vector<std::int8_t> side(count, -1);
      side[ab.first] = 0;
      side[ab.second] = 1;
      if (necks.neck(side) < kLimbNeck)
        continue;
      best_c = c;
      best = ab;
    }
    if (best.first == kNone)
      break;
    merged = true;
    const std::uint32_t gone = best.second;
    const auto shift = [gone, &best](std::uint32_t s) {
      return s == gone ? best.first : s > gone ? s - 1 : s;
    };
    for (auto& s : segment)
      s = shift(s);
    for (auto& s : map)
      s = shift(s);
    --count;
  }
  if (!merged)
    return {};
  num_segments = count;
  return map;
}

} // namespace pcl_ncut_seg
