#include "shapes/cad_shapes.h"

#include <Eigen/Core>

#include <algorithm>
#include <array>
#include <cmath>
#include <random>
#include <stdexcept>

namespace pcl_ncut_seg {
namespace test {
namespace {

constexpr double kPi = 3.14159265358979323846;

double uniform01(std::mt19937_64& rng) {
  return static_cast<double>(rng() >> 11) * (1.0 / 9007199254740992.0); // 53 bits
}

double gaussian(std::mt19937_64& rng) {
  // Box-Muller with our own uniforms: the same numbers on every platform.
  const double u1 = 1.0 - uniform01(rng), u2 = uniform01(rng);
  return std::sqrt(-2.0 * std::log(u1)) * std::cos(2.0 * kPi * u2);
}

struct Triangle {
  Eigen::Vector3d a, b, c;
  int face;
};

/** \brief A prism: the polygon (counter-clockwise, in the xy plane, triangulated by `tris`,
 * index triples) extruded from z = 0 to z = height. Faces: 0 bottom, 1 top, 2.. the sides. */
std::vector<Triangle> extrude(const std::vector<Eigen::Vector2d>& polygon,
                              const std::vector<std::array<int, 3>>& tris, double height) {
  std::vector<Triangle> out;
  auto at = [](const Eigen::Vector2d& p, double z) { return Eigen::Vector3d(p.x(), p.y(), z); };
  for (const auto& t : tris) {
    out.push_back({at(polygon[t[0]], 0), at(polygon[t[1]], 0), at(polygon[t[2]], 0), 0});
    out.push_back(
        {at(polygon[t[0]], height), at(polygon[t[1]], height), at(polygon[t[2]], height), 1});
  }
  const int m = static_cast<int>(polygon.size());
  for (int i = 0; i < m; ++i) {
    const Eigen::Vector2d& p = polygon[i];
    const Eigen::Vector2d& q = polygon[(i + 1) % m];
    out.push_back({at(p, 0), at(q, 0), at(q, height), 2 + i});
    out.push_back({at(p, 0), at(q, height), at(p, height), 2 + i});
  }
  return out;
}

std::vector<std::array<int, 3>> fan(int m) {
  std::vector<std::array<int, 3>> tris;
  for (int i = 1; i + 1 < m; ++i)
    tris.push_back({0, i, i + 1});
  return tris;
}

std::vector<Eigen::Vector2d> regularPolygon(int m, double radius) {
  std::vector<Eigen::Vector2d> polygon;
  for (int i = 0; i < m; ++i)
    polygon.emplace_back(radius * std::cos(2 * kPi * i / m), radius * std::sin(2 * kPi * i / m));
  return polygon;
}

/** \brief n points uniformly by area on the triangles; their faces and face normals. */
void sampleTriangles(const std::vector<Triangle>& tris, std::size_t n, std::mt19937_64& rng,
                     std::vector<Eigen::Vector3d>& points, std::vector<int>& faces,
                     std::vector<Eigen::Vector3d>& normals) {
  std::vector<double> cumulative;
  double total = 0;
  for (const auto& t : tris) {
    total += 0.5 * (t.b - t.a).cross(t.c - t.a).norm();
    cumulative.push_back(total);
  }
  for (std::size_t i = 0; i < n; ++i) {
    const double r = uniform01(rng) * total;
    const std::size_t k = std::min<std::size_t>(
        std::upper_bound(cumulative.begin(), cumulative.end(), r) - cumulative.begin(),
        tris.size() - 1);
    const Triangle& t = tris[k];
    double u = uniform01(rng), v = uniform01(rng);
    if (u + v > 1.0)
      u = 1.0 - u, v = 1.0 - v;
    points.push_back(t.a + u * (t.b - t.a) + v * (t.c - t.a));
    faces.push_back(t.face);
    normals.push_back((t.b - t.a).cross(t.c - t.a).normalized());
  }
}

void sampleCylinder(std::size_t n, std::mt19937_64& rng, std::vector<Eigen::Vector3d>& points,
                    std::vector<int>& faces, std::vector<Eigen::Vector3d>& normals) {
  const double radius = 0.5, height = 1.0;
  const double side = 2 * kPi * radius * height, cap = kPi * radius * radius;
  for (std::size_t i = 0; i < n; ++i) {
    const double r = uniform01(rng) * (side + 2 * cap);
    const double angle = 2 * kPi * uniform01(rng);
    const Eigen::Vector3d dir(std::cos(angle), std::sin(angle), 0.0);
    if (r < side) {
      points.push_back(radius * dir + Eigen::Vector3d(0, 0, height * uniform01(rng)));
      faces.push_back(0);
      normals.push_back(dir);
    } else {
      const bool top = r >= side + cap;
      points.push_back(radius * std::sqrt(uniform01(rng)) * dir +
                       Eigen::Vector3d(0, 0, top ? height : 0.0));
      faces.push_back(top ? 2 : 1);
      normals.push_back(Eigen::Vector3d(0, 0, top ? 1.0 : -1.0));
    }
  }
}

struct Sampled {
  LabeledShape shape;
  std::vector<Eigen::Vector3d> normals;
};

Sampled sample(const std::string& name, std::size_t n, std::uint64_t seed, double noise) {
  std::mt19937_64 rng(seed);
  std::vector<Eigen::Vector3d> points, normals;
  std::vector<int> faces;
  int num_faces = 0;
  if (name == "cylinder") {
    sampleCylinder(n, rng, points, faces, normals);
    num_faces = 3;
  } else {
    std::vector<Triangle> tris;
    if (name == "cube") {
      tris = extrude({{0, 0}, {1, 0}, {1, 1}, {0, 1}}, fan(4), 1.0);
      num_faces = 6;
    } else if (name == "triangular_prism") {
      tris = extrude(regularPolygon(3, 1.0 / std::sqrt(3.0)), fan(3), 1.2);
      num_faces = 5;
    } else if (name == "hexagonal_prism") {
      tris = extrude(regularPolygon(6, 0.5), fan(6), 1.0);
      num_faces = 8;
    } else if (name == "l_block") {
      // (0,0) (1,0) (1,.5) (.5,.5) (.5,1) (0,1): two rectangles, four triangles.
      tris = extrude({{0, 0}, {1, 0}, {1, 0.5}, {0.5, 0.5}, {0.5, 1}, {0, 1}},
                     {{0, 1, 2}, {0, 2, 3}, {0, 3, 4}, {0, 4, 5}}, 0.4);
      num_faces = 8;
    } else {
      throw std::invalid_argument("unknown CAD shape '" + name + "'");
    }
    sampleTriangles(tris, n, rng, points, faces, normals);
  }
  Sampled out;
  out.shape.cloud.reset(new pcl::PointCloud<pcl::PointXYZ>);
  out.shape.num_parts = num_faces;
  for (std::size_t i = 0; i < points.size(); ++i) {
    Eigen::Vector3d p = points[i];
    if (noise > 0)
      for (int d = 0; d < 3; ++d)
        p[d] += noise * gaussian(rng);
    out.shape.cloud->push_back(pcl::PointXYZ(float(p.x()), float(p.y()), float(p.z())));
    out.shape.labels.push_back(faces[i]);
  }
  out.normals = std::move(normals);
  return out;
}

} // namespace

LabeledShape makeCube(std::size_t n, std::uint64_t seed, double noise) {
  return sample("cube", n, seed, noise).shape;
}
LabeledShape makeTriangularPrism(std::size_t n, std::uint64_t seed, double noise) {
  return sample("triangular_prism", n, seed, noise).shape;
}
LabeledShape makeHexagonalPrism(std::size_t n, std::uint64_t seed, double noise) {
  return sample("hexagonal_prism", n, seed, noise).shape;
}
LabeledShape makeLBlock(std::size_t n, std::uint64_t seed, double noise) {
  return sample("l_block", n, seed, noise).shape;
}
LabeledShape makeCylinder(std::size_t n, std::uint64_t seed, double noise) {
  return sample("cylinder", n, seed, noise).shape;
}
LabeledShape makeCadShape(const std::string& name, std::size_t n, std::uint64_t seed,
                          double noise) {
  return sample(name, n, seed, noise).shape;
}

pcl::PointCloud<pcl::PointNormal>::Ptr withFaceNormals(const std::string& name, std::size_t n,
                                                       std::uint64_t seed, double noise) {
  const Sampled s = sample(name, n, seed, noise);
  pcl::PointCloud<pcl::PointNormal>::Ptr out(new pcl::PointCloud<pcl::PointNormal>);
  for (std::size_t i = 0; i < s.normals.size(); ++i) {
    pcl::PointNormal p;
    p.getVector3fMap() = (*s.shape.cloud)[i].getVector3fMap();
    p.getNormalVector3fMap() = s.normals[i].cast<float>();
    p.curvature = 0.0f;
    out->push_back(p);
  }
  return out;
}

const std::vector<CadCase>& cadCases() {
  static const std::vector<CadCase> cases = {{"cube", 6000, 0.0},
                                             {"cube", 6000, 0.005},
                                             {"triangular_prism", 6000, 0.0},
                                             {"triangular_prism", 6000, 0.005},
                                             {"hexagonal_prism", 8000, 0.0},
                                             {"hexagonal_prism", 8000, 0.005},
                                             {"l_block", 8000, 0.0},
                                             {"l_block", 8000, 0.005},
                                             {"cylinder", 6000, 0.0},
                                             {"cylinder", 6000, 0.005},
                                             {"cube", 6000, 0.01},
                                             {"triangular_prism", 6000, 0.01},
                                             {"hexagonal_prism", 6000, 0.01},
                                             {"l_block", 6000, 0.01},
                                             {"cylinder", 6000, 0.01}};
  return cases;
}

std::string caseName(const CadCase& c) {
  return c.shape + (c.noise == 0.0 ? "_clean" : c.noise < 0.01 ? "_noisy" : "_heavy_noise");
}

void PrintTo(const CadCase& c, std::ostream* os) {
  *os << caseName(c) << " (n " << c.n << ", noise " << c.noise << ")";
}

} // namespace test
} // namespace pcl_ncut_seg
