#include "shapes/shapes.h"

#include <pcl/common/point_tests.h>
#include <pcl/search/kdtree.h>

#include <Eigen/Geometry>

#include <algorithm>
#include <cmath>
#include <limits>
#include <random>
#include <stdexcept>

namespace pcl_ncut_seg {
namespace test {

namespace {

constexpr double kPi = 3.14159265358979323846;

/** \brief Uniform in [0, 1) from the top 53 bits; identical on every standard library. */
double uniform01(std::mt19937_64& rng) {
  return double(rng() >> 11) * 0x1.0p-53;
}

/** \brief A uniformly distributed unit vector. */
Eigen::Vector3d unitVector(std::mt19937_64& rng) {
  const double z = 2.0 * uniform01(rng) - 1.0;
  const double phi = 2.0 * kPi * uniform01(rng);
  const double s = std::sqrt(std::max(0.0, 1.0 - z * z));
  return {s * std::cos(phi), s * std::sin(phi), z};
}

/** \brief Two unit vectors completing unit vector a to an orthonormal basis. */
void basis(const Eigen::Vector3d& a, Eigen::Vector3d& u, Eigen::Vector3d& v) {
  const Eigen::Vector3d helper =
      std::abs(a.x()) < 0.9 ? Eigen::Vector3d::UnitX() : Eigen::Vector3d::UnitY();
  u = a.cross(helper).normalized();
  v = a.cross(u);
}

/** \brief A solid whose surface is sampled; "inside" is strict so that a primitive's own
 * surface points are never inside it. */
struct Primitive {
  enum class Type { Ellipsoid, Capsule };
  Type type = Type::Ellipsoid;
  int label = 0;
  Eigen::Vector3d center = Eigen::Vector3d::Zero();                           ///< ellipsoid
  Eigen::Vector3d radii = Eigen::Vector3d::Ones();                            ///< ellipsoid
  Eigen::Matrix3d rotation = Eigen::Matrix3d::Identity();                     ///< local to world
  Eigen::Vector3d p0 = Eigen::Vector3d::Zero(), p1 = Eigen::Vector3d::Zero(); ///< capsule
  double radius = 0;                                                          ///< capsule

  /** \brief Area of the proposal distribution of sample(): the true area for capsules, an
   * upper bound for ellipsoids (which reject some proposals). */
  double proposalArea() const {
    switch (type) {
    case Type::Ellipsoid: {
      const Eigen::Vector3d& r = radii;
      return 4.0 * kPi * std::max({r.y() * r.z(), r.x() * r.z(), r.x() * r.y()});
    }
    case Type::Capsule:
      return 2.0 * kPi * radius * (p1 - p0).norm() + 4.0 * kPi * radius * radius;
    }
    return 0;
  }

  /** \brief A point uniform by area on the surface, or false if the proposal was rejected. */
  bool sample(std::mt19937_64& rng, Eigen::Vector3d& p) const {
    switch (type) {
    case Type::Ellipsoid: {
      // Map a uniform unit vector through diag(radii); accept with the map's area scaling,
      // |det M| |M^-T n| = sqrt((r_y r_z n_x)^2 + ...), relative to its maximum.
      const Eigen::Vector3d n = unitVector(rng);
      const Eigen::Vector3d& r = radii;
      const double scale =
          std::sqrt(std::pow(r.y() * r.z() * n.x(), 2) + std::pow(r.x() * r.z() * n.y(), 2) +
                    std::pow(r.x() * r.y() * n.z(), 2));
      const double max_scale = std::max({r.y() * r.z(), r.x() * r.z(), r.x() * r.y()});
      if (uniform01(rng) * max_scale >= scale)
        return false;
      p = center + rotation * r.cwiseProduct(n);
      return true;
    }
    case Type::Capsule: {
      const Eigen::Vector3d axis = p1 - p0;
      const double length = axis.norm();
      const double side = 2.0 * kPi * radius * length;
      const double caps = 4.0 * kPi * radius * radius;
      Eigen::Vector3d a = length > 0 ? Eigen::Vector3d(axis / length) : Eigen::Vector3d::UnitZ();
      if (uniform01(rng) * (side + caps) < side) {
        Eigen::Vector3d u, v;
        basis(a, u, v);
        const double t = uniform01(rng) * length;
        const double phi = 2.0 * kPi * uniform01(rng);
        p = p0 + t * a + radius * (std::cos(phi) * u + std::sin(phi) * v);
      } else {
        // A uniform sphere point: its half facing away from p1 caps p0, the other half p1.
        const Eigen::Vector3d n = unitVector(rng);
        p = (n.dot(a) <= 0 ? p0 : p1) + radius * n;
      }
      return true;
    }
    }
    return false;
  }

  bool inside(const Eigen::Vector3d& p) const {
    constexpr double kShrink = 1.0 - 1e-9;
    switch (type) {
    case Type::Ellipsoid: {
      const Eigen::Vector3d local = rotation.transpose() * (p - center);
      return local.cwiseQuotient(radii).squaredNorm() < kShrink;
    }
    case Type::Capsule: {
      const Eigen::Vector3d axis = p1 - p0;
      const double len2 = axis.squaredNorm();
      const double t = len2 > 0 ? std::clamp((p - p0).dot(axis) / len2, 0.0, 1.0) : 0.0;
      return (p - (p0 + t * axis)).norm() < radius * kShrink;
    }
    }
    return false;
  }

  /** \brief Smallest and largest x over the solid (for the density ramp). */
  void xRange(double& lo, double& hi) const {
    double extent = 0;
    switch (type) {
    case Type::Ellipsoid:
      // max of e_x . (R diag(r) s) over unit s is the norm of R's row x scaled by r.
      extent = rotation.row(0).transpose().cwiseProduct(radii).norm();
      lo = center.x() - extent;
      hi = center.x() + extent;
      return;
    case Type::Capsule:
      lo = std::min(p0.x(), p1.x()) - radius;
      hi = std::max(p0.x(), p1.x()) + radius;
      return;
    }
  }
};

Primitive ellipsoid(const Eigen::Vector3d& center, const Eigen::Vector3d& radii, int label) {
  Primitive p;
  p.type = Primitive::Type::Ellipsoid;
  p.center = center;
  p.radii = radii;
  p.label = label;
  return p;
}

Primitive sphere(const Eigen::Vector3d& center, double radius, int label) {
  return ellipsoid(center, Eigen::Vector3d::Constant(radius), label);
}

Primitive capsule(const Eigen::Vector3d& p0, const Eigen::Vector3d& p1, double radius, int label) {
  Primitive p;
  p.type = Primitive::Type::Capsule;
  p.p0 = p0;
  p.p1 = p1;
  p.radius = radius;
  p.label = label;
  return p;
}

/** \brief n samples uniform by area over the outer surface of the union of the primitives
 * (times the density ramp of the options). */
LabeledShape sampleUnion(const std::vector<Primitive>& primitives, int num_parts, std::size_t n,
                         std::uint64_t seed, const SamplingOptions& options) {
  if (!(options.density_ratio > 0) || !std::isfinite(options.density_ratio))
    throw std::invalid_argument("density_ratio must be positive");
  std::vector<double> cumulative;
  double total = 0, x_lo = std::numeric_limits<double>::infinity(), x_hi = -x_lo;
  for (const Primitive& p : primitives) {
    total += p.proposalArea();
    cumulative.push_back(total);
    double lo = 0, hi = 0;
    p.xRange(lo, hi);
    x_lo = std::min(x_lo, lo);
    x_hi = std::max(x_hi, hi);
  }
  const double ramp = options.density_ratio - 1.0;
  const double max_weight = std::max(1.0, options.density_ratio);

  LabeledShape shape;
  shape.cloud.reset(new pcl::PointCloud<pcl::PointXYZ>);
  shape.cloud->reserve(n);
  shape.labels.reserve(n);
  shape.num_parts = num_parts;
  std::mt19937_64 rng(seed);
  // Every shape here keeps well over 1% of its proposals; the bound only stops a bad shape.
  const std::size_t max_attempts = 1000 * n + 1000;
  for (std::size_t attempt = 0; shape.labels.size() < n; ++attempt) {
    if (attempt == max_attempts)
      throw std::runtime_error("shape sampling rejects almost every point");
    const double u = uniform01(rng) * total;
    const std::size_t i = std::min<std::size_t>(
        std::upper_bound(cumulative.begin(), cumulative.end(), u) - cumulative.begin(),
        primitives.size() - 1);
    Eigen::Vector3d p;
    if (!primitives[i].sample(rng, p))
      continue;
    if (ramp != 0.0) {
      const double t = (p.x() - x_lo) / (x_hi - x_lo);
      if (uniform01(rng) * max_weight >= 1.0 + ramp * t)
        continue;
    }
    bool covered = false;
    for (std::size_t j = 0; j < primitives.size() && !covered; ++j)
      covered = j != i && primitives[j].inside(p);
    if (covered)
      continue;
    shape.cloud->push_back(pcl::PointXYZ(static_cast<float>(p.x()), static_cast<float>(p.y()),
                                         static_cast<float>(p.z())));
    shape.labels.push_back(primitives[i].label);
  }
  return shape;
}

} // namespace

LabeledShape makeHand(std::size_t n, std::uint64_t seed, const SamplingOptions& options) {
  // y up along the fingers, the palm flat in the xy plane. The outer fingers leave the curved
  // top of the palm lower than the inner ones, as on a real hand.
  std::vector<Primitive> parts;
  parts.push_back(ellipsoid({0, 0, 0}, {0.62, 0.65, 0.2}, 0));
  const double finger_radius = 0.08;
  const double finger_x[4] = {-0.405, -0.135, 0.135, 0.405}; // index, middle, ring, little
  const double tip_y[4] = {1.19, 1.38, 1.30, 1.04};
  for (int f = 0; f < 4; ++f)
    parts.push_back(capsule({finger_x[f], 0.1, 0}, {finger_x[f], tip_y[f] - finger_radius, 0},
                            finger_radius, f + 1));
  // The thumb leaves the palm's side below the index finger, pointing out and up.
  const Eigen::Vector3d thumb_base(-0.3, -0.2, 0);
  const Eigen::Vector3d thumb_dir = Eigen::Vector3d(-1.0, 0.55, 0).normalized();
  parts.push_back(capsule(thumb_base, thumb_base + 0.85 * thumb_dir, 0.09, 5));
  return sampleUnion(parts, 6, n, seed, options);
}

LabeledShape makeQuadruped(std::size_t n, std::uint64_t seed, const SamplingOptions& options) {
  // x forward, z up.
  std::vector<Primitive> parts;
  parts.push_back(ellipsoid({0, 0, 0}, {1.0, 0.4, 0.4}, 0));
  int label = 1;
  for (double x : {0.6, -0.6})
    for (double y : {0.2, -0.2})
      parts.push_back(capsule({x, y, 0}, {x, y, -1.2}, 0.1, label++));
  parts.push_back(capsule({0.7, 0, 0.1}, {1.2, 0, 0.6}, 0.12, 5)); // neck
  parts.push_back(sphere({1.3, 0, 0.72}, 0.22, 5));                // head
  parts.push_back(capsule({-0.8, 0, 0.05}, {-1.55, 0, 0.4}, 0.07, 6));
  return sampleUnion(parts, 7, n, seed, options);
}

LabeledShape makeDumbbell(std::size_t n, std::uint64_t seed, const SamplingOptions& options) {
  std::vector<Primitive> parts;
  parts.push_back(sphere({-1.2, 0, 0}, 0.5, 0));
  parts.push_back(capsule({-1.2, 0, 0}, {1.2, 0, 0}, 0.12, 1));
  parts.push_back(sphere({1.2, 0, 0}, 0.5, 2));
  return sampleUnion(parts, 3, n, seed, options);
}

LabeledShape makeTwoObjects(std::size_t n, std::uint64_t seed, const SamplingOptions& options) {
  std::vector<Primitive> parts;
  parts.push_back(sphere({0, 0, 0}, 0.5, 0));
  parts.push_back(capsule({2.5, 0, 0}, {4.0, 0.3, 0}, 0.3, 1));
  return sampleUnion(parts, 2, n, seed, options);
}

LabeledShape makeGappedBar(std::size_t n, std::uint64_t seed, double gap) {
  std::vector<Primitive> parts;
  parts.push_back(capsule({-1.5, 0, 0}, {1.5, 0, 0}, 0.25, 0));
  const LabeledShape bar = sampleUnion(parts, 1, n, seed, {});
  LabeledShape out;
  out.cloud.reset(new pcl::PointCloud<pcl::PointXYZ>);
  out.num_parts = 2;
  for (const auto& p : *bar.cloud) {
    if (std::abs(p.x) < 0.5 * gap)
      continue;
    out.cloud->push_back(p);
    out.labels.push_back(p.x < 0 ? 0 : 1);
  }
  return out;
}

std::vector<double> fibonacciSphere(std::size_t n) {
  const double golden = kPi * (3.0 - std::sqrt(5.0));
  std::vector<double> xyz;
  xyz.reserve(3 * n);
  for (std::size_t i = 0; i < n; ++i) {
    const double z = 1.0 - 2.0 * (i + 0.5) / n, r = std::sqrt(1.0 - z * z), a = golden * i;
    xyz.insert(xyz.end(), {r * std::cos(a), r * std::sin(a), z});
  }
  return xyz;
}

LabeledShape evenCapsule(double length, double radius, double spacing) {
  LabeledShape out;
  out.cloud.reset(new pcl::PointCloud<pcl::PointXYZ>);
  out.num_parts = 1;
  auto add = [&](double x, double y, double z) {
    out.cloud->push_back(
        pcl::PointXYZ(static_cast<float>(x), static_cast<float>(y), static_cast<float>(z)));
    out.labels.push_back(0);
  };
  const int around = std::max(3, static_cast<int>(std::lround(2 * kPi * radius / spacing)));
  const int along = std::max(1, static_cast<int>(std::lround(length / spacing)));
  for (int i = 0; i <= along; ++i)
    for (int j = 0; j < around; ++j) {
      const double angle = 2 * kPi * (j + 0.5 * (i % 2)) / around;
      add(length * i / along, radius * std::cos(angle), radius * std::sin(angle));
    }
  // A hexagonal packing covers spacing^2 sqrt(3) / 2 per point.
  const int cap = static_cast<int>(
      std::lround(2 * kPi * radius * radius / (spacing * spacing * std::sqrt(3.0) / 2)));
  const double golden = kPi * (3 - std::sqrt(5.0));
  for (int end = 0; end < 2; ++end)
    for (int k = 0; k < cap; ++k) {
      const double h = 1 - (k + 0.5) / cap; // uniform in height: uniform by area
      if (h * radius < 0.5 * spacing)
        continue; // the cylinder's last ring is there
      const double s = std::sqrt(1 - h * h), angle = golden * k;
      add(end ? length + radius * h : -radius * h, radius * s * std::cos(angle),
          radius * s * std::sin(angle));
    }
  return out;
}

LabeledShape makeShape(const std::string& name, std::size_t n, std::uint64_t seed,
                       const SamplingOptions& options) {
  if (name == "hand")
    return makeHand(n, seed, options);
  if (name == "quadruped")
    return makeQuadruped(n, seed, options);
  if (name == "dumbbell")
    return makeDumbbell(n, seed, options);
  if (name == "two_objects")
    return makeTwoObjects(n, seed, options);
  throw std::invalid_argument("unknown shape: " + name);
}

pcl::PointCloud<pcl::PointXYZ>::Ptr applyRigidMotion(const pcl::PointCloud<pcl::PointXYZ>& cloud,
                                                     std::uint64_t seed) {
  std::mt19937_64 rng(seed);
  // Shoemake's uniform random unit quaternion.
  const double u1 = uniform01(rng), u2 = uniform01(rng), u3 = uniform01(rng);
  const double a = std::sqrt(1.0 - u1), b = std::sqrt(u1);
  const Eigen::Quaterniond q(b * std::cos(2 * kPi * u3), a * std::sin(2 * kPi * u2),
                             a * std::cos(2 * kPi * u2), b * std::sin(2 * kPi * u3));
  const Eigen::Matrix3d rotation = q.normalized().toRotationMatrix();
  Eigen::Vector3d translation;
  for (int d = 0; d < 3; ++d)
    translation[d] = 20.0 * uniform01(rng) - 10.0;

  pcl::PointCloud<pcl::PointXYZ>::Ptr out(new pcl::PointCloud<pcl::PointXYZ>(cloud));
  for (auto& point : *out) {
    const Eigen::Vector3d p = rotation * point.getVector3fMap().cast<double>() + translation;
    point.getVector3fMap() = p.cast<float>(); // NaN in, NaN out
  }
  return out;
}

pcl::PointCloud<pcl::PointXYZ>::Ptr discView(std::uint64_t seed, float bump) {
  auto cloud = std::make_shared<pcl::PointCloud<pcl::PointXYZ>>(160, 120);
  std::mt19937_64 rng(seed);
  std::normal_distribution<float> noise(0.0f, 0.0005f);
  const float f = 150.0f, nan = std::numeric_limits<float>::quiet_NaN();
  for (int row = 0; row < 120; ++row)
    for (int col = 0; col < 160; ++col) {
      const float u = (col - 80 + 0.5f) / f, v = (row - 60 + 0.5f) / f;
      // The plane z = 1 + 0.3 y, along the ray (u, v, 1).
      float z = 1.0f / (1.0f - 0.3f * v);
      pcl::PointXYZ& p = (*cloud)(col, row);
      if (std::hypot(u * z, v * z) > 0.25f) {
        p.x = p.y = p.z = nan;
        continue;
      }
      const float r = std::hypot(u * z - 0.1f, v * z);
      if (bump > 0.0f && r < 0.03f)
        z -= bump * std::cos(0.5f * 3.14159265f * r / 0.03f);
      const float zn = z + noise(rng);
      p.x = u * zn;
      p.y = v * zn;
      p.z = zn;
    }
  cloud->is_dense = false;
  return cloud;
}

double meanPointSpacing(const pcl::PointCloud<pcl::PointXYZ>& cloud) {
  pcl::PointCloud<pcl::PointXYZ>::Ptr finite(new pcl::PointCloud<pcl::PointXYZ>);
  for (const auto& p : cloud)
    if (pcl::isFinite(p))
      finite->push_back(p);
  if (finite->size() < 2)
    return 0;
  pcl::search::KdTree<pcl::PointXYZ> tree;
  tree.setInputCloud(finite);
  double sum = 0;
  std::vector<int> index(2);
  std::vector<float> sq_dist(2);
  for (const auto& p : *finite) {
    tree.nearestKSearch(p, 2, index, sq_dist);
    sum += std::sqrt(sq_dist[1]); // [0] is the point itself
  }
  return sum / finite->size();
}

pcl::PointCloud<pcl::PointXYZ>::Ptr randomCube(std::size_t n, std::uint64_t seed) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<float> u(-1.0f, 1.0f);
  pcl::PointCloud<pcl::PointXYZ>::Ptr c(new pcl::PointCloud<pcl::PointXYZ>);
  for (std::size_t i = 0; i < n; ++i)
    c->push_back(pcl::PointXYZ(u(rng), u(rng), u(rng)));
  return c;
}

} // namespace test
} // namespace pcl_ncut_seg
