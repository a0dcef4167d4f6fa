// The surface's local thickness from medial balls (an extension of Sec. 5.1).
#include "core/cut/thickness.h"
#include "core/common/threads.h"
#include "core/graph/subsample.h"

#include <flann/algorithms/dist.h>
#include <flann/algorithms/kdtree_single_index.h>
#include <flann/util/result_set.h>

#include <algorithm>
#include <cmath>
#include <limits>

namespace pcl_ncut_seg {

namespace {
using Index = flann::KDTreeSingleIndex<flann::L2_Simple<float>>;

constexpr int kMaxShrinks = 30;
// A refined supernode holds at least 1% of the area (Sec. 4.3's small supernodes are merged):
// about 80 probes of an even subset of this many, enough for its median.
constexpr std::size_t kThicknessProbes = 8192;
// A ball whose new contact q is seen from its centre within this angle of p is shrinking to
// the noise of p's own neighbourhood, not to the far side (Ma et al.'s denoising angle).
const double kMinSeparation = std::cos(M_PI / 8.0);

double dot3(const double* a, const double* b) {
  return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}

/// The cloud's bounding-box diagonal: no medial ball of a closed surface is larger.
double diagonal(const float* xyz, std::size_t n) {
  double lo[3], hi[3];
  for (int d = 0; d < 3; ++d)
    lo[d] = hi[d] = xyz[d];
  for (std::size_t i = 0; i < n; ++i)
    for (int d = 0; d < 3; ++d) {
      lo[d] = std::min(lo[d], static_cast<double>(xyz[3 * i + d]));
      hi[d] = std::max(hi[d], static_cast<double>(xyz[3 * i + d]));
    }
  return std::sqrt((hi[0] - lo[0]) * (hi[0] - lo[0]) + (hi[1] - lo[1]) * (hi[1] - lo[1]) +
                   (hi[2] - lo[2]) * (hi[2] - lo[2]));
}

/// The nearest point other than p strictly inside a ball: FLANN prunes every cell farther than
/// the ball (or than the nearest found so far), so a query costs what the ball covers. Of two
/// at the same distance, the one first by position (x, then y, then z): the point order does
/// not choose.
class NearestInBall : public flann::ResultSet<float> {
public:
  explicit NearestInBall(const float* xyz) : xyz_(xyz) {}
  void reset(float squared_radius, std::size_t excluded) {
    setBest(squared_radius);
    index_ = kNoPoint;
    excluded_ = excluded;
  }
  bool full() const override { return true; }
  void addPoint(float dist, std::size_t index) override {
    if (index == excluded_ || dist > best_ || (dist == best_ && !before(index)))
      return;
    setBest(dist);
    index_ = index;
  }
  /// A hair above the best, so that FLANN still offers points at the same distance. (FLANN
  /// asks at every cell: kept, not computed.)
  float worstDist() const override { return worst_; }
  static constexpr std::size_t kNoPoint = static_cast<std::size_t>(-1);
  std::size_t index_ = kNoPoint;

private:
  bool before(std::size_t index) const {
    if (index_ == kNoPoint)
      return false; // at the ball's own radius: on its sphere, not inside
    return std::lexicographical_compare(xyz_ + 3 * index, xyz_ + 3 * index + 3, xyz_ + 3 * index_,
                                        xyz_ + 3 * index_ + 3);
  }
  void setBest(float best) {
    best_ = best;
    worst_ = std::nextafter(best, std::numeric_limits<float>::infinity());
  }
  const float* xyz_;
  float best_ = 0.0f, worst_ = 0.0f;
  std::size_t excluded_ = kNoPoint;
};

/// One point's shrinking ball; NaN for a zero normal or an open side.
float shrinkBall(const Index& index, const float* xyz, const float* normal, std::size_t i,
                 double r_max, NearestInBall& inside) {
  const double p[3] = {xyz[3 * i], xyz[3 * i + 1], xyz[3 * i + 2]};
  const double m[3] = {-normal[0], -normal[1], -normal[2]}; // inward
  if (!(dot3(m, m) > 0.5))
    return std::numeric_limits<float>::quiet_NaN();
  const flann::SearchParams params(-1, 0.0f, false);
  double r = r_max;
  for (int it = 0; it < kMaxShrinks; ++it) {
    const float c[3] = {static_cast<float>(p[0] + r * m[0]), static_cast<float>(p[1] + r * m[1]),
                        static_cast<float>(p[2] + r * m[2])};
    // Points within a hair of the sphere count as on it, not inside.
    inside.reset(static_cast<float>(r * r * (1.0 - 1e-5)), i);
    index.findNeighbors(inside, c, params);
    if (inside.index_ == NearestInBall::kNoPoint)
      break; // no point inside the ball
    const float* q = xyz + 3 * inside.index_;
    const double pq[3] = {q[0] - p[0], q[1] - p[1], q[2] - p[2]};
    const double along = dot3(m, pq);
    if (!(along > 0.0))
      break;
    const double r_new = dot3(pq, pq) / (2.0 * along);
    // The angle at the new centre between p and q.
    const double cp[3] = {-r_new * m[0], -r_new * m[1], -r_new * m[2]};
    const double cq[3] = {pq[0] + cp[0], pq[1] + cp[1], pq[2] + cp[2]};
    if (!(r_new < r) || dot3(cp, cq) / (r_new * r_new) > kMinSeparation)
      break;
    r = r_new;
  }
  return r >= r_max ? std::numeric_limits<float>::quiet_NaN() : static_cast<float>(r);
}
} // namespace

std::vector<float> medialRadii(const float* xyz, std::size_t n, const std::vector<float>& normals,
                               unsigned num_threads) {
  std::vector<float> radii(n, std::numeric_limits<float>::quiet_NaN());
  if (n < 2 || normals.size() < 3 * n)
    return radii;
  // The probes: an even subset, whose balls shrink to every point (a large ball costs a search
  // over every cell near its sphere).
  const std::vector<char> probe = evenSubset(xyz, n, kThicknessProbes);
  Index index(flann::Matrix<float>(const_cast<float*>(xyz), n, 3),
              flann::KDTreeSingleIndexParams(15));
  index.buildIndex();
  const double r_max = diagonal(xyz, n);
#pragma omp parallel num_threads(usableThreads(num_threads))
  {
    NearestInBall inside(xyz);
#pragma omp for schedule(dynamic, 256)
    for (std::ptrdiff_t qi = 0; qi < static_cast<std::ptrdiff_t>(n); ++qi) {
      const auto i = static_cast<std::size_t>(qi);
      if (probe[i])
        radii[i] = shrinkBall(index, xyz, normals.data() + 3 * i, i, r_max, inside);
    }
  }
  return radii;
}

std::vector<float> supernodeThickness(const std::vector<float>& radii,
                                      const std::vector<std::uint32_t>& label,
                                      std::size_t num_supernodes) {
  std::vector<std::vector<float>> members(num_supernodes);
  for (std::size_t p = 0; p < label.size() && p < radii.size(); ++p)
    if (label[p] < num_supernodes && std::isfinite(radii[p]))
      members[label[p]].push_back(radii[p]);
  std::vector<float> thickness(num_supernodes, std::numeric_limits<float>::quiet_NaN());
  for (std::size_t s = 0; s < num_supernodes; ++s) {
    std::vector<float>& v = members[s];
    if (v.empty())
      continue;
    std::nth_element(v.begin(), v.begin() + v.size() / 2, v.end());
    thickness[s] = v[v.size() / 2];
  }
  return thickness;
}

} // namespace pcl_ncut_seg
