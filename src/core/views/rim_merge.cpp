#include "core/views/rim_merge.h"

#include "core/common/geometry.h"
#include "core/cut/short_cut.h"
#include "core/graph/shortest_paths.h"
#include "core/supernodes/supernodes.h"

#include <Eigen/Dense>

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>
#include <optional>
#include <utility>

namespace pcl_ncut_seg {

namespace {
constexpr double kPi = 3.14159265358979323846;

/// Moments of one side of a boundary: enough to fit its plane, and to add up when segments
/// merge.
struct Band {
  double count = 0;
  Eigen::Vector3d sum = Eigen::Vector3d::Zero(), normal = Eigen::Vector3d::Zero();
  Eigen::Matrix3d outer = Eigen::Matrix3d::Zero();
  void add(const Band& o) {
    count += o.count;
    sum += o.sum;
    normal += o.normal;
    outer += o.outer;
  }
  /// The least-squares plane: its centre and unit normal, oriented as the points' normals;
  /// nothing for fewer than 3 points or collinear ones, whose normal would be any.
  std::optional<Plane> plane() const {
    Scatter scatter;
    scatter.count = count;
    if (count >= 3) {
      scatter.centroid = sum / count;
      scatter.matrix = outer / count - scatter.centroid * scatter.centroid.transpose();
    }
    std::optional<Plane> out = fitPlane(scatter, kNotCollinearDouble, EigenSolve::kClosedForm);
    if (out && out->normal.dot(normal) < 0)
      out->normal = -out->normal;
    return out;
  }
};

/// Per ordered pair (a, b) of segments (index a * t + b), a's band towards b: the points of a
/// within band_width of b along kNN edges inside a (a search from a's points next to b).
std::vector<Band> sideBands(const CsrGraph& graph, const std::vector<float>& xyz,
                            const std::vector<float>& normals,
                            const std::vector<std::uint32_t>& segment, std::size_t t,
                            double band_width) {
  const std::size_t n = graph.numVertices();
  std::vector<Band> band(t * t);
  std::vector<std::uint32_t> border, touched, sources;
  std::vector<double> dist(n, std::numeric_limits<double>::infinity());
  for (std::uint32_t p = 0; p < n; ++p) // the points with a neighbour in another segment
    for (std::uint32_t e = graph.offsets[p]; e < graph.offsets[p + 1]; ++e)
      if (segment[graph.targets[e]] != segment[p]) {
        border.push_back(p);
        break;
      }
  // Within a segment, and no farther than the band's width.
  auto reach = [&](std::uint32_t p, std::uint32_t q, double dq) {
    return segment[q] == segment[p] && dq <= band_width;
  };
  for (std::uint32_t b = 0; b < t; ++b) {
    sources.clear();
    for (std::uint32_t p : border)
      if (segment[p] != b)
        for (std::uint32_t e = graph.offsets[p]; e < graph.offsets[p + 1]; ++e)
          if (segment[graph.targets[e]] == b) {
            dist[p] = 0.0;
            sources.push_back(p);
            break;
          }
    touched = sources;
    // Each point adds to its side's band once, in the order settled (the sums' order).
    auto add = [&](std::uint32_t p, double) {
      Band& bd = band[segment[p] * t + b];
      const Eigen::Vector3d x(xyz[3 * p], xyz[3 * p + 1], xyz[3 * p + 2]);
      bd.count += 1;
      bd.sum += x;
      bd.outer += x * x.transpose();
      bd.normal += Eigen::Vector3d(normals[3 * p], normals[3 * p + 1], normals[3 * p + 2]);
      return Settle::kExpand;
    };
    multiSourceDijkstra(graph, sources, dist.data(), reach, add, nullptr, &touched);
    for (std::uint32_t p : touched)
      dist[p] = std::numeric_limits<double>::infinity();
    touched.clear();
  }
  return band;
}

/// How concave (radians) the two merged groups a and b meet; negative when they cannot be
/// measured (a side with fewer than 3 points).
double concaveAngle(const std::vector<Band>& band, const std::vector<std::uint32_t>& group,
                    std::uint32_t a, std::uint32_t b) {
  const std::size_t t = group.size();
  Band ab, ba;
  for (std::size_t i = 0; i < t; ++i)
    for (std::size_t j = 0; j < t; ++j)
      if (group[i] == a && group[j] == b) {
        ab.add(band[i * t + j]);
        ba.add(band[j * t + i]);
      }
  const std::optional<Plane> pa = ab.plane(), pb = ba.plane();
  if (!pa || !pb)
    return -1.0;
  // Concave where the normals lean towards each other (as contactConcavity() reads bends).
  if ((pa->normal - pb->normal).dot(pa->centroid - pb->centroid) >= 0.0)
    return 0.0;
  return std::acos(std::clamp(pa->normal.dot(pb->normal), -1.0, 1.0));
}
} // namespace

std::vector<std::uint32_t>
mergeAcrossRim(const CsrGraph& graph, const std::vector<std::uint8_t>& rim,
               const std::vector<float>& xyz, const std::vector<float>& normals, double max_degrees,
               double band_width, std::vector<std::uint32_t>& segment, std::size_t& num_segments) {
  const std::size_t n = graph.numVertices(), t = num_segments;
  if (rim.size() != n || xyz.size() != 3 * n || normals.size() != 3 * n || t < 2)
    return {};
  std::vector<std::uint8_t> on_rim(t, 0);
  for (std::uint32_t p = 0; p < n; ++p)
    on_rim[segment[p]] |= rim[p];
  // Measured once over the input segments; a merged segment's sides are sums of these.
  const std::vector<Band> band = sideBands(graph, xyz, normals, segment, t, band_width);
  // No vote (core/cut/short_cut.h): these boundaries are the boundary refinement's cuts, not a
  // fringe of interleaved supernodes.
  const NeckMeasure necks(graph, segment, t, false);
  std::vector<std::uint32_t> group(t); // per input segment, its merged one (its smallest id)
  std::iota(group.begin(), group.end(), 0u);
  const double bound = max_degrees * kPi / 180.0;
  bool merged = false;
  for (;;) {
    std::uint32_t best_a = kNone, best_b = kNone;
    double best = bound;
    for (std::uint32_t a = 0; a < t; ++a)
      for (std::uint32_t b = a + 1; b < t; ++b) {
        if (group[a] != a || group[b] != b || !(on_rim[a] || on_rim[b]))
          continue;
        const double angle = concaveAngle(band, group, a, b);
        if (angle < 0.0 || !(angle < best))
          continue;
        std::vector<std::int8_t> side(t, -1);
        for (std::size_t s = 0; s < t; ++s)
          side[s] = group[s] == a ? 0 : group[s] == b ? 1 : -1;
        if (necks.neck(side) < kLimbNeck)
          continue;
        best = angle;
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
  return joinGroups(group, segment, num_segments);
}

} // namespace pcl_ncut_seg
