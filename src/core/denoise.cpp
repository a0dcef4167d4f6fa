// Sensor noise detected and projected away (see core/denoise.h).
#include <pcl_ncut_seg/core/denoise.h>
#include <pcl_ncut_seg/core/threads.h>

#include <Eigen/Dense>

#include <cmath>
#include <cstdint>

namespace pcl_ncut_seg {

namespace {

/// Plane of the given vertices: centroid, unit normal and RMS distance to the plane; false
/// when they have none. Moments in double relative to the first vertex.
bool fitPlane(const float* xyz, const std::vector<std::uint32_t>& members,
              Eigen::Vector3d& centroid, Eigen::Vector3d& normal, double& rms) {
  if (members.size() < 3)
    return false;
  const Eigen::Vector3d origin(xyz[3 * members[0]], xyz[3 * members[0] + 1],
                               xyz[3 * members[0] + 2]);
  Eigen::Vector3d sum = Eigen::Vector3d::Zero();
  Eigen::Matrix3d moments = Eigen::Matrix3d::Zero();
  for (std::uint32_t v : members) {
    const Eigen::Vector3d d = Eigen::Vector3d(xyz[3 * v], xyz[3 * v + 1], xyz[3 * v + 2]) - origin;
    sum += d;
    moments += d * d.transpose();
  }
  const double m = static_cast<double>(members.size());
  const Eigen::Vector3d mean = sum / m;
  const Eigen::Matrix3d cov = moments - m * mean * mean.transpose();
  Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> solver;
  solver.computeDirect(cov);
  const Eigen::Vector3d& lambda = solver.eigenvalues(); // ascending
  if (!(lambda[2] > 0.0) || !(lambda[1] > 1e-10 * lambda[2]))
    return false; // coincident or collinear
  normal = solver.eigenvectors().col(0).normalized();
  centroid = origin + mean;
  // Scatter below float rounding (squared: 1e-12 of the spread) is none: an exactly flat grid.
  rms = lambda[0] > 1e-12 * lambda[2] ? std::sqrt(lambda[0] / m) : 0.0;
  return true;
}

} // namespace

LocalPlanes fitLocalPlanes(const CsrGraph& graph, const float* xyz, unsigned num_threads) {
  const std::size_t n = graph.numVertices();
  LocalPlanes out;
  out.projected.assign(xyz, xyz + 3 * n);
  std::vector<double> rms1(n, 0.0), rms2(n, 0.0);
  const auto sn = static_cast<std::int64_t>(n);
#pragma omp parallel num_threads(usableThreads(num_threads))
  {
    std::vector<std::uint32_t> stamp(n, 0), ring1, ring2;
    std::uint32_t tick = 0;
#pragma omp for schedule(static, 1024)
    for (std::int64_t sp = 0; sp < sn; ++sp) {
      const auto p = static_cast<std::uint32_t>(sp);
      ++tick;
      ring1.assign(1, p);
      stamp[p] = tick;
      for (std::uint32_t e = graph.offsets[p]; e < graph.offsets[p + 1]; ++e)
        if (stamp[graph.targets[e]] != tick) {
          stamp[graph.targets[e]] = tick;
          ring1.push_back(graph.targets[e]);
        }
      ring2 = ring1;
      for (std::size_t i = 1; i < ring1.size(); ++i)
        for (std::uint32_t e = graph.offsets[ring1[i]]; e < graph.offsets[ring1[i] + 1]; ++e)
          if (stamp[graph.targets[e]] != tick) {
            stamp[graph.targets[e]] = tick;
            ring2.push_back(graph.targets[e]);
          }
      Eigen::Vector3d c1, n1, c2, n2;
      double r1 = 0.0, r2 = 0.0;
      if (!fitPlane(xyz, ring2, c2, n2, r2))
        continue;
      const Eigen::Vector3d x(xyz[3 * p], xyz[3 * p + 1], xyz[3 * p + 2]);
      const Eigen::Vector3d y = x - (x - c2).dot(n2) * n2;
      for (int d = 0; d < 3; ++d)
        out.projected[3 * p + d] = static_cast<float>(y[d]);
      if (fitPlane(xyz, ring1, c1, n1, r1)) { // both fits, or the point does not count
        rms1[p] = r1;
        rms2[p] = r2;
      }
    }
  }
  // Summed in vertex order: the same for any number of threads.
  double sum1 = 0.0, sum2 = 0.0;
  for (std::size_t p = 0; p < n; ++p) {
    sum1 += rms1[p];
    sum2 += rms2[p];
  }
  out.residual_growth = sum1 > 0.0 ? sum2 / sum1 : 0.0;
  return out;
}

} // namespace pcl_ncut_seg
