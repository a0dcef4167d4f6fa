// Single views and their rims (see core/views/single_view.h).
#include "core/views/single_view.h"
#include "core/common/radix_sort.h"
#include "core/common/threads.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>

namespace pcl_ncut_seg {

namespace {

constexpr double kPi = 3.14159265358979323846;
// A camera or a scanner's sector sees less than a hemisphere around its mean direction; a
// closed object around the sensor fills every direction.
const double kMinCosOffMean = std::cos(80.0 * kPi / 180.0);
// Two ranges in one cell are two layers beyond this many edge lengths: a sensor's range noise,
// a surface's slope across one cell and a step the graph bridges stay below it.
constexpr float kLayerGap = 5.0f;
// A few hidden-surface cells can be flying pixels; a surface seen from behind fills many.
constexpr double kMaxLayeredFraction = 0.02;
// pcl::BoundaryEstimation's default angle threshold.
constexpr float kRimGap = static_cast<float>(kPi / 2.0);

/// Points as seen from the origin: unit direction (3 floats) and range of each.
struct Rays {
  std::vector<float> dir, range;
};

/// False when a point is at the origin (it has no direction) or not finite.
bool raysFrom(const float* xyz, std::size_t n, const float origin[3], Rays& rays) {
  rays.dir.resize(3 * n);
  rays.range.resize(n);
  for (std::size_t p = 0; p < n; ++p) {
    double d[3], r2 = 0.0;
    for (int c = 0; c < 3; ++c) {
      d[c] = static_cast<double>(xyz[3 * p + c]) - origin[c];
      r2 += d[c] * d[c];
    }
    const double r = std::sqrt(r2);
    if (!(r > 0.0) || !std::isfinite(r))
      return false;
    for (int c = 0; c < 3; ++c)
      rays.dir[3 * p + c] = static_cast<float>(d[c] * (1.0 / r));
    rays.range[p] = static_cast<float>(r);
  }
  return true;
}

/// The unit mean of the directions (summed in vertex order: the same for any threads); false
/// when they cancel out.
bool meanDirection(const Rays& rays, double m[3]) {
  m[0] = m[1] = m[2] = 0.0;
  for (std::size_t i = 0; i < rays.dir.size(); i += 3)
    for (int c = 0; c < 3; ++c)
      m[c] += rays.dir[i + c];
  const double norm = std::sqrt(m[0] * m[0] + m[1] * m[1] + m[2] * m[2]);
  if (!(norm > 1e-9 * static_cast<double>(rays.range.size())))
    return false;
  for (int c = 0; c < 3; ++c)
    m[c] /= norm;
  return true;
}

/// Rule 1a: every direction within 80 degrees of the mean m.
bool withinCone(const Rays& rays, const double m[3]) {
  for (std::size_t i = 0; i < rays.dir.size(); i += 3)
    if (!(rays.dir[i] * m[0] + rays.dir[i + 1] * m[1] + rays.dir[i + 2] * m[2] >= kMinCosOffMean))
      return false;
  return true;
}

/// Vectors e1, e2 across the unit vector d, orthogonal and of equal length (at least 0.8; not
/// normalised, as what they measure here does not depend on the scale).
template <typename T> void frameAcross(const T d[3], T e1[3], T e2[3]) {
  // Cross d with the axis it is least aligned with: far from parallel.
  const int c = std::abs(d[0]) <= std::abs(d[1]) ? (std::abs(d[0]) <= std::abs(d[2]) ? 0 : 2)
                                                 : (std::abs(d[1]) <= std::abs(d[2]) ? 1 : 2);
  T axis[3] = {0, 0, 0};
  axis[c] = 1;
  e1[0] = d[1] * axis[2] - d[2] * axis[1];
  e1[1] = d[2] * axis[0] - d[0] * axis[2];
  e1[2] = d[0] * axis[1] - d[1] * axis[0];
  e2[0] = d[1] * e1[2] - d[2] * e1[1];
  e2[1] = d[2] * e1[0] - d[0] * e1[2];
  e2[2] = d[0] * e1[1] - d[1] * e1[0];
}

/// A neighbour's direction across p's ray: its pseudo-angle and its components (a, b).
struct Bearing {
  float angle, a, b;
};

/// The diamond angle of (a, b) != 0: in [0, 4], increasing with the true angle at 1/2 to 1
/// times its rate (radians), so a turn of t is a true turn between t and 2 t. No atan2.
float pseudoAngle(float a, float b) {
  const float x = std::abs(a), y = std::abs(b), r = y / (x + y);
  if (b >= 0.0f)
    return a >= 0.0f ? r : 2.0f - r;
  return a < 0.0f ? 2.0f + r : 4.0f - r;
}

/// The bearings around a vertex in 16 bins of pseudo-angle, the first and last of each: a bin
/// spans at most half a radian, so a gap above pi / 2 between consecutive bearings runs from a
/// bin's last to the next occupied bin's first. Linear in the bearings: no sort.
class Gaps {
public:
  void add(float a, float b) {
    const Bearing x{pseudoAngle(a, b), a, b};
    const unsigned bin = std::min(15u, static_cast<unsigned>(4.0f * x.angle));
    if (!(used_ >> bin & 1u) || x.angle < first_[bin].angle)
      first_[bin] = x;
    if (!(used_ >> bin & 1u) || x.angle > last_[bin].angle)
      last_[bin] = x;
    used_ |= 1u << bin;
  }

  /// Whether the widest gap exceeds pi / 2 (or there is no bearing).
  bool wide() const {
    for (unsigned i = 0; i < 16; ++i) {
      if (!(used_ >> i & 1u))
        continue;
      unsigned j = (i + 1) % 16;
      while (!(used_ >> j & 1u))
        j = (j + 1) % 16;
      const Bearing &s = last_[i], &t = first_[j];
      const float turn = t.angle - s.angle + (j <= i ? 4.0f : 0.0f);
      // A turn above pi / 2 is surely wider; below it the gap is at most pi, where the signs
      // of the cross and dot products tell exactly whether it exceeds pi / 2.
      if (turn > kRimGap || s.a * t.b - s.b * t.a < 0.0f || s.a * t.a + s.b * t.b < 0.0f)
        return true;
    }
    return used_ == 0;
  }

private:
  Bearing first_[16], last_[16];
  unsigned used_ = 0;
};

/// The sector of the bearing (a, b) as a bit: 16 sectors counter-clockwise, 22.5 degrees each,
/// closed (bit i: from 22.5 i to 22.5 (i + 1) degrees).
unsigned sectorBit(float a, float b) {
  // By: a < 0, b < 0, |a| < |b|, and the smaller of |a|, |b| below tan(22.5) times the larger.
  static constexpr std::uint16_t kBit[16] = {
      1u << 1, 1u << 0, 1u << 2, 1u << 3, 1u << 14, 1u << 15, 1u << 13, 1u << 12,
      1u << 6, 1u << 7, 1u << 5, 1u << 4, 1u << 9,  1u << 8,  1u << 10, 1u << 11};
  const float x = std::abs(a), y = std::abs(b);
  const bool low = std::min(x, y) < 0.41421356f * std::max(x, y);
  return kBit[(a < 0.0f) << 3 | (b < 0.0f) << 2 | (x < y) << 1 | low];
}

/// The bearings of p's neighbours (its graph neighbours, or theirs as well) across its ray.
class Around {
public:
  Around(const CsrGraph& graph, const float* xyz, const Rays& rays, std::uint32_t p)
      : graph_(graph), xyz_(xyz), p_(p) {
    frameAcross(&rays.dir[3 * p], e1_, e2_);
  }

  /// Whether v's neighbours' bearings surely leave no gap above 90 degrees: they leave no 3
  /// neighbouring sectors empty, so a gap spans at most 4 (cheap; most vertices end here).
  bool closedSectors(std::uint32_t v, unsigned& sectors) const {
    for (std::uint32_t e = graph_.offsets[v]; e < graph_.offsets[v + 1]; ++e) {
      float a, b;
      if (bearing(graph_.targets[e], a, b)) {
        sectors |= sectorBit(a, b);
        const unsigned empty = ~sectors & 0xffffu, twice = empty | empty << 16;
        if ((twice & twice >> 1 & twice >> 2 & 0xffffu) == 0)
          return true;
      }
    }
    return false;
  }

  /// Adds v's neighbours' bearings to gaps.
  void addTo(std::uint32_t v, Gaps& gaps) const {
    for (std::uint32_t e = graph_.offsets[v]; e < graph_.offsets[v + 1]; ++e) {
      float a, b;
      if (bearing(graph_.targets[e], a, b))
        gaps.add(a, b);
    }
  }

private:
  /// q's bearing (a, b); false when q is on p's ray (p itself): no direction in the image.
  bool bearing(std::uint32_t q, float& a, float& b) const {
    const float* x = xyz_ + 3 * p_;
    const float* y = xyz_ + 3 * q;
    const float w[3] = {y[0] - x[0], y[1] - x[1], y[2] - x[2]};
    a = w[0] * e1_[0] + w[1] * e1_[1] + w[2] * e1_[2];
    b = w[0] * e2_[0] + w[1] * e2_[1] + w[2] * e2_[2];
    return a != 0.0f || b != 0.0f;
  }

  const CsrGraph& graph_;
  const float* xyz_;
  std::uint32_t p_;
  float e1_[3], e2_[3];
};

/// Rule 2 at vertex p: its neighbours projected along its ray onto the plane across it. For a
/// height field over the image that is the image plane at p, where the view's rim is exact.
/// Where the graph's neighbours all lie on one side only because the sampling is sparser that
/// way (a surface turning away from the sensor is foreshortened), their neighbours reach on.
bool onRim(const CsrGraph& graph, const float* xyz, const Rays& rays, std::uint32_t p) {
  if (graph.degree(p) < 3)
    return true;
  const Around around(graph, xyz, rays, p);
  unsigned sectors = 0;
  if (around.closedSectors(p, sectors))
    return false;
  Gaps gaps;
  around.addTo(p, gaps);
  if (!gaps.wide())
    return false;
  for (std::uint32_t e = graph.offsets[p]; e < graph.offsets[p + 1]; ++e)
    if (around.closedSectors(graph.targets[e], sectors))
      return false;
  for (std::uint32_t e = graph.offsets[p]; e < graph.offsets[p + 1]; ++e)
    around.addTo(graph.targets[e], gaps);
  return gaps.wide();
}

// A rim flag not decided yet, and one queued for a batch (decided: 0 or 1).
constexpr std::uint8_t kRimUnknown = 2, kRimQueued = 3;

/// Rule 2 for the vertices listed (in parallel).
void decideRim(const CsrGraph& graph, const float* xyz, const Rays& rays,
               const std::vector<std::uint32_t>& list, std::vector<std::uint8_t>& rim,
               int threads) {
  const auto sn = static_cast<std::int64_t>(list.size());
#pragma omp parallel for num_threads(threads) schedule(static, 256)
  for (std::int64_t i = 0; i < sn; ++i)
    rim[list[i]] = onRim(graph, xyz, rays, list[i]) ? 1 : 0;
}

/// Per vertex, the point in the image plane across the mean direction m (gnomonic: u = d.e1 /
/// d.m, v = d.e2 / d.m; a pinhole camera's pixels along m lie on a square grid there).
std::vector<float> imagePoints(const Rays& rays, const double m[3]) {
  double e1[3], e2[3];
  frameAcross(m, e1, e2);
  const std::size_t n = rays.range.size();
  std::vector<float> uv(2 * n);
  for (std::size_t p = 0; p < n; ++p) {
    const float* d = &rays.dir[3 * p];
    const double z = d[0] * m[0] + d[1] * m[1] + d[2] * m[2]; // > 0.17 by rule 1a
    uv[2 * p] = static_cast<float>((d[0] * e1[0] + d[1] * e1[1] + d[2] * e1[2]) / z);
    uv[2 * p + 1] = static_cast<float>((d[0] * e2[0] + d[1] * e2[1] + d[2] * e2[2]) / z);
  }
  return uv;
}

/// p's mean graph edge length (its edges summed in order); +infinity below 3 neighbours (such a
/// vertex is on the rim, rule 2).
float meanEdge(const CsrGraph& graph, std::uint32_t p) {
  if (graph.degree(p) < 3)
    return std::numeric_limits<float>::infinity();
  float sum = 0.0f;
  for (std::uint32_t e = graph.offsets[p]; e < graph.offsets[p + 1]; ++e)
    sum += graph.lengths[e];
  return sum / static_cast<float>(graph.degree(p));
}

/// Whether p and its graph neighbours are off the rim (it lies inside its layer's image); their
/// flags decided.
bool inside(const CsrGraph& graph, const std::vector<std::uint8_t>& rim, std::uint32_t p) {
  if (rim[p])
    return false;
  for (std::uint32_t e = graph.offsets[p]; e < graph.offsets[p + 1]; ++e)
    if (rim[graph.targets[e]])
      return false;
  return true;
}

/// The cells' size: about a point spacing in the image plane, the median over vertices (at most
/// about 32,768, evenly spread in vertex order: a median needs no more) of the root mean square
/// of their edge lengths there; 0 when no edge crosses the rays.
double cellSize(const CsrGraph& graph, const std::vector<float>& uv) {
  std::vector<float> length;
  const std::size_t stride = 1 + graph.numVertices() / 32768;
  for (std::size_t p = 0; p < graph.numVertices(); p += stride) {
    float sum = 0.0f;
    for (std::uint32_t e = graph.offsets[p]; e < graph.offsets[p + 1]; ++e) {
      const std::uint32_t q = graph.targets[e];
      const float du = uv[2 * q] - uv[2 * p], dv = uv[2 * q + 1] - uv[2 * p + 1];
      sum += du * du + dv * dv;
    }
    if (sum > 0.0f)
      length.push_back(std::sqrt(sum / graph.degree(static_cast<std::uint32_t>(p))));
  }
  if (length.empty())
    return 0.0;
  const auto mid = length.begin() + length.size() / 2;
  std::nth_element(length.begin(), mid, length.end());
  return *mid;
}

/// Per vertex its cell of size h in the image plane, as one 32-bit key. The cells double in
/// size until their rectangle has fewer than 2^32 (only for spread, very dense points).
std::vector<std::uint32_t> cellKeys(const std::vector<float>& uv, double h) {
  const std::size_t n = uv.size() / 2;
  float lo[2] = {uv[0], uv[1]}, hi[2] = {uv[0], uv[1]};
  for (std::size_t i = 0; i < 2 * n; ++i) {
    lo[i % 2] = std::min(lo[i % 2], uv[i]);
    hi[i % 2] = std::max(hi[i % 2], uv[i]);
  }
  double width, height;
  for (;; h *= 2.0) {
    width = std::floor((double(hi[0]) - lo[0]) / h) + 1.0;
    height = std::floor((double(hi[1]) - lo[1]) / h) + 1.0;
    if (width * height < 4294967296.0)
      break;
  }
  std::vector<std::uint32_t> key(n);
  for (std::size_t p = 0; p < n; ++p) {
    // Non-negative: truncation is the floor.
    const auto i = static_cast<std::uint32_t>((double(uv[2 * p]) - lo[0]) / h);
    const auto j = static_cast<std::uint32_t>((double(uv[2 * p + 1]) - lo[1]) / h);
    key[p] = static_cast<std::uint32_t>(i * static_cast<std::uint64_t>(height) + j);
  }
  return key;
}

/// Whether the size points of a cell hold two layers: two points inside their layers whose
/// ranges differ by more than kLayerGap of their mean edges. Their and their neighbours' rim
/// flags decided.
bool cellLayered(const CsrGraph& graph, const Rays& rays, const std::vector<float>& edge,
                 const std::vector<std::uint8_t>& rim, const std::uint32_t* cell,
                 std::size_t size) {
  std::uint32_t nearest = cell[0], farthest = cell[0];
  bool any = false;
  for (std::size_t i = 0; i < size; ++i) {
    const std::uint32_t p = cell[i];
    if (!inside(graph, rim, p))
      continue;
    if (!any || rays.range[p] < rays.range[nearest])
      nearest = p;
    if (!any || rays.range[p] > rays.range[farthest])
      farthest = p;
    any = true;
  }
  return any && rays.range[farthest] - rays.range[nearest] >
                    kLayerGap * std::max(edge[nearest], edge[farthest]);
}

/// Rule 1b: whether more than 2% of the occupied cells hold two layers (cellLayered()). A
/// surface seen through another has such cells all over. Where one surface of a view hides
/// another, both end (rim), and points inside them, a graph step or more in on either side, lie
/// farther apart across the image than a cell spans.
/// Only cells whose ranges spread by more than kLayerGap of their least mean edge can hold two
/// layers; they are counted in batches of growing size, rule 2 decided for their points and
/// their neighbours alone, and the count stops once it passes 2%: a closed surface seen from
/// outside is told after a few percent of its rim flags. rim: per vertex kRimUnknown, or
/// decided, and filled where decided here.
bool twoLayered(const CsrGraph& graph, const float* xyz, const Rays& rays,
                const std::vector<std::uint32_t>& key, std::vector<std::uint8_t>& rim,
                int threads) {
  const std::size_t n = key.size();
  std::vector<float> edge(n);
  for (std::uint32_t p = 0; p < n; ++p)
    edge[p] = meanEdge(graph, p);
  const std::vector<std::uint32_t> order = stableOrderByKey(key);
  std::vector<std::size_t> cell_begin; // of the cells that may hold two layers, and their ends
  std::vector<std::size_t> cell_end;
  std::size_t occupied = 0;
  for (std::size_t begin = 0, end = 0; begin < n; begin = end, ++occupied) {
    float lo = rays.range[order[begin]], hi = lo, least = edge[order[begin]];
    for (end = begin; end < n && key[order[end]] == key[order[begin]]; ++end) {
      const std::uint32_t p = order[end];
      lo = std::min(lo, rays.range[p]);
      hi = std::max(hi, rays.range[p]);
      least = std::min(least, edge[p]);
    }
    if (hi - lo > kLayerGap * least) {
      cell_begin.push_back(begin);
      cell_end.push_back(end);
    }
  }
  const double most = kMaxLayeredFraction * static_cast<double>(occupied);
  std::size_t layered = 0;
  std::vector<std::uint32_t> list;
  auto queue = [&](std::uint32_t v) {
    if (rim[v] == kRimUnknown) {
      rim[v] = kRimQueued;
      list.push_back(v);
    }
  };
  for (std::size_t next = 0, batch = 2 * static_cast<std::size_t>(most) + 64;
       next < cell_begin.size(); batch *= 2) {
    const std::size_t last = std::min(cell_begin.size(), next + batch);
    list.clear();
    for (std::size_t c = next; c < last; ++c)
      for (std::size_t i = cell_begin[c]; i < cell_end[c]; ++i) {
        const std::uint32_t p = order[i];
        queue(p);
        for (std::uint32_t e = graph.offsets[p]; e < graph.offsets[p + 1]; ++e)
          queue(graph.targets[e]);
      }
    decideRim(graph, xyz, rays, list, rim, threads);
    for (; next < last; ++next)
      layered += cellLayered(graph, rays, edge, rim, order.data() + cell_begin[next],
                             cell_end[next] - cell_begin[next]);
    if (static_cast<double>(layered) > most)
      return true;
  }
  return false;
}

} // namespace

std::vector<std::uint8_t> singleViewRim(const CsrGraph& graph, const float* xyz,
                                        const float origin[3], unsigned num_threads) {
  const std::size_t n = graph.numVertices();
  Rays rays;
  double m[3];
  if (n < 3 || !raysFrom(xyz, n, origin, rays) || !meanDirection(rays, m) || !withinCone(rays, m))
    return {};
  const int threads = usableThreads(num_threads);
  const std::vector<float> uv = imagePoints(rays, m);
  const double h = cellSize(graph, uv);
  // No spacing across the rays: the points line up along them, no surface is seen.
  if (!(h > 0.0))
    return {};
  std::vector<std::uint8_t> rim(n, kRimUnknown);
  if (twoLayered(graph, xyz, rays, cellKeys(uv, h), rim, threads))
    return {};
  const auto sn = static_cast<std::int64_t>(n);
#pragma omp parallel for num_threads(threads) schedule(static, 1024)
  for (std::int64_t p = 0; p < sn; ++p)
    if (rim[p] == kRimUnknown)
      rim[p] = onRim(graph, xyz, rays, static_cast<std::uint32_t>(p)) ? 1 : 0;
  return rim;
}

} // namespace pcl_ncut_seg
