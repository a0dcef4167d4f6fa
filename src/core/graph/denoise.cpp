// Sensor noise detected and projected away (see core/graph/denoise.h).
#include "core/graph/denoise.h"
#include "core/common/geometry.h"
#include "core/common/threads.h"

#include <Eigen/Dense>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <optional>

namespace pcl_ncut_seg {

namespace {

/// The least-squares plane of the given vertices (moments in double about the first one) and
/// the RMS distance to it; nothing when they have none.
std::optional<Plane> ringPlane(const float* xyz, const std::vector<std::uint32_t>& members,
                               double& rms) {
  if (members.size() < 3)
    return std::nullopt;
  ShiftedMoments<double> moments(&xyz[3 * members[0]]);
  for (std::uint32_t v : members)
    moments.add(&xyz[3 * v]);
  const Scatter scatter = moments.scatter(MeanProduct::kRowFirst);
  std::optional<Plane> plane = fitPlane(scatter, kNotCollinearDouble, EigenSolve::kClosedForm);
  if (!plane)
    return std::nullopt;
  const Eigen::Vector3d& lambda = plane->lambda;
  // Scatter below float rounding (squared: 1e-12 of the spread) is none: an exactly flat grid.
  rms = lambda[0] > 1e-12 * lambda[2] ? std::sqrt(lambda[0] / scatter.count) : 0.0;
  return plane;
}

/// The 1-ring (first) and 2-ring of vertex p, without repeats; stamp marks what is in.
class Rings {
public:
  explicit Rings(std::size_t n) : stamp_(n, 0) {}
  void collect(const CsrGraph& graph, std::uint32_t p) {
    ++tick_;
    ring1_.assign(1, p);
    stamp_[p] = tick_;
    for (std::uint32_t e = graph.offsets[p]; e < graph.offsets[p + 1]; ++e)
      add(graph.targets[e], ring1_);
    ring2_ = ring1_;
    for (std::size_t i = 1; i < ring1_.size(); ++i)
      for (std::uint32_t e = graph.offsets[ring1_[i]]; e < graph.offsets[ring1_[i] + 1]; ++e)
        add(graph.targets[e], ring2_);
  }
  const std::vector<std::uint32_t>& ring1() const { return ring1_; }
  const std::vector<std::uint32_t>& ring2() const { return ring2_; }

private:
  void add(std::uint32_t v, std::vector<std::uint32_t>& ring) {
    if (stamp_[v] != tick_) {
      stamp_[v] = tick_;
      ring.push_back(v);
    }
  }
  std::vector<std::uint32_t> stamp_, ring1_, ring2_;
  std::uint32_t tick_ = 0;
};

/// Vertex p projected onto the plane: 3 floats to out.
void projectOnto(const float* xyz, std::uint32_t p, const Plane& plane, float* out) {
  const Eigen::Vector3d x(xyz[3 * p], xyz[3 * p + 1], xyz[3 * p + 2]);
  const Eigen::Vector3d y = x - (x - plane.centroid).dot(plane.normal) * plane.normal;
  for (int d = 0; d < 3; ++d)
    out[d] = static_cast<float>(y[d]);
}

/// residualGrowth() fits every kStride-th vertex.
constexpr std::size_t kStride = 4;

} // namespace

double residualGrowth(const CsrGraph& graph, const float* xyz, unsigned num_threads,
                      RingFits* fits) {
  const std::size_t m = (graph.numVertices() + kStride - 1) / kStride;
  std::vector<double> rms1(m, 0.0), rms2(m, 0.0);
  if (fits) {
    fits->state.assign(m, 0);
    fits->projected.assign(3 * m, 0.0f);
  }
  const auto sm = static_cast<std::int64_t>(m);
#pragma omp parallel num_threads(usableThreads(num_threads))
  {
    Rings rings(graph.numVertices());
    double r1 = 0.0, r2 = 0.0;
#pragma omp for schedule(static, 256)
    for (std::int64_t i = 0; i < sm; ++i) {
      const auto p = static_cast<std::uint32_t>(i * kStride);
      rings.collect(graph, p);
      if (!ringPlane(xyz, rings.ring1(), r1))
        continue;
      const std::optional<Plane> plane = ringPlane(xyz, rings.ring2(), r2);
      if (plane) {
        rms1[i] = r1;
        rms2[i] = r2;
      }
      if (fits) {
        fits->state[i] = plane ? 1 : 2;
        if (plane)
          projectOnto(xyz, p, *plane, &fits->projected[3 * i]);
      }
    }
  }
  double sum1 = 0.0, sum2 = 0.0; // in vertex order: the same for any number of threads
  for (std::size_t i = 0; i < m; ++i) {
    sum1 += rms1[i];
    sum2 += rms2[i];
  }
  return sum1 > 0.0 ? sum2 / sum1 : 0.0;
}

double samplingIrregularity(const CsrGraph& graph) {
  double sum = 0.0, sum_sq = 0.0;
  std::size_t count = 0;
  for (std::uint32_t p = 0; p < graph.numVertices(); ++p) {
    const std::uint32_t begin = graph.offsets[p], end = graph.offsets[p + 1];
    if (begin == end)
      continue;
    double shortest = graph.lengths[begin], total = 0.0;
    for (std::uint32_t e = begin; e < end; ++e) {
      shortest = std::min<double>(shortest, graph.lengths[e]);
      total += graph.lengths[e];
    }
    if (!(total > 0.0))
      continue;
    const double ratio = shortest * (end - begin) / total;
    sum += ratio;
    sum_sq += ratio * ratio;
    ++count;
  }
  if (count < 2 || !(sum > 0.0))
    return 0.0;
  const double mean = sum / count;
  return std::sqrt(std::max(0.0, sum_sq / count - mean * mean)) / mean;
}

std::vector<float> projectOntoLocalPlanes(const CsrGraph& graph, const float* xyz,
                                          unsigned num_threads, const RingFits* fits) {
  const std::size_t n = graph.numVertices();
  std::vector<float> out(xyz, xyz + 3 * n);
  const auto sn = static_cast<std::int64_t>(n);
#pragma omp parallel num_threads(usableThreads(num_threads))
  {
    Rings rings(n);
    double rms = 0.0;
#pragma omp for schedule(static, 1024)
    for (std::int64_t sp = 0; sp < sn; ++sp) {
      const auto p = static_cast<std::uint32_t>(sp);
      if (fits && p % kStride == 0 && fits->state[p / kStride] != 0) { // fitted already
        if (fits->state[p / kStride] == 1)
          std::copy_n(&fits->projected[3 * (p / kStride)], 3, &out[3 * p]);
        continue;
      }
      rings.collect(graph, p);
      if (const std::optional<Plane> plane = ringPlane(xyz, rings.ring2(), rms))
        projectOnto(xyz, p, *plane, &out[3 * p]);
    }
  }
  return out;
}

std::vector<float> neighbourhoodMean(const CsrGraph& graph, const std::vector<float>& values,
                                     unsigned num_threads) {
  const std::size_t n = graph.numVertices();
  std::vector<float> out(n);
  const auto sn = static_cast<std::int64_t>(n);
#pragma omp parallel for num_threads(usableThreads(num_threads)) schedule(static, 4096)
  for (std::int64_t sp = 0; sp < sn; ++sp) {
    const auto p = static_cast<std::uint32_t>(sp);
    double sum = values[p];
    for (std::uint32_t e = graph.offsets[p]; e < graph.offsets[p + 1]; ++e)
      sum += values[graph.targets[e]];
    out[p] = static_cast<float>(sum / (1.0 + graph.degree(p)));
  }
  return out;
}

} // namespace pcl_ncut_seg
