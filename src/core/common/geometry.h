/*
 * pcl_ncut_seg: the geometry the stages share: the distance between two points, and the
 * least-squares plane of a set of points (the normals of the concavity measures and of Sec. 7's
 * faces, the noise test's residuals, a view's boundary points and rim).
 */
#pragma once

#include <Eigen/Core>

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <optional>
#include <vector>

namespace pcl_ncut_seg {

/** \brief Euclidean distance between points a and b: the coordinate differences in float, their
 * squares summed in Real (float for the kNN graph's edge lengths, double for the bridges').
 * \param[in] xyz  3 floats per point */
template <typename Real = float>
inline Real pointDistance(const float* xyz, std::size_t a, std::size_t b) {
  const float* pa = xyz + 3 * a;
  const float* pb = xyz + 3 * b;
  const Real dx = pa[0] - pb[0], dy = pa[1] - pb[1], dz = pa[2] - pb[2];
  return std::sqrt(dx * dx + dy * dy + dz * dz);
}

/** \brief Points' centroid and scatter matrix: what a plane fit needs. */
struct Scatter {
  Eigen::Vector3d centroid = Eigen::Vector3d::Zero();
  /// sum (x - c)(x - c)^T, or a positive multiple of it; fitPlane() reads the lower triangle.
  Eigen::Matrix3d matrix = Eigen::Matrix3d::Zero();
  double count = 0.0; ///< number of points
};

/** \brief The scatter of the given points about their centroid, in two passes in double (the
 * centroid, then the outer products of the differences), in the order given.
 * \param[in] xyz     3 floats per point
 * \param[in] points  indices into xyz */
Scatter centredScatter(const float* xyz, const std::vector<std::uint32_t>& points);

/// Which rounding of m mu_r mu_c (m points, mean mu) the scatter's lower triangle gets: the
/// two differ in the last bit, and each stage keeps the one its output was measured with.
enum class MeanProduct {
  kRowFirst,    ///< (m mu_r) mu_c, r >= c
  kColumnFirst, ///< (m mu_c) mu_r, r >= c
};

/** \brief The moments of points about the first one, summed in Real in one pass: one read per
 * point, and the differences stay exact far from the origin. Real = float halves the work of
 * the per-point fits where float rounding of the sums is enough. */
template <typename Real> class ShiftedMoments {
public:
  /** \param[in] origin  the first point (3 floats); add() it too if it is one of the points */
  explicit ShiftedMoments(const float* origin) : origin_{origin[0], origin[1], origin[2]} {}

  /** \brief Adds a point (3 floats). */
  void add(const float* x) {
    const Real dx = x[0] - origin_[0], dy = x[1] - origin_[1], dz = x[2] - origin_[2];
    s_[0] += dx;
    s_[1] += dy;
    s_[2] += dz;
    ss_[0] += dx * dx;
    ss_[1] += dy * dx;
    ss_[2] += dy * dy;
    ss_[3] += dz * dx;
    ss_[4] += dz * dy;
    ss_[5] += dz * dz;
    ++count_;
  }

  /** \brief The scatter: the moments less m mu mu^T, lower triangle only (count > 0). */
  Scatter scatter(MeanProduct order) const {
    Scatter out;
    const double m = static_cast<double>(count_);
    out.count = m;
    const Eigen::Vector3d mean(s_[0] / m, s_[1] / m, s_[2] / m);
    static constexpr int kRow[6] = {0, 1, 1, 2, 2, 2}, kCol[6] = {0, 0, 1, 0, 1, 2};
    for (int i = 0; i < 6; ++i) {
      const int r = kRow[i], c = kCol[i];
      const double product =
          order == MeanProduct::kRowFirst ? m * mean[r] * mean[c] : m * mean[c] * mean[r];
      out.matrix(r, c) = ss_[i] - product;
    }
    out.centroid = Eigen::Vector3d(origin_[0], origin_[1], origin_[2]) + mean;
    return out;
  }

private:
  Real origin_[3];
  Real s_[3] = {0, 0, 0};
  Real ss_[6] = {0, 0, 0, 0, 0, 0}; ///< lower triangle, row by row
  std::size_t count_ = 0;
};

/// How a plane fit's 3x3 eigenproblem is solved. The two agree up to rounding, not bit for bit,
/// and each stage keeps the one its output was measured with.
enum class EigenSolve {
  kClosedForm, ///< Eigen's computeDirect(), the eigenvector normalised again
  kIterative,  ///< Eigen's iterative (tridiagonal QL) solver, its unit eigenvector as it is
};

/// Thresholds of fitPlane()'s flatness rule (the middle eigenvalue over the largest), by what
/// each stage's points need.
constexpr double kAnyPlane = 0.0; ///< a view's boundary test: any middle eigenvalue above 0
constexpr double kNotCollinearDouble = 1e-10; ///< collinear up to the rounding of double sums
constexpr double kNotCollinearFloat = 1e-5;   ///< collinear up to the rounding of float sums
constexpr double kFaceFlatness = 1e-3; ///< Sec. 7's faces: a row of points gives no orientation

/** \brief The least-squares plane of a scatter.
 *
 * One rule for a degenerate neighbourhood: there is no plane when there are fewer than 3
 * points, when the largest eigenvalue is not above 0 (coincident points), when the middle one
 * is not above min_flatness times the largest (collinear points, whose normal could be any),
 * or when the solve fails or gives a normal that is not finite. The threshold is relative, so
 * the rule does not depend on the model's scale; each stage passes the one it needs (above).
 */
struct Plane {
  Eigen::Vector3d centroid; ///< the scatter's
  Eigen::Vector3d normal;   ///< unit: the eigenvector of the smallest eigenvalue
  Eigen::Vector3d lambda;   ///< the scatter's eigenvalues, ascending
};

/** \brief The plane of a scatter, or nothing when it is degenerate (see Plane).
 * \param[in] scatter      centredScatter(), ShiftedMoments::scatter() or the like
 * \param[in] min_flatness the middle eigenvalue must exceed this times the largest
 * \param[in] solve        the eigensolver */
std::optional<Plane> fitPlane(const Scatter& scatter, double min_flatness, EigenSolve solve);

} // namespace pcl_ncut_seg
