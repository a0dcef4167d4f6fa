#include "eval_sampling.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <numeric>
#include <random>
#include <stdexcept>

namespace pcl_ncut_seg {
namespace eval {

namespace {

/** [0, 1) from the top 53 bits: the same on every platform. */
double uniform01(std::mt19937_64& rng) {
  return static_cast<double>(rng() >> 11) * 0x1.0p-53;
}

std::uint64_t splitMix64(std::uint64_t x) {
  x += 0x9e3779b97f4a7c15ULL;
  x = (x ^ (x >> 30)) * 0xbf58476d1ce4e5b9ULL;
  x = (x ^ (x >> 27)) * 0x94d049bb133111ebULL;
  return x ^ (x >> 31);
}

double totalArea(const TriangleMesh& mesh) {
  const std::vector<double> areas = faceAreas(mesh);
  return std::accumulate(areas.begin(), areas.end(), 0.0);
}

/** The bounding box of x y z triples. */
struct Box {
  std::array<double, 3> lo{}, hi{};
  explicit Box(const std::vector<float>& xyz) {
    lo.fill(std::numeric_limits<double>::max());
    hi.fill(std::numeric_limits<double>::lowest());
    for (std::size_t i = 0; i + 2 < xyz.size(); i += 3)
      for (int d = 0; d < 3; ++d) {
        lo[d] = std::min<double>(lo[d], xyz[i + d]);
        hi[d] = std::max<double>(hi[d], xyz[i + d]);
      }
  }
};

/** Points bucketed in a uniform grid of cubic cells (CSR: the points of cell c are
 * index[start[c] .. start[c + 1])). */
class Grid {
public:
  explicit Grid(const std::vector<float>& points) : points_(points), box_(points) {
    const std::size_t n = points.size() / 3;
    double extent = 0;
    for (int d = 0; d < 3; ++d)
      extent = std::max(extent, box_.hi[d] - box_.lo[d]);
    // About 2 cbrt(n) cells along the longest side: a few points per cell on a surface.
    cell_ = std::max(extent / (2.0 * std::cbrt(static_cast<double>(n))), 1e-12);
    for (int d = 0; d < 3; ++d)
      dims_[d] = std::max(1L, static_cast<long>((box_.hi[d] - box_.lo[d]) / cell_) + 1);
    std::vector<std::size_t> cell_of(n);
    start_.assign(static_cast<std::size_t>(dims_[0] * dims_[1] * dims_[2]) + 1, 0);
    for (std::size_t i = 0; i < n; ++i) {
      cell_of[i] = cellIndex(cellOf(&points[3 * i]));
      ++start_[cell_of[i] + 1];
    }
    std::partial_sum(start_.begin(), start_.end(), start_.begin());
    index_.resize(n);
    std::vector<std::size_t> fill(start_.begin(), start_.end() - 1);
    for (std::size_t i = 0; i < n; ++i) // ascending within a cell: ties go to the lower index
      index_[fill[cell_of[i]]++] = static_cast<std::uint32_t>(i);
  }

  std::uint32_t nearest(const float* q) const {
    const std::array<long, 3> c = cellOf(q);
    double best = std::numeric_limits<double>::max();
    std::uint32_t best_i = 0;
    for (long r = 0;; ++r) {
      if (r > dims_[0] && r > dims_[1] && r > dims_[2])
        break;
      scanRing(q, c, r, best, best_i);
      // Any point in ring r + 1 or beyond is at least r cells away.
      const double reach = static_cast<double>(r) * cell_;
      if (best <= reach * reach)
        break;
    }
    return best_i;
  }

private:
  std::array<long, 3> cellOf(const float* p) const {
    std::array<long, 3> c{};
    for (int d = 0; d < 3; ++d)
      c[d] = std::clamp(static_cast<long>((p[d] - box_.lo[d]) / cell_), 0L, dims_[d] - 1);
    return c;
  }
  std::size_t cellIndex(const std::array<long, 3>& c) const {
    return static_cast<std::size_t>((c[2] * dims_[1] + c[1]) * dims_[0] + c[0]);
  }

  /** The cells at Chebyshev distance exactly r from c. */
  void scanRing(const float* q, const std::array<long, 3>& c, long r, double& best,
                std::uint32_t& best_i) const {
    for (long dz = -r; dz <= r; ++dz)
      for (long dy = -r; dy <= r; ++dy)
        for (long dx = -r; dx <= r; ++dx) {
          if (std::max({std::labs(dx), std::labs(dy), std::labs(dz)}) != r)
            continue;
          const std::array<long, 3> cell = {c[0] + dx, c[1] + dy, c[2] + dz};
          bool inside = true;
          for (int d = 0; d < 3; ++d)
            inside = inside && cell[d] >= 0 && cell[d] < dims_[d];
          if (inside)
            scanCell(q, cellIndex(cell), best, best_i);
        }
  }

  void scanCell(const float* q, std::size_t cell, double& best, std::uint32_t& best_i) const {
    for (std::size_t k = start_[cell]; k < start_[cell + 1]; ++k) {
      const std::uint32_t i = index_[k];
      double d2 = 0;
      for (int d = 0; d < 3; ++d) {
        const double e = static_cast<double>(points_[3 * i + d]) - q[d];
        d2 += e * e;
      }
      if (d2 < best || (d2 == best && i < best_i)) {
        best = d2;
        best_i = i;
      }
    }
  }

  const std::vector<float>& points_;
  Box box_;
  double cell_ = 1;
  std::array<long, 3> dims_{};
  std::vector<std::size_t> start_;
  std::vector<std::uint32_t> index_;
};

} // namespace

std::uint64_t drawSeed(int model_id, int draw, int stream) {
  std::uint64_t x = splitMix64(static_cast<std::uint64_t>(model_id));
  x = splitMix64(x ^ static_cast<std::uint64_t>(draw));
  return splitMix64(x ^ static_cast<std::uint64_t>(stream));
}

double meanSpacing(double area, std::size_t n) {
  return n == 0 ? 0.0 : std::sqrt(area / static_cast<double>(n));
}

int longestAxis(const std::vector<float>& vertices) {
  const Box box(vertices);
  int axis = 0;
  for (int d = 1; d < 3; ++d)
    if (box.hi[d] - box.lo[d] > box.hi[axis] - box.lo[axis])
      axis = d;
  return axis;
}

double gradientDensity(double ratio, double t) {
  return ratio - (ratio - 1.0) * t;
}

std::vector<float> sampleWithGradient(const TriangleMesh& mesh, std::size_t n, double ratio,
                                      std::uint64_t seed) {
  if (ratio == 1.0)
    return sampleSurface(mesh, n, seed);
  const int axis = longestAxis(mesh.vertices);
  const Box box(mesh.vertices);
  const double lo = box.lo[axis], length = std::max(box.hi[axis] - lo, 1e-300);
  std::mt19937_64 keep(splitMix64(seed ^ 0x6b656570ULL));
  std::vector<float> out;
  out.reserve(3 * n);
  for (std::uint64_t batch = 0; out.size() < 3 * n; ++batch) {
    const std::vector<float> candidates = sampleSurface(mesh, n, splitMix64(seed + batch));
    if (candidates.empty())
      return {};
    for (std::size_t i = 0; i < candidates.size() && out.size() < 3 * n; i += 3) {
      const double t = std::clamp((candidates[i + axis] - lo) / length, 0.0, 1.0);
      if (uniform01(keep) * ratio < gradientDensity(ratio, t))
        out.insert(out.end(), &candidates[i], &candidates[i] + 3);
    }
  }
  return out;
}

void addNoise(std::vector<float>& xyz, double sigma, std::uint64_t seed) {
  std::mt19937_64 rng(seed);
  const double two_pi = 6.283185307179586476925;
  for (std::size_t i = 0; i < xyz.size(); i += 2) {
    const double u1 = 1.0 - uniform01(rng); // (0, 1]
    const double u2 = uniform01(rng);
    const double radius = sigma * std::sqrt(-2.0 * std::log(u1));
    xyz[i] += static_cast<float>(radius * std::cos(two_pi * u2));
    if (i + 1 < xyz.size())
      xyz[i + 1] += static_cast<float>(radius * std::sin(two_pi * u2));
  }
}

std::vector<std::uint32_t> randomOrder(std::size_t n, std::uint64_t seed) {
  std::vector<std::uint32_t> order(n);
  std::iota(order.begin(), order.end(), 0u);
  std::mt19937_64 rng(seed);
  for (std::size_t i = n; i > 1; --i) {
    const auto j = static_cast<std::size_t>(uniform01(rng) * static_cast<double>(i));
    std::swap(order[i - 1], order[std::min(j, i - 1)]);
  }
  return order;
}

std::vector<float> reordered(const std::vector<float>& xyz,
                             const std::vector<std::uint32_t>& order) {
  std::vector<float> out(3 * order.size());
  for (std::size_t i = 0; i < order.size(); ++i)
    for (int d = 0; d < 3; ++d)
      out[3 * i + d] = xyz[3 * static_cast<std::size_t>(order[i]) + d];
  return out;
}

std::vector<int> mappedBack(const std::vector<int>& labels,
                            const std::vector<std::uint32_t>& order) {
  if (order.empty())
    return labels;
  std::vector<int> out(labels.size(), -1);
  for (std::size_t i = 0; i < order.size() && i < labels.size(); ++i)
    out[order[i]] = labels[i];
  return out;
}

std::vector<std::uint32_t> nearestPoints(const std::vector<float>& points,
                                         const std::vector<float>& queries) {
  if (points.size() < 3)
    throw std::invalid_argument("nearestPoints: no points");
  const Grid grid(points);
  std::vector<std::uint32_t> out(queries.size() / 3);
  for (std::size_t q = 0; q < out.size(); ++q)
    out[q] = grid.nearest(&queries[3 * q]);
  return out;
}

std::vector<int> faceLabels(const std::vector<int>& point_labels,
                            const std::vector<std::uint32_t>& nearest) {
  if (nearest.empty())
    return point_labels;
  std::vector<int> out(nearest.size());
  for (std::size_t f = 0; f < nearest.size(); ++f)
    out[f] = point_labels[nearest[f]];
  return out;
}

std::vector<float> outwardFaceNormals(const TriangleMesh& mesh) {
  std::vector<double> sum(3 * mesh.num_original_faces, 0.0);
  double volume = 0; // six times the signed volume: positive when wound outward
  const float* v = mesh.vertices.data();
  for (std::size_t t = 0; t < mesh.numTriangles(); ++t) {
    const std::uint32_t* f = &mesh.faces[3 * t];
    const float *a = v + 3 * f[0], *b = v + 3 * f[1], *c = v + 3 * f[2];
    const double u[3] = {b[0] - a[0], b[1] - a[1], b[2] - a[2]};
    const double w[3] = {c[0] - a[0], c[1] - a[1], c[2] - a[2]};
    const double cross[3] = {u[1] * w[2] - u[2] * w[1], u[2] * w[0] - u[0] * w[2],
                             u[0] * w[1] - u[1] * w[0]};
    for (int d = 0; d < 3; ++d)
      sum[3 * mesh.original_face[t] + d] += cross[d];
    volume += a[0] * cross[0] + a[1] * cross[1] + a[2] * cross[2];
  }
  const double sign = volume < 0 ? -1.0 : 1.0;
  std::vector<float> normals(sum.size());
  for (std::size_t i = 0; i < mesh.num_original_faces; ++i) {
    const double len = std::sqrt(sum[3 * i] * sum[3 * i] + sum[3 * i + 1] * sum[3 * i + 1] +
                                 sum[3 * i + 2] * sum[3 * i + 2]);
    for (int d = 0; d < 3; ++d)
      normals[3 * i + d] =
          len > 0 ? static_cast<float>(sign * sum[3 * i + d] / len) : (d == 2 ? 1.0f : 0.0f);
  }
  return normals;
}

std::vector<float> nearestFaceNormals(const std::vector<float>& xyz,
                                      const std::vector<float>& centroids,
                                      const std::vector<float>& face_normals) {
  const std::vector<std::uint32_t> face = nearestPoints(centroids, xyz);
  std::vector<float> normals(xyz.size());
  for (std::size_t i = 0; i < face.size(); ++i)
    std::copy_n(&face_normals[3 * face[i]], 3, &normals[3 * i]);
  return normals;
}

SampledCloud makeCloud(const TriangleMesh& mesh, const std::vector<float>& centroids,
                       const SamplingOptions& options, int model_id, int draw) {
  SampledCloud cloud;
  if (!options.active()) {
    cloud.xyz = centroids;
    return cloud;
  }
  const int sample_draw = options.permute || options.jitter > 0 ? 0 : draw;
  cloud.xyz = sampleWithGradient(mesh, options.samples, options.density_ratio,
                                 drawSeed(model_id, sample_draw, 0));
  if (cloud.xyz.empty())
    throw std::runtime_error("the mesh has no area to sample");
  cloud.nearest = nearestPoints(cloud.xyz, centroids);
  cloud.spacing = meanSpacing(totalArea(mesh), options.samples);
  if (options.noise > 0)
    addNoise(cloud.xyz, options.noise * cloud.spacing, drawSeed(model_id, sample_draw, 1));
  if (options.jitter > 0 && draw > 0)
    addNoise(cloud.xyz, options.jitter * cloud.spacing, drawSeed(model_id, draw, 3));
  if (options.permute && draw > 0) {
    cloud.order = randomOrder(options.samples, drawSeed(model_id, draw, 2));
    cloud.xyz = reordered(cloud.xyz, cloud.order);
  }
  return cloud;
}

} // namespace eval
} // namespace pcl_ncut_seg
