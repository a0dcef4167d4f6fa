#include "surfaces/depth_view.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <limits>
#include <numeric>
#include <random>

namespace pcl_ncut_seg {

namespace {

using Vec = std::array<double, 3>;

constexpr double kPi = 3.14159265358979323846;

Vec sub(const Vec& a, const Vec& b) {
  return {a[0] - b[0], a[1] - b[1], a[2] - b[2]};
}
double dot(const Vec& a, const Vec& b) {
  return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}
Vec cross(const Vec& a, const Vec& b) {
  return {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]};
}

/** A triangle's corner and edges in double, the same for the BVH and the brute force. */
struct Triangle {
  Vec a, e1, e2;
};

Triangle triangleOf(const TriangleMesh& mesh, std::size_t t) {
  Vec v[3];
  for (int c = 0; c < 3; ++c)
    for (int d = 0; d < 3; ++d)
      v[c][d] = mesh.vertices[3 * mesh.faces[3 * t + c] + d];
  return {v[0], sub(v[1], v[0]), sub(v[2], v[0])};
}

/** Moeller-Trumbore, two-sided: the ray's t at the triangle, or a negative value for none. */
double intersect(const Triangle& tri, const Vec& o, const Vec& d) {
  const Vec p = cross(d, tri.e2);
  const double det = dot(tri.e1, p);
  if (det == 0)
    return -1;
  const double inv = 1.0 / det;
  const Vec s = sub(o, tri.a);
  const double u = dot(s, p) * inv;
  if (u < 0 || u > 1)
    return -1;
  const Vec q = cross(s, tri.e1);
  const double v = dot(d, q) * inv;
  if (v < 0 || u + v > 1)
    return -1;
  const double t = dot(tri.e2, q) * inv;
  return t > 0 ? t : -1;
}

/** Keep the nearer hit; of equal t, the lower triangle index. */
void consider(const Triangle& tri, std::int64_t index, const Vec& o, const Vec& d, RayHit& best) {
  const double t = intersect(tri, o, d);
  if (t > 0 && (best.triangle < 0 || t < best.t || (t == best.t && index < best.triangle))) {
    best.triangle = index;
    best.t = t;
  }
}

/** A uniform double in [0, 1) from 53 bits, the same on every platform. */
double uniform(std::mt19937_64& rng) {
  return static_cast<double>(rng() >> 11) * 0x1.0p-53;
}

/** A standard normal (Box-Muller on our own uniforms). */
double normal(std::mt19937_64& rng) {
  const double u1 = 1.0 - uniform(rng); // (0, 1]
  const double u2 = uniform(rng);
  return std::sqrt(-2.0 * std::log(u1)) * std::cos(2.0 * kPi * u2);
}

} // namespace

// ------------------------------------------------------------------------------------ BVH

struct RayCaster::Impl {
  struct Node {
    Vec lo, hi;
    std::uint32_t first = 0, count = 0; ///< leaf: triangles order[first, first + count)
    std::uint32_t left = 0, right = 0;  ///< inner node (count == 0): the children
  };
  std::vector<Triangle> tris;
  std::vector<std::uint32_t> order;
  std::vector<Node> nodes;
  std::vector<Vec> centroid;
  double pad = 0;

  explicit Impl(const TriangleMesh& mesh);
  std::uint32_t build(std::uint32_t first, std::uint32_t count);
  bool boxHit(const Node& n, const Vec& o, const Vec& inv, const Vec& d, double far) const;
};

RayCaster::Impl::Impl(const TriangleMesh& mesh) {
  const std::size_t n = mesh.numTriangles();
  tris.reserve(n);
  centroid.reserve(n);
  Vec lo{{1e300, 1e300, 1e300}}, hi{{-1e300, -1e300, -1e300}};
  for (std::size_t t = 0; t < n; ++t) {
    tris.push_back(triangleOf(mesh, t));
    const Triangle& tr = tris.back();
    Vec c;
    for (int d = 0; d < 3; ++d) {
      c[d] = tr.a[d] + (tr.e1[d] + tr.e2[d]) / 3.0;
      lo[d] = std::min({lo[d], tr.a[d], tr.a[d] + tr.e1[d], tr.a[d] + tr.e2[d]});
      hi[d] = std::max({hi[d], tr.a[d], tr.a[d] + tr.e1[d], tr.a[d] + tr.e2[d]});
    }
    centroid.push_back(c);
  }
  // Boxes grow by a little more than rounding, so that no exact hit is lost at a box's face.
  pad = n == 0 ? 0 : 1e-9 * (std::sqrt(dot(sub(hi, lo), sub(hi, lo))) + 1.0);
  order.resize(n);
  std::iota(order.begin(), order.end(), 0u);
  nodes.reserve(n / 2 + 1);
  if (n > 0)
    build(0, static_cast<std::uint32_t>(n));
}

std::uint32_t RayCaster::Impl::build(std::uint32_t first, std::uint32_t count) {
  const auto index = static_cast<std::uint32_t>(nodes.size());
  nodes.emplace_back();
  Node node;
  node.lo = {1e300, 1e300, 1e300};
  node.hi = {-1e300, -1e300, -1e300};
  Vec clo = node.lo, chi = node.hi;
  for (std::uint32_t i = first; i < first + count; ++i) {
    const Triangle& t = tris[order[i]];
    for (int d = 0; d < 3; ++d) {
      const double v[3] = {t.a[d], t.a[d] + t.e1[d], t.a[d] + t.e2[d]};
      node.lo[d] = std::min({node.lo[d], v[0], v[1], v[2]}) - pad;
      node.hi[d] = std::max({node.hi[d], v[0], v[1], v[2]}) + pad;
      clo[d] = std::min(clo[d], centroid[order[i]][d]);
      chi[d] = std::max(chi[d], centroid[order[i]][d]);
    }
  }
  if (count <= 4) {
    node.first = first;
    node.count = count;
    nodes[index] = node;
    return index;
  }
  int axis = 0;
  for (int d = 1; d < 3; ++d)
    if (chi[d] - clo[d] > chi[axis] - clo[axis])
      axis = d;
  const std::uint32_t half = count / 2;
  std::nth_element(
      order.begin() + first, order.begin() + first + half, order.begin() + first + count,
      [&](std::uint32_t a, std::uint32_t b) { return centroid[a][axis] < centroid[b][axis]; });
  node.left = build(first, half);
  node.right = build(first + half, count - half);
  nodes[index] = node;
  return index;
}

/** Whether the ray meets the box at some t in (0, far]. */
bool RayCaster::Impl::boxHit(const Node& n, const Vec& o, const Vec& inv, const Vec& d,
                             double far) const {
  double near = 0;
  for (int k = 0; k < 3; ++k) {
    if (d[k] == 0) {
      if (o[k] < n.lo[k] || o[k] > n.hi[k])
        return false;
      continue;
    }
    double t0 = (n.lo[k] - o[k]) * inv[k], t1 = (n.hi[k] - o[k]) * inv[k];
    if (t0 > t1)
      std::swap(t0, t1);
    near = std::max(near, t0);
    far = std::min(far, t1);
    if (near > far)
      return false;
  }
  return true;
}

RayCaster::RayCaster(const TriangleMesh& mesh) : impl_(new Impl(mesh)) {}
RayCaster::~RayCaster() = default;

RayHit RayCaster::cast(const Vec& origin, const Vec& direction) const {
  RayHit best;
  if (impl_->nodes.empty())
    return best;
  const Vec inv{{1.0 / direction[0], 1.0 / direction[1], 1.0 / direction[2]}};
  std::uint32_t stack[128];
  int top = 0;
  stack[top++] = 0;
  while (top > 0) {
    const Impl::Node& n = impl_->nodes[stack[--top]];
    const double far = best.triangle < 0 ? std::numeric_limits<double>::max() : best.t;
    if (!impl_->boxHit(n, origin, inv, direction, far))
      continue;
    if (n.count > 0) {
      for (std::uint32_t i = n.first; i < n.first + n.count; ++i) {
        const std::uint32_t t = impl_->order[i];
        consider(impl_->tris[t], t, origin, direction, best);
      }
      continue;
    }
    // The nearer child last, so that it is visited first and prunes the other.
    const Impl::Node& l = impl_->nodes[n.left];
    const Impl::Node& r = impl_->nodes[n.right];
    const bool left_first = dot(sub(l.lo, origin), direction) + dot(sub(l.hi, origin), direction) <
                            dot(sub(r.lo, origin), direction) + dot(sub(r.hi, origin), direction);
    stack[top++] = left_first ? n.right : n.left;
    stack[top++] = left_first ? n.left : n.right;
  }
  return best;
}

RayHit RayCaster::castBruteForce(const TriangleMesh& mesh, const Vec& origin,
                                 const Vec& direction) {
  RayHit best;
  for (std::size_t t = 0; t < mesh.numTriangles(); ++t)
    consider(triangleOf(mesh, t), static_cast<std::int64_t>(t), origin, direction, best);
  return best;
}

// --------------------------------------------------------------------------------- camera

double CameraSettings::focalLength() const {
  return 0.5 * width / std::tan(0.5 * horizontal_fov_degrees * kPi / 180.0);
}

std::array<double, 4> CameraPose::quaternion() const {
  const auto& m = rotation; // Shepperd's method: the largest of w, x, y, z first
  const double tr = m[0] + m[4] + m[8];
  std::array<double, 4> q;
  if (tr > 0) {
    const double s = 2.0 * std::sqrt(1.0 + tr);
    q = {0.25 * s, (m[7] - m[5]) / s, (m[2] - m[6]) / s, (m[3] - m[1]) / s};
  } else if (m[0] > m[4] && m[0] > m[8]) {
    const double s = 2.0 * std::sqrt(1.0 + m[0] - m[4] - m[8]);
    q = {(m[7] - m[5]) / s, 0.25 * s, (m[1] + m[3]) / s, (m[2] + m[6]) / s};
  } else if (m[4] > m[8]) {
    const double s = 2.0 * std::sqrt(1.0 + m[4] - m[0] - m[8]);
    q = {(m[2] - m[6]) / s, (m[1] + m[3]) / s, 0.25 * s, (m[5] + m[7]) / s};
  } else {
    const double s = 2.0 * std::sqrt(1.0 + m[8] - m[0] - m[4]);
    q = {(m[3] - m[1]) / s, (m[2] + m[6]) / s, (m[5] + m[7]) / s, 0.25 * s};
  }
  return q;
}

std::size_t DepthView::validPixels() const {
  return static_cast<std::size_t>(
      std::count_if(face.begin(), face.end(), [](std::int64_t f) { return f >= 0; }));
}

bool parseResolution(const std::string& text, int& width, int& height) {
  const std::size_t x = text.find('x');
  if (x == std::string::npos || x == 0 || x + 1 == text.size() ||
      text.find_first_not_of("0123456789x") != std::string::npos ||
      text.find('x', x + 1) != std::string::npos)
    return false;
  const long w = std::strtol(text.substr(0, x).c_str(), nullptr, 10);
  const long h = std::strtol(text.substr(x + 1).c_str(), nullptr, 10);
  if (x > 6 || text.size() - x - 1 > 6 || w < 8 || h < 8 || w > 4096 || h > 4096)
    return false;
  width = static_cast<int>(w);
  height = static_cast<int>(h);
  return true;
}

std::array<double, 9> randomRotation(std::uint64_t seed) {
  std::mt19937_64 rng(seed);
  const double u1 = uniform(rng), u2 = uniform(rng), u3 = uniform(rng);
  // Shoemake's uniform random unit quaternion.
  const double x = std::sqrt(1 - u1) * std::sin(2 * kPi * u2);
  const double y = std::sqrt(1 - u1) * std::cos(2 * kPi * u2);
  const double z = std::sqrt(u1) * std::sin(2 * kPi * u3);
  const double w = std::sqrt(u1) * std::cos(2 * kPi * u3);
  return {1 - 2 * (y * y + z * z), 2 * (x * y - z * w),     2 * (x * z + y * w),
          2 * (x * y + z * w),     1 - 2 * (x * x + z * z), 2 * (y * z - x * w),
          2 * (x * z - y * w),     2 * (y * z + x * w),     1 - 2 * (x * x + y * y)};
}

std::uint64_t viewSeed(std::uint64_t model, std::uint64_t view) {
  std::uint64_t z = model * 0x9E3779B97F4A7C15ull + view * 0xD1B54A32D192ED03ull + 1;
  z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull; // splitmix64's finaliser
  z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
  return z ^ (z >> 31);
}

DepthView renderMesh(const TriangleMesh& world_mesh, const CameraSettings& camera,
                     const CameraPose& pose, std::uint64_t noise_seed) {
  DepthView view;
  view.width = camera.width;
  view.height = camera.height;
  view.pose = pose;
  const std::size_t pixels = static_cast<std::size_t>(camera.width) * camera.height;
  view.xyz.assign(3 * pixels, std::numeric_limits<float>::quiet_NaN());
  view.face.assign(pixels, -1);
  const RayCaster caster(world_mesh);
  const double f = camera.focalLength();
  const auto& R = pose.rotation;
  std::mt19937_64 rng(noise_seed);
  for (int v = 0; v < camera.height; ++v)
    for (int u = 0; u < camera.width; ++u) {
      const Vec c{{(u + 0.5 - 0.5 * camera.width) / f, (v + 0.5 - 0.5 * camera.height) / f, 1.0}};
      const Vec d{{R[0] * c[0] + R[1] * c[1] + R[2], R[3] * c[0] + R[4] * c[1] + R[5],
                   R[6] * c[0] + R[7] * c[1] + R[8]}};
      const RayHit hit = caster.cast(pose.origin, d);
      if (hit.triangle < 0)
        continue;
      // c has z = 1, so t is the depth; the noise moves the point along its ray.
      const double sigma = camera.noise_at_1m * hit.t * hit.t;
      const double depth = sigma > 0 ? hit.t + sigma * normal(rng) : hit.t;
      const std::size_t i = static_cast<std::size_t>(v) * camera.width + u;
      for (int k = 0; k < 3; ++k)
        view.xyz[3 * i + k] = static_cast<float>(pose.origin[k] + depth * d[k]);
      view.face[i] = world_mesh.original_face.empty()
                         ? hit.triangle
                         : static_cast<std::int64_t>(world_mesh.original_face[hit.triangle]);
    }
  return view;
}

DepthView renderView(const TriangleMesh& mesh, const CameraSettings& camera, std::uint64_t seed) {
  Vec lo{{1e300, 1e300, 1e300}}, hi{{-1e300, -1e300, -1e300}};
  for (std::size_t i = 0; i < mesh.vertices.size(); ++i) {
    lo[i % 3] = std::min(lo[i % 3], static_cast<double>(mesh.vertices[i]));
    hi[i % 3] = std::max(hi[i % 3], static_cast<double>(mesh.vertices[i]));
  }
  const double diagonal = mesh.vertices.empty() ? 0 : std::sqrt(dot(sub(hi, lo), sub(hi, lo)));
  if (!(diagonal > 0) || mesh.numTriangles() == 0)
    return DepthView();
  const double scale = camera.object_diagonal / diagonal;
  Vec centre;
  for (int d = 0; d < 3; ++d)
    centre[d] = 0.5 * (lo[d] + hi[d]);
  TriangleMesh world = mesh;
  for (std::size_t i = 0; i < world.vertices.size(); ++i)
    world.vertices[i] = static_cast<float>(scale * (mesh.vertices[i] - centre[i % 3]));
  CameraPose pose;
  pose.rotation = randomRotation(seed);
  for (int d = 0; d < 3; ++d) // the camera's z axis (the rotation's third column) at the centre
    pose.origin[d] = -camera.distance * pose.rotation[3 * d + 2];
  DepthView view = renderMesh(world, camera, pose, viewSeed(seed, 0x6e6f697365ull));
  view.scale = scale;
  view.centre = centre;
  return view;
}

} // namespace pcl_ncut_seg
