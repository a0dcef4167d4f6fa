/*
 * pcl_ncut_seg kit, shared by the tests and bench/: generated point clouds with known parts.
 *
 * Each shape is a union of simple primitives (ellipsoids, spheres, capsules). Points are
 * drawn uniformly by area over the primitives' surfaces and a point inside another primitive is
 * rejected, so the samples lie on the closed outer surface of the union, uniformly by area.
 * Every primitive carries a part label. Everything is deterministic for a seed on every
 * platform (std::mt19937_64 with our own mapping to [0, 1)).
 */
#pragma once

#include <pcl/point_cloud.h>
#include <pcl/point_types.h>

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

namespace pcl_ncut_seg {
namespace test {

/** \brief A point cloud and the part label (0 .. num_parts-1) of each point. */
struct LabeledShape {
  pcl::PointCloud<pcl::PointXYZ>::Ptr cloud;
  std::vector<int> labels;
  int num_parts = 0;
};

/** \brief How points are spread over the surface. */
struct SamplingOptions {
  /** \brief Density ratio between the two ends of the shape along x: 1 is uniform by area; r
   * makes the density grow linearly with x from 1 to r (relative) across the bounding box of
   * the primitives, by rejection. */
  double density_ratio = 1.0;
};

/** \brief A hand, about 2.2 units tall: a flattened-ellipsoid palm (label 0) with four
 * parallel fingers (labels 1-4, index to little) and a thumb pointing sideways (label 5).
 * Fingers have radius 0.08, lengths outside the palm of 0.55-0.8 (length/radius >= 6) and gaps
 * of 0.11 between them, over 3 times the mean point spacing at n = 4000. */
LabeledShape makeHand(std::size_t n, std::uint64_t seed, const SamplingOptions& options = {});

/** \brief A four-legged animal: body (label 0), four legs (1-4), neck and head (5), tail (6).
 * Legs are capsules of radius 0.1 and length about 0.9 below the body. */
LabeledShape makeQuadruped(std::size_t n, std::uint64_t seed, const SamplingOptions& options = {});

/** \brief Two balls of radius 0.5 joined by a bar of radius 0.12 and visible length about 1.4:
 * ball (0), bar (1), ball (2). */
LabeledShape makeDumbbell(std::size_t n, std::uint64_t seed, const SamplingOptions& options = {});

/** \brief Two separate objects 2 units apart: a sphere (label 0) and a capsule (label 1). */
LabeledShape makeTwoObjects(std::size_t n, std::uint64_t seed, const SamplingOptions& options = {});

/** \brief A bar (capsule of radius 0.25 from x = -1.5 to 1.5) with no points in the band
 * |x| < gap / 2, as a surface sampled with a gap: the half with x < 0 is label 0, the other 1.
 * With gap = 0 it is one bar. About n points (those in the band are dropped). */
LabeledShape makeGappedBar(std::size_t n, std::uint64_t seed, double gap);

/** \brief All the shapes above by name ("hand", "quadruped", "dumbbell", "two_objects"); throws
 * std::invalid_argument for another name. */
LabeledShape makeShape(const std::string& name, std::size_t n, std::uint64_t seed,
                       const SamplingOptions& options = {});

/** \brief A capsule spread evenly, not at random: its axis from (0, 0, 0) to (length, 0, 0),
 * radius `radius`; rings of points `spacing` apart along the cylinder (each ring turned by half
 * a step against the last) and a golden-angle spiral on each hemispherical cap, about `spacing`
 * between neighbours everywhere. Deterministic; one part (label 0). */
LabeledShape evenCapsule(double length, double radius, double spacing);

/** \brief n points of the unit sphere spread evenly on a Fibonacci lattice (the golden-angle
 * spiral; neighbours about sqrt(4 pi / n) apart), x, y, z in turn. */
std::vector<double> fibonacciSphere(std::size_t n);

/** \brief n points drawn uniformly in the cube [-1, 1]^3 (std::uniform_real_distribution of
 * std::mt19937_64(seed): the same on one standard library, unlike the shapes above). */
pcl::PointCloud<pcl::PointXYZ>::Ptr randomCube(std::size_t n, std::uint64_t seed);

/** \brief The cloud moved by a random rotation (uniform over rotations) and a random
 * translation with coordinates in [-10, 10], the same for a given seed. Points keep their
 * order; non-finite points stay non-finite. */
pcl::PointCloud<pcl::PointXYZ>::Ptr applyRigidMotion(const pcl::PointCloud<pcl::PointXYZ>& cloud,
                                                     std::uint64_t seed);

/** \brief What a depth camera 1 m in front of a flat disc (radius 0.25 m, tilted: the plane
 * z = 1 + 0.3 y) sees: an organized 160 x 120 cloud, NaN off the disc, with range noise of
 * 0.5 mm (std::mt19937_64(seed)). With bump > 0, a smooth bump of that height towards the
 * camera, 3 cm in radius, 0.1 m right of the disc's centre. */
pcl::PointCloud<pcl::PointXYZ>::Ptr discView(std::uint64_t seed, float bump = 0.0f);

/** \brief Mean distance from each finite point to its nearest other point, to check the
 * shapes' proportions against the point spacing. */
double meanPointSpacing(const pcl::PointCloud<pcl::PointXYZ>& cloud);

} // namespace test
} // namespace pcl_ncut_seg
