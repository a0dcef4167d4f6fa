// The sensor position of a view read off its points (see core/views/view_origin.h).
#include "core/views/view_origin.h"
#include "core/common/geometry.h"
#include "core/common/threads.h"
#include "core/views/single_view.h"

#include <Eigen/Core>
#include <Eigen/Geometry>

#include <algorithm>
#include <cmath>
#include <optional>

namespace pcl_ncut_seg {

namespace {

constexpr double kPi = 3.14159265358979323846;
// pcl::BoundaryEstimation's default angle threshold.
constexpr double kBoundaryGap = kPi / 2.0;
// Far enough that the sensor sees the whole object within rule 1a's cone
// (core/views/single_view.h), near enough to stay a perspective view like a camera's at one to
// three diagonals.
constexpr double kOriginDiagonals = 3.0;
// See estimateViewOrigin().
constexpr double kMinBoundaryOnRim = 0.5;
constexpr double kMinRimOnBoundary = 0.25;
// See couldBeSensor().
constexpr double kMinSensorDiagonals = 0.5;

Eigen::Vector3d point(const float* xyz, std::uint32_t v) {
  return {xyz[3 * v], xyz[3 * v + 1], xyz[3 * v + 2]};
}

/// The points' centroid and bounding-box diagonal (n > 0).
struct Extent {
  Eigen::Vector3d centroid;
  double diagonal;
};
Extent extentOf(const float* xyz, std::size_t n) {
  Eigen::Vector3d centroid = Eigen::Vector3d::Zero(), lo = point(xyz, 0), hi = lo;
  for (std::uint32_t v = 0; v < n; ++v) {
    const Eigen::Vector3d p = point(xyz, v);
    centroid += p;
    lo = lo.cwiseMin(p);
    hi = hi.cwiseMax(p);
  }
  return {centroid / static_cast<double>(n), (hi - lo).norm()};
}

/// The sector of the bearing (a, b) != 0 as a bit: 16 sectors of 22.5 degrees, in some fixed
/// order around the circle (neighbouring sectors on neighbouring bits, cyclically).
unsigned sectorBit(double a, double b) {
  const double x = std::abs(a), y = std::abs(b);
  // Within the quadrant, 0-3 counter-clockwise from the axis of a (by tan 22.5 degrees).
  const double lo = std::min(x, y), hi = std::max(x, y);
  const int half = lo < 0.41421356237309503 * hi ? 0 : 1;
  const int in_quadrant = x >= y ? half : 3 - half;
  const int quadrant = b >= 0.0 ? (a >= 0.0 ? 0 : 1) : (a < 0.0 ? 2 : 3);
  // Quadrants 1 and 3 run from the axis of b: mirror their order.
  const int sector = quadrant % 2 == 0 ? in_quadrant : 3 - in_quadrant;
  return 1u << (4 * quadrant + sector);
}

/// Whether three neighbouring sectors are empty: a gap above 90 degrees spans at least that.
bool threeEmpty(unsigned used) {
  const unsigned empty = ~used & 0xffffu, twice = empty | empty << 16;
  return (twice & twice >> 1 & twice >> 2 & 0xffffu) != 0;
}

/// The widest angular gap between the bearings of the points (around p, across normal); 0
/// when it surely is at most 90 degrees (no three neighbouring sectors of 16 are empty).
double widestGap(const Eigen::Vector3d& p, const Eigen::Vector3d& normal,
                 const std::vector<Eigen::Vector3d>& points, std::vector<double>& angles) {
  const Eigen::Vector3d u = normal.unitOrthogonal(), w = normal.cross(u);
  unsigned used = 0;
  for (const Eigen::Vector3d& q : points) {
    const Eigen::Vector3d d = q - p;
    const double a = d.dot(u), b = d.dot(w);
    if (a != 0.0 || b != 0.0)
      used |= sectorBit(a, b);
  }
  if (!threeEmpty(used))
    return 0.0;
  angles.clear();
  for (const Eigen::Vector3d& q : points) {
    const Eigen::Vector3d d = q - p;
    const double a = d.dot(u), b = d.dot(w);
    if (a != 0.0 || b != 0.0)
      angles.push_back(std::atan2(b, a));
  }
  if (angles.size() < 2)
    return 2.0 * kPi;
  std::sort(angles.begin(), angles.end());
  double gap = angles.front() + 2.0 * kPi - angles.back();
  for (std::size_t i = 1; i < angles.size(); ++i)
    gap = std::max(gap, angles[i] - angles[i - 1]);
  return gap;
}

/// Whether v's neighbours, projected onto the plane across normal, leave a gap above
/// kBoundaryGap, and so do its 2-ring's (ten neighbours drawn at random leave such a gap about
/// two times in three; fifty almost never, while at an edge they all lie on one side).
bool leavesGap(const CsrGraph& graph, const float* xyz, std::uint32_t v,
               const Eigen::Vector3d& normal, std::vector<Eigen::Vector3d>& ring,
               std::vector<double>& angles) {
  ring.clear();
  for (std::uint32_t e = graph.offsets[v]; e < graph.offsets[v + 1]; ++e)
    ring.push_back(point(xyz, graph.targets[e]));
  const Eigen::Vector3d p = point(xyz, v);
  if (widestGap(p, normal, ring, angles) <= kBoundaryGap)
    return false;
  for (std::uint32_t e = graph.offsets[v]; e < graph.offsets[v + 1]; ++e) {
    const std::uint32_t q = graph.targets[e];
    for (std::uint32_t f = graph.offsets[q]; f < graph.offsets[q + 1]; ++f)
      if (graph.targets[f] != v)
        ring.push_back(point(xyz, graph.targets[f]));
  }
  return widestGap(p, normal, ring, angles) > kBoundaryGap;
}

/// Rule of boundaryPoints() at v (closed ring: a buffer for v and its neighbours).
std::uint8_t isBoundary(const CsrGraph& graph, const float* xyz, std::uint32_t v,
                        std::vector<std::uint32_t>& closed, std::vector<Eigen::Vector3d>& ring,
                        std::vector<double>& angles) {
  if (graph.degree(v) < 3)
    return 0;
  closed.assign(1, v);
  closed.insert(closed.end(), graph.targets.begin() + graph.offsets[v],
                graph.targets.begin() + graph.offsets[v + 1]);
  const std::optional<Plane> plane =
      fitPlane(centredScatter(xyz, closed), kAnyPlane, EigenSolve::kIterative);
  return plane && leavesGap(graph, xyz, v, plane->normal, ring, angles) ? 1 : 0;
}

} // namespace

std::vector<std::uint8_t> boundaryPoints(const CsrGraph& graph, const float* xyz,
                                         unsigned num_threads) {
  const auto sn = static_cast<std::int64_t>(graph.numVertices());
  std::vector<std::uint8_t> boundary(graph.numVertices(), 0);
  const int threads = usableThreads(num_threads);
#pragma omp parallel num_threads(threads)
  {
    std::vector<double> angles;
    std::vector<std::uint32_t> closed;
    std::vector<Eigen::Vector3d> ring;
#pragma omp for schedule(static, 1024)
    for (std::int64_t i = 0; i < sn; ++i)
      boundary[i] = isBoundary(graph, xyz, static_cast<std::uint32_t>(i), closed, ring, angles);
  }
  return boundary;
}

bool couldBeSensor(const float* xyz, std::size_t n, const float origin[3]) {
  if (n == 0)
    return false;
  const Extent extent = extentOf(xyz, n);
  const Eigen::Vector3d o(origin[0], origin[1], origin[2]);
  return (o - extent.centroid).norm() >= kMinSensorDiagonals * extent.diagonal;
}

std::optional<std::array<float, 3>> estimateViewOrigin(const CsrGraph& graph, const float* xyz,
                                                       unsigned num_threads,
                                                       std::vector<std::uint8_t>* rim) {
  const std::size_t n = graph.numVertices();
  if (n < 10)
    return std::nullopt;
  // A rim is a curve: its points have rim neighbours on either side. A point alone among
  // inside points is a gap of an irregular sampling, not a rim.
  const std::vector<std::uint8_t> gap = boundaryPoints(graph, xyz, num_threads);
  std::vector<std::uint8_t> boundary(n, 0);
  for (std::uint32_t v = 0; v < n; ++v) {
    int along = 0;
    for (std::uint32_t e = graph.offsets[v]; gap[v] && e < graph.offsets[v + 1]; ++e)
      along += gap[graph.targets[e]];
    boundary[v] = along >= 2;
  }
  std::vector<std::uint32_t> rim_points;
  for (std::uint32_t v = 0; v < n; ++v)
    if (boundary[v])
      rim_points.push_back(v);
  const std::size_t m = rim_points.size();
  // A view's rim runs around it: about 3.5 sqrt(n) points around a disc of n points, and even
  // where the sampling thins out towards a silhouette, more than sqrt(n).
  if (static_cast<double>(m) < std::sqrt(static_cast<double>(n)) || m < 3)
    return std::nullopt;
  const Extent extent = extentOf(xyz, n);
  const Eigen::Vector3d& centroid = extent.centroid;
  const std::optional<Plane> rim_plane =
      fitPlane(centredScatter(xyz, rim_points), kAnyPlane, EigenSolve::kIterative);
  if (!rim_plane)
    return std::nullopt;
  const Eigen::Vector3d& rim_mean = rim_plane->centroid;
  Eigen::Vector3d axis = rim_plane->normal;
  // A sensor sees an object's near side, which bulges towards it from the silhouette: try
  // the side the points' centroid lies on from the rim's first (by the axis' largest
  // component when the points are flat, so that the order of the points does not matter).
  const double bulge = (centroid - rim_mean).dot(axis);
  int largest = 0;
  axis.cwiseAbs().maxCoeff(&largest);
  if (bulge < 0.0 || (bulge == 0.0 && axis(largest) < 0.0))
    axis = -axis;
  const double reach = kOriginDiagonals * extent.diagonal;
  for (const double side : {1.0, -1.0}) {
    const Eigen::Vector3d o = centroid + side * reach * axis;
    const float origin[3] = {static_cast<float>(o(0)), static_cast<float>(o(1)),
                             static_cast<float>(o(2))};
    std::vector<std::uint8_t> seen = singleViewRim(graph, xyz, origin, num_threads);
    // A view's surface ends where the sensor's sight does: its rim seen from the sensor is its
    // own boundary (where the boundary test finds it: it misses some at grazing silhouettes).
    // A closed surface's rim seen from outside is a silhouette it continues behind, and the
    // boundary points of its thin parts (a table's top, edge-on to its kNN graph) lie elsewhere.
    std::size_t on_rim = 0, rim_size = 0;
    for (std::uint32_t v = 0; v < seen.size(); ++v) {
      on_rim += seen[v] && boundary[v];
      rim_size += seen[v];
    }
    if (seen.empty() || static_cast<double>(on_rim) < kMinBoundaryOnRim * static_cast<double>(m) ||
        static_cast<double>(on_rim) < kMinRimOnBoundary * static_cast<double>(rim_size))
      continue;
    if (rim)
      *rim = std::move(seen);
    return std::array<float, 3>{origin[0], origin[1], origin[2]};
  }
  return std::nullopt;
}

} // namespace pcl_ncut_seg
