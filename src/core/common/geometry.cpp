// The geometry the stages share (see core/common/geometry.h).
#include "core/common/geometry.h"

#include <Eigen/Eigenvalues>

namespace pcl_ncut_seg {

namespace {
Eigen::Vector3d point(const float* xyz, std::uint32_t v) {
  return {xyz[3 * v], xyz[3 * v + 1], xyz[3 * v + 2]};
}
} // namespace

Scatter centredScatter(const float* xyz, const std::vector<std::uint32_t>& points) {
  Scatter out;
  out.count = static_cast<double>(points.size());
  if (points.empty())
    return out;
  for (std::uint32_t v : points)
    out.centroid += point(xyz, v);
  out.centroid /= out.count;
  for (std::uint32_t v : points) {
    const Eigen::Vector3d d = point(xyz, v) - out.centroid;
    out.matrix += d * d.transpose();
  }
  return out;
}

std::optional<Plane> fitPlane(const Scatter& scatter, double min_flatness, EigenSolve solve) {
  if (!(scatter.count >= 3.0))
    return std::nullopt;
  Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> solver;
  if (solve == EigenSolve::kClosedForm)
    solver.computeDirect(scatter.matrix);
  else
    solver.compute(scatter.matrix);
  if (solver.info() != Eigen::Success)
    return std::nullopt;
  Plane plane;
  plane.lambda = solver.eigenvalues(); // ascending
  if (!(plane.lambda[2] > 0.0) || !(plane.lambda[1] > min_flatness * plane.lambda[2]))
    return std::nullopt; // coincident or collinear: the normal could be any
  const Eigen::Vector3d v = solver.eigenvectors().col(0);
  // computeDirect()'s eigenvector is unit only up to rounding.
  plane.normal = solve == EigenSolve::kClosedForm ? v.normalized() : v;
  if (!plane.normal.allFinite() || !(plane.normal.squaredNorm() > 0.0))
    return std::nullopt;
  plane.centroid = scatter.centroid;
  return plane;
}

} // namespace pcl_ncut_seg
