// Concave creases between supernodes (an extension of Sec. 5.1).
#include "core/cut/concavity.h"
#include "core/common/geometry.h"
#include "core/common/threads.h"

#include <Eigen/Dense>

#ifdef _OPENMP
#include <omp.h>
#endif

#include <algorithm>
#include <array>
#include <cmath>
#include <map>
#include <optional>

namespace pcl_ncut_seg {

namespace {

/// The least-squares plane's unit normal through p and its graph neighbours (3 floats to
/// normal), or false when they have no plane. The moments are summed in float relative to p
/// (exact enough at the neighbourhood's scale, and far from the origin too); the 3x3
/// eigenproblem is solved in closed form.
bool pointNormal(const CsrGraph& graph, const float* xyz, std::size_t p, float* normal) {
  const std::uint32_t begin = graph.offsets[p], end = graph.offsets[p + 1];
  if (end - begin < 2)
    return false;
  ShiftedMoments<float> moments(&xyz[3 * p]);
  moments.add(&xyz[3 * p]);
  for (std::uint32_t e = begin; e < end; ++e)
    moments.add(&xyz[3 * graph.targets[e]]);
  const std::optional<Plane> plane = fitPlane(moments.scatter(MeanProduct::kColumnFirst),
                                              kNotCollinearFloat, EigenSolve::kClosedForm);
  if (!plane)
    return false;
  for (int d = 0; d < 3; ++d)
    normal[d] = static_cast<float>(plane->normal[d]);
  return true;
}

/// Bucket queue for Prim's tree: the cost 1 - |n_p . n_q| in [0, 1], rounded down to a multiple
/// of 1/1024, is the bucket. (On the benchmark's models this orients every point as the tree
/// over exact costs does; steps of 1/64 turned parts of a rotor the other way.) Each bucket is
/// first in, first out, so the tree grows through smooth regions as a compact front that holds
/// few queued vertices. A bitmap finds the lowest non-empty bucket.
class BucketQueue {
public:
  static constexpr std::size_t kBuckets = 1025; // cost 1 is the last

  static std::uint16_t key(float cost) {
    return static_cast<std::uint16_t>(std::min(std::max(cost, 0.0f), 1.0f) * 1024.0f);
  }
  bool empty() const { return nonempty_ == 0; }
  void push(std::uint16_t key, std::uint32_t v) {
    buckets_[key].items.push_back(v);
    if (!(bits_[key >> 6] & (1ull << (key & 63)))) {
      bits_[key >> 6] |= 1ull << (key & 63);
      ++nonempty_;
    }
  }
  /// Removes a vertex from the lowest bucket (the earliest pushed there); returns its key.
  std::uint16_t pop(std::uint32_t& v) {
    std::size_t w = 0;
    while (bits_[w] == 0)
      ++w;
    const auto key =
        static_cast<std::uint16_t>(64 * w + static_cast<std::size_t>(__builtin_ctzll(bits_[w])));
    Fifo& bucket = buckets_[key];
    v = bucket.items[bucket.head++];
    if (bucket.head == bucket.items.size()) {
      bucket.items.clear();
      bucket.head = 0;
      bits_[w] &= ~(1ull << (key & 63));
      --nonempty_;
    } else if (bucket.head >= 1024 && 2 * bucket.head >= bucket.items.size()) {
      // Drop the taken half: the storage stays proportional to what is queued.
      bucket.items.erase(bucket.items.begin(),
                         bucket.items.begin() + static_cast<std::ptrdiff_t>(bucket.head));
      bucket.head = 0;
    }
    return key;
  }

private:
  struct Fifo {
    std::vector<std::uint32_t> items; ///< queued from head on
    std::size_t head = 0;
  };
  std::array<Fifo, kBuckets> buckets_;
  std::array<std::uint64_t, (kBuckets + 63) / 64> bits_{};
  std::size_t nonempty_ = 0;
};

} // namespace

namespace {
Eigen::Vector3d point(const float* xyz, std::size_t v) {
  return {xyz[3 * v], xyz[3 * v + 1], xyz[3 * v + 2]};
}

float dot(const std::vector<float>& normals, std::size_t a, std::size_t b) {
  return normals[3 * a] * normals[3 * b] + normals[3 * a + 1] * normals[3 * b + 1] +
         normals[3 * a + 2] * normals[3 * b + 2];
}

/// The components of the graph, each with its normals made consistent and its centroid.
struct OrientedComponents {
  std::vector<std::uint32_t> component; ///< per vertex
  std::vector<Eigen::Vector3d> centroid;
};

/// Orientation: Prim's tree over 1 - |n_p . n_q|, grown over each component from its first
/// vertex, each normal turned to agree with its tree parent's. The tree does not depend on
/// where it starts (up to ties), so a component may then be turned as a whole.
OrientedComponents orientAlongTree(const CsrGraph& graph, const float* xyz,
                                   std::vector<float>& normals) {
  const std::size_t n = graph.numVertices();
  // key[v]: v's best bucket so far (or kUnseen, kDone). parent[v]: while v is queued, the tree
  // vertex it came from; once v is done, its component.
  constexpr std::uint16_t kUnseen = 0xFFFF, kDone = 0xFFFE;
  std::vector<std::uint16_t> key(n, kUnseen);
  std::vector<std::uint32_t> parent(n);
  std::vector<Eigen::Vector3d> centroid;
  std::vector<std::size_t> size;
  BucketQueue queue;
  for (std::size_t root = 0; root < n; ++root) {
    if (key[root] != kUnseen)
      continue;
    const auto c = static_cast<std::uint32_t>(centroid.size());
    centroid.emplace_back(Eigen::Vector3d::Zero());
    size.push_back(0);
    parent[root] = static_cast<std::uint32_t>(root);
    key[root] = 0;
    queue.push(0, static_cast<std::uint32_t>(root));
    while (!queue.empty()) {
      std::uint32_t v;
      const std::uint16_t k = queue.pop(v);
      if (key[v] != k)
        continue; // done, or queued again with a lower key
      key[v] = kDone;
      if (v != parent[v] && dot(normals, v, parent[v]) < 0.0f)
        for (int d = 0; d < 3; ++d)
          normals[3 * v + d] = -normals[3 * v + d];
      parent[v] = c;
      centroid[c] += point(xyz, v);
      ++size[c];
      for (std::uint32_t e = graph.offsets[v]; e < graph.offsets[v + 1]; ++e) {
        const std::uint32_t w = graph.targets[e];
        if (key[w] == kDone)
          continue;
        const std::uint16_t kw = BucketQueue::key(1.0f - std::abs(dot(normals, v, w)));
        if (kw < key[w]) {
          key[w] = kw;
          parent[w] = v;
          queue.push(kw, w);
        }
      }
    }
  }
  for (std::size_t c = 0; c < centroid.size(); ++c)
    centroid[c] /= static_cast<double>(size[c]);
  return {std::move(parent), std::move(centroid)};
}

/// Per component, whether to turn it so that its normals point outwards (or, with a
/// viewpoint, face the sensor). Of two tests the more decisive: (a) at the point farthest from
/// the centroid a smooth closed surface touches the sphere through it, so its normal is
/// parallel to p - c: the cosine tells the side, and how well the fitted plane is the tangent
/// plane there (near 0 at the tip of a thin fin, whose plane holds both sides). (b) Over a
/// closed surface the sum of n . (p - c) is 3 times the enclosed volume for outward normals
/// (the divergence theorem; the points stand for equal areas), so its sign tells the side, and
/// its ratio to the sum of |n . (p - c)| how consistently the points agree (low where thin
/// parts took the wrong side).
std::vector<char> componentsToTurn(const float* xyz, const std::vector<float>& normals,
                                   const OrientedComponents& comps, const float* viewpoint) {
  const std::size_t num_comps = comps.centroid.size();
  std::vector<double> flux(num_comps, 0.0), spread(num_comps, 0.0), far(num_comps, -1.0);
  std::vector<double> seed_cos(num_comps, 0.0), facing(num_comps, 0.0);
  for (std::size_t v = 0; v < comps.component.size(); ++v) {
    const std::uint32_t c = comps.component[v];
    if (viewpoint) {
      const Eigen::Vector3d to_sensor =
          Eigen::Vector3d(viewpoint[0], viewpoint[1], viewpoint[2]) - point(xyz, v);
      const double d = to_sensor.norm();
      if (d > 0.0)
        facing[c] += (normals[3 * v] * to_sensor[0] + normals[3 * v + 1] * to_sensor[1] +
                      normals[3 * v + 2] * to_sensor[2]) /
                     d;
    }
    const Eigen::Vector3d out = point(xyz, v) - comps.centroid[c];
    const double along =
        normals[3 * v] * out[0] + normals[3 * v + 1] * out[1] + normals[3 * v + 2] * out[2];
    flux[c] += along;
    spread[c] += std::abs(along);
    const double d = out.norm();
    const bool has_normal =
        normals[3 * v] != 0.0f || normals[3 * v + 1] != 0.0f || normals[3 * v + 2] != 0.0f;
    if (has_normal && d > far[c]) {
      far[c] = d;
      seed_cos[c] = d > 0.0 ? along / d : 0.0;
    }
  }
  std::vector<char> turn(num_comps, 0);
  for (std::size_t c = 0; c < num_comps; ++c) {
    const double consistency = spread[c] > 0.0 ? flux[c] / spread[c] : 0.0;
    turn[c] = viewpoint ? facing[c] < 0.0
                        : (std::abs(seed_cos[c]) >= std::abs(consistency) ? seed_cos[c]
                                                                          : consistency) < 0.0;
  }
  return turn;
}
} // namespace

std::vector<float> orientedNormals(const CsrGraph& graph, const float* xyz, unsigned num_threads,
                                   const float* viewpoint) {
  const std::size_t n = graph.numVertices();
  std::vector<float> normals(3 * n, 0.0f);
  // The plane fits are independent: the same result for any number of threads.
  const auto sn = static_cast<std::int64_t>(n);
#pragma omp parallel for schedule(static, 4096) num_threads(usableThreads(num_threads))
  for (std::int64_t p = 0; p < sn; ++p)
    pointNormal(graph, xyz, static_cast<std::size_t>(p), &normals[3 * p]);
  const OrientedComponents comps = orientAlongTree(graph, xyz, normals);
  const std::vector<char> turn = componentsToTurn(xyz, normals, comps, viewpoint);
  for (std::size_t v = 0; v < n; ++v)
    if (turn[comps.component[v]])
      for (int d = 0; d < 3; ++d)
        normals[3 * v + d] = -normals[3 * v + d];
  return normals;
}

double meanAbsBend(const CsrGraph& graph, const float* xyz, const std::vector<float>& normals,
                   unsigned num_threads) {
  const std::size_t n = graph.numVertices();
  constexpr std::size_t kBlock = 4096;
  const std::size_t blocks = (n + kBlock - 1) / kBlock;
  std::vector<double> block_bend(blocks, 0.0);
  std::vector<std::size_t> block_edges(blocks, 0);
#pragma omp parallel for schedule(dynamic, 1) num_threads(usableThreads(num_threads))
  for (std::ptrdiff_t b = 0; b < static_cast<std::ptrdiff_t>(blocks); ++b) {
    const std::size_t last = std::min(n, (static_cast<std::size_t>(b) + 1) * kBlock);
    double bend = 0.0; // in a register: the same additions in the same order
    std::size_t edges = 0;
    for (std::size_t p = static_cast<std::size_t>(b) * kBlock; p < last; ++p)
      for (std::uint32_t e = graph.offsets[p]; e < graph.offsets[p + 1]; ++e)
        if (graph.targets[e] > p) {
          bend += std::abs(edgeBend(xyz, normals, p, graph.targets[e], graph.lengths[e]));
          ++edges;
        }
    block_bend[b] = bend;
    block_edges[b] = edges;
  }
  double total = 0.0;
  std::size_t edges = 0;
  for (std::size_t b = 0; b < blocks; ++b) {
    total += block_bend[b];
    edges += block_edges[b];
  }
  return edges > 0 ? total / static_cast<double>(edges) : 0.0;
}

Connectivity contactConcavity(const CsrGraph& graph, const float* xyz,
                              const std::vector<float>& normals,
                              const std::vector<std::uint32_t>& label, double typical_bend) {
  const std::size_t n = graph.numVertices();
  std::map<std::pair<std::uint32_t, std::uint32_t>, std::pair<double, std::size_t>> sum;
  for (std::size_t p = 0; p < n; ++p)
    for (std::uint32_t e = graph.offsets[p]; e < graph.offsets[p + 1]; ++e) {
      const std::uint32_t q = graph.targets[e];
      if (q <= p || label[p] == label[q])
        continue;
      auto& s = sum[{std::min(label[p], label[q]), std::max(label[p], label[q])}];
      s.first += std::max(0.0, -edgeBend(xyz, normals, p, q, graph.lengths[e]));
      ++s.second;
    }
  Connectivity out;
  const double typical = typical_bend > 0.0 ? typical_bend : meanAbsBend(graph, xyz, normals);
  for (const auto& [key, s] : sum)
    out[key] = typical > 0.0 ? s.first / static_cast<double>(s.second) / typical : 0.0;
  return out;
}

} // namespace pcl_ncut_seg
