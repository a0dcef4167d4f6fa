// Concave creases between supernodes (an extension of Sec. 5.1).
#include <pcl_ncut_seg/core/concavity.h>

#include <Eigen/Dense>

#include <algorithm>
#include <cmath>
#include <functional>
#include <map>
#include <queue>
#include <tuple>

namespace pcl_ncut_seg {

std::vector<float> orientedNormals(const CsrGraph& graph, const float* xyz) {
  const std::size_t n = graph.numVertices();
  std::vector<float> normals(3 * n, 0.0f);
  for (std::size_t p = 0; p < n; ++p) {
    const std::uint32_t begin = graph.offsets[p], end = graph.offsets[p + 1];
    if (end - begin < 2)
      continue;
    Eigen::Vector3d mean = Eigen::Vector3d::Zero();
    auto point = [&](std::size_t v) {
      return Eigen::Vector3d(xyz[3 * v], xyz[3 * v + 1], xyz[3 * v + 2]);
    };
    mean += point(p);
    for (std::uint32_t e = begin; e < end; ++e)
      mean += point(graph.targets[e]);
    mean /= static_cast<double>(end - begin + 1);
    Eigen::Matrix3d cov = (point(p) - mean) * (point(p) - mean).transpose();
    for (std::uint32_t e = begin; e < end; ++e) {
      const Eigen::Vector3d d = point(graph.targets[e]) - mean;
      cov += d * d.transpose();
    }
    Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> solver(cov);
    if (solver.info() != Eigen::Success || !(solver.eigenvalues()[1] > 0.0))
      continue; // collinear or coincident: no plane
    const Eigen::Vector3d normal = solver.eigenvectors().col(0);
    for (int d = 0; d < 3; ++d)
      normals[3 * p + d] = static_cast<float>(normal[d]);
  }

  // Orientation: Prim's tree over 1 - |n_p . n_q| from a seed per component.
  auto dot = [&](std::size_t a, std::size_t b) {
    return normals[3 * a] * normals[3 * b] + normals[3 * a + 1] * normals[3 * b + 1] +
           normals[3 * a + 2] * normals[3 * b + 2];
  };
  std::vector<std::uint32_t> comp;
  const std::size_t num_comps = connectedComponents(graph, comp);
  std::vector<Eigen::Vector3d> centroid(num_comps, Eigen::Vector3d::Zero());
  std::vector<std::size_t> size(num_comps, 0);
  for (std::size_t v = 0; v < n; ++v) {
    centroid[comp[v]] += Eigen::Vector3d(xyz[3 * v], xyz[3 * v + 1], xyz[3 * v + 2]);
    ++size[comp[v]];
  }
  for (std::size_t c = 0; c < num_comps; ++c)
    centroid[c] /= static_cast<double>(size[c]);
  std::vector<std::int64_t> seed(num_comps, -1);
  std::vector<double> far(num_comps, -1.0);
  for (std::size_t v = 0; v < n; ++v) {
    const Eigen::Vector3d d =
        Eigen::Vector3d(xyz[3 * v], xyz[3 * v + 1], xyz[3 * v + 2]) - centroid[comp[v]];
    const bool has_normal =
        normals[3 * v] != 0.0f || normals[3 * v + 1] != 0.0f || normals[3 * v + 2] != 0.0f;
    if (has_normal && d.norm() > far[comp[v]]) {
      far[comp[v]] = d.norm();
      seed[comp[v]] = static_cast<std::int64_t>(v);
    }
  }
  std::vector<char> done(n, 0);
  using Item = std::tuple<double, std::uint32_t, std::uint32_t>; // cost, vertex, from
  std::priority_queue<Item, std::vector<Item>, std::greater<Item>> queue;
  for (std::size_t c = 0; c < num_comps; ++c) {
    if (seed[c] < 0)
      continue;
    const auto s = static_cast<std::uint32_t>(seed[c]);
    const Eigen::Vector3d out =
        Eigen::Vector3d(xyz[3 * s], xyz[3 * s + 1], xyz[3 * s + 2]) - centroid[c];
    const double along =
        normals[3 * s] * out[0] + normals[3 * s + 1] * out[1] + normals[3 * s + 2] * out[2];
    if (along < 0.0)
      for (int d = 0; d < 3; ++d)
        normals[3 * s + d] = -normals[3 * s + d];
    queue.emplace(0.0, s, s);
    while (!queue.empty()) {
      const auto [cost, v, from] = queue.top();
      queue.pop();
      if (done[v])
        continue;
      done[v] = 1;
      if (v != from && dot(v, from) < 0.0f)
        for (int d = 0; d < 3; ++d)
          normals[3 * v + d] = -normals[3 * v + d];
      for (std::uint32_t e = graph.offsets[v]; e < graph.offsets[v + 1]; ++e) {
        const std::uint32_t w = graph.targets[e];
        if (!done[w])
          queue.emplace(1.0 - std::abs(dot(v, w)), w, v);
      }
    }
  }
  return normals;
}

Connectivity contactConcavity(const CsrGraph& graph, const float* xyz,
                              const std::vector<float>& normals,
                              const std::vector<std::uint32_t>& label) {
  const std::size_t n = graph.numVertices();
  // Signed bend of an edge: > 0 where the surface folds outwards (convex), < 0 inwards.
  auto bend = [&](std::size_t p, std::uint32_t q, float length) {
    if (!(length > 0.0f))
      return 0.0;
    double s = 0.0;
    for (int d = 0; d < 3; ++d)
      s += (normals[3 * p + d] - normals[3 * q + d]) * (xyz[3 * p + d] - xyz[3 * q + d]);
    return s / length;
  };
  double total = 0.0;
  std::size_t edges = 0;
  std::map<std::pair<std::uint32_t, std::uint32_t>, std::pair<double, std::size_t>> sum;
  for (std::size_t p = 0; p < n; ++p)
    for (std::uint32_t e = graph.offsets[p]; e < graph.offsets[p + 1]; ++e) {
      const std::uint32_t q = graph.targets[e];
      if (q <= p)
        continue;
      const double b = bend(p, q, graph.lengths[e]);
      total += std::abs(b);
      ++edges;
      if (label[p] == label[q])
        continue;
      auto& s = sum[{std::min(label[p], label[q]), std::max(label[p], label[q])}];
      s.first += std::max(0.0, -b);
      ++s.second;
    }
  Connectivity out;
  const double typical = edges > 0 ? total / static_cast<double>(edges) : 0.0;
  for (const auto& [key, s] : sum)
    out[key] = typical > 0.0 ? s.first / static_cast<double>(s.second) / typical : 0.0;
  return out;
}

} // namespace pcl_ncut_seg
