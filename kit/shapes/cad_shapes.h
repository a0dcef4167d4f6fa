/*
 * pcl_ncut_seg kit, shared by the tests and bench/: generated CAD parts with known faces (Sec. 7).
 *
 * Each part is a closed polyhedron (or a cylinder) whose faces are labelled 0 .. num_parts-1.
 * Points are drawn uniformly by area, then optionally displaced by isotropic Gaussian noise.
 * Everything is deterministic for a seed on every platform (std::mt19937_64 with our own
 * mappings to [0, 1) and to the normal distribution).
 */
#pragma once

#include "shapes/shapes.h"

#include <pcl/point_cloud.h>
#include <pcl/point_types.h>

#include <cstddef>
#include <cstdint>
#include <ostream>
#include <string>
#include <vector>

namespace pcl_ncut_seg {
namespace test {

/** \brief A unit cube: 6 faces. */
LabeledShape makeCube(std::size_t n, std::uint64_t seed, double noise = 0.0);

/** \brief A prism over an equilateral triangle of side 1, 1.2 long: 5 faces (2 ends, 3 sides at
 * 60 degrees to each other). */
LabeledShape makeTriangularPrism(std::size_t n, std::uint64_t seed, double noise = 0.0);

/** \brief A prism over a regular hexagon of circumradius 0.5, 1 long: 8 faces (2 ends, 6 sides
 * that turn by 60 degrees from one to the next). */
LabeledShape makeHexagonalPrism(std::size_t n, std::uint64_t seed, double noise = 0.0);

/** \brief An L-shaped block: the unit square minus its [0.5, 1]^2 corner, 0.4 thick: 8 faces
 * (2 L-shaped, 6 sides, one of which meets its neighbours at a concave ridge). */
LabeledShape makeLBlock(std::size_t n, std::uint64_t seed, double noise = 0.0);

/** \brief A cylinder of radius 0.5 and height 1 with flat caps: 3 faces (the curved side is
 * one face). */
LabeledShape makeCylinder(std::size_t n, std::uint64_t seed, double noise = 0.0);

/** \brief The parts above by name ("cube", "triangular_prism", "hexagonal_prism", "l_block",
 * "cylinder"); throws std::invalid_argument for another name. noise is the standard deviation
 * of the displacement of each coordinate. */
LabeledShape makeCadShape(const std::string& name, std::size_t n, std::uint64_t seed,
                          double noise = 0.0);

/** \brief The same cloud with the exact normal of each point's face (before noise, so a noisy
 * cloud gets its faces' clean normals), for the path that reads normals from the input. */
pcl::PointCloud<pcl::PointNormal>::Ptr withFaceNormals(const std::string& name, std::size_t n,
                                                       std::uint64_t seed, double noise = 0.0);

/** \brief A case of the tests (test_cad.cpp) and of pcl_ncut_seg_bench_perturbation: a part,
 * its number of points and its noise. */
struct CadCase {
  std::string shape;
  std::size_t n = 0;
  /// Standard deviation per coordinate, in model units (parts are about 1 unit); the mean
  /// nearest-neighbour spacing is 0.010-0.016 at these n, so 0.005 is 0.3-0.5 spacings and
  /// 0.01 0.6-0.9.
  double noise = 0.0;
};

/** \brief Every part clean and with noise 0.005 and 0.01 (15 cases; n 6,000, 8,000 for the
 * hexagonal prism and the L-block below noise 0.01). */
const std::vector<CadCase>& cadCases();

/** \brief "<shape>_clean", "<shape>_noisy" (below 0.01) or "<shape>_heavy_noise". */
std::string caseName(const CadCase& c);

/** \brief gtest prints a case by its name, n and noise. */
void PrintTo(const CadCase& c, std::ostream* os);

} // namespace test
} // namespace pcl_ncut_seg
