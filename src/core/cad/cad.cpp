// Sec. 7: point-sampled CAD models. Normal smoothing, ridge distance, the transformed kNN graph,
// and the face-orientation similarity of supernodes.
#include "core/cad/cad.h"

#include "core/common/geometry.h"
#include "core/graph/shortest_paths.h"
#include "core/supernodes/refinement.h"

#include <Eigen/Dense>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <map>
#include <optional>

namespace pcl_ncut_seg {
namespace {
constexpr double kDegree = 3.14159265358979323846 / 180.0;
constexpr double kMinWeight = 1e-200; // as in supernode_graph.cpp: keeps D regular

bool usable(const float* n) {
  return std::isfinite(n[0]) && std::isfinite(n[1]) && std::isfinite(n[2]) &&
         n[0] * n[0] + n[1] * n[1] + n[2] * n[2] > 0.0f;
}
} // namespace

std::vector<float> smoothNormals(const CsrGraph& graph, const float* normals, int iterations) {
  const std::size_t n = graph.numVertices();
  std::vector<float> cur(3 * n, 0.0f), next(3 * n, 0.0f);
  for (std::size_t p = 0; p < n; ++p)
    if (usable(normals + 3 * p)) {
      const float* v = normals + 3 * p;
      const float len = std::sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
      for (int d = 0; d < 3; ++d)
        cur[3 * p + d] = v[d] / len;
    }
  for (int it = 0; it < iterations; ++it) {
    for (std::size_t p = 0; p < n; ++p) {
      const float* np = &cur[3 * p];
      double sum[3] = {np[0], np[1], np[2]};
      const bool has = np[0] != 0.0f || np[1] != 0.0f || np[2] != 0.0f;
      // The first usable normal fixes the orientation when p has none of its own.
      const float* ref = has ? np : nullptr;
      for (std::uint32_t e = graph.offsets[p]; e < graph.offsets[p + 1]; ++e) {
        const float* nq = &cur[3 * graph.targets[e]];
        if (nq[0] == 0.0f && nq[1] == 0.0f && nq[2] == 0.0f)
          continue;
        if (!ref)
          ref = nq;
        const float s = ref[0] * nq[0] + ref[1] * nq[1] + ref[2] * nq[2] < 0.0f ? -1.0f : 1.0f;
        for (int d = 0; d < 3; ++d)
          sum[d] += s * nq[d];
      }
      const double len = std::sqrt(sum[0] * sum[0] + sum[1] * sum[1] + sum[2] * sum[2]);
      for (int d = 0; d < 3; ++d)
        next[3 * p + d] = len > 0.0 ? static_cast<float>(sum[d] / len) : 0.0f;
    }
    cur.swap(next);
  }
  return cur;
}

std::vector<bool> ridgePoints(const CsrGraph& graph, const std::vector<float>& normals,
                              float ridge_angle) {
  const std::size_t n = graph.numVertices();
  std::vector<bool> ridge(n, false);
  const double limit = ridge_angle * kDegree;
  for (std::size_t p = 0; p < n; ++p) {
    const float* np = &normals[3 * p];
    if (np[0] == 0.0f && np[1] == 0.0f && np[2] == 0.0f)
      continue;
    double sum = 0.0;
    std::size_t count = 0;
    for (std::uint32_t e = graph.offsets[p]; e < graph.offsets[p + 1]; ++e) {
      const float* nq = &normals[3 * graph.targets[e]];
      if (nq[0] == 0.0f && nq[1] == 0.0f && nq[2] == 0.0f)
        continue;
      const double c =
          std::abs(double(np[0]) * nq[0] + double(np[1]) * nq[1] + double(np[2]) * nq[2]);
      sum += std::acos(std::min(c, 1.0)); // unoriented: the angle is at most 90 degrees
      ++count;
    }
    ridge[p] = count > 0 && sum / double(count) > limit;
  }
  return ridge;
}

std::vector<float> ridgeDistance(const CsrGraph& graph, const std::vector<bool>& ridge) {
  const std::size_t n = graph.numVertices();
  std::vector<float> phi(n, std::numeric_limits<float>::infinity());
  std::vector<std::uint32_t> sources;
  for (std::uint32_t p = 0; p < n; ++p)
    if (ridge[p]) {
      phi[p] = 0.0f;
      sources.push_back(p);
    }
  multiSourceDijkstra(graph, sources, phi.data(), AnyEdge(), ExpandAll());
  return phi;
}

CsrGraph transformGraph(const CsrGraph& graph, const std::vector<float>& phi, float shrink,
                        float stretch) {
  CsrGraph out = graph;
  const std::size_t n = graph.numVertices();
  for (std::size_t p = 0; p < n; ++p)
    for (std::uint32_t e = graph.offsets[p]; e < graph.offsets[p + 1]; ++e) {
      const float d = graph.lengths[e];
      const float a_p = phi[p], a_q = phi[graph.targets[e]];
      float a = 0.0f; // share of the edge that points away from the ridge
      if (d > 0.0f && std::isfinite(a_p) && std::isfinite(a_q))
        a = std::min(1.0f, std::abs(a_p - a_q) / d);
      out.lengths[e] = d * (shrink + (stretch - shrink) * a);
    }
  return out;
}

namespace {
/// The face normal of a supernode at its points, fitted on demand (only points on a contact
/// need one): a plane through the points of the same supernode off the ridges within kFitHops
/// kNN steps (a ridge point may lie on the other face). Zero when the fit is not planar (fewer
/// than kMinFit points, or collinear ones).
class FaceNormals {
public:
  FaceNormals(const CsrGraph& graph, const float* xyz, const std::vector<std::uint32_t>& label,
              const std::vector<bool>& ridge)
      : graph_(graph), xyz_(xyz), label_(label), ridge_(ridge), normal_(3 * graph.numVertices()),
        done_(graph.numVertices(), 0), mark_(graph.numVertices(), kNone) {}

  /// p's face normal (3 floats, zero when there is none).
  const float* at(std::uint32_t p) {
    if (!done_[p]) {
      done_[p] = 1;
      fit(p);
    }
    return &normal_[3 * p];
  }

private:
  static constexpr std::size_t kFitHops = 3, kMinFit = 6;

  void fit(std::uint32_t p) {
    ring_.clear();
    ring_.push_back(p);
    mark_[p] = p;
    for (std::size_t step = 0, begin = 0; step < kFitHops; ++step) {
      const std::size_t end = ring_.size();
      for (std::size_t i = begin; i < end; ++i) {
        const std::uint32_t v = ring_[i];
        for (std::uint32_t e = graph_.offsets[v]; e < graph_.offsets[v + 1]; ++e) {
          const std::uint32_t q = graph_.targets[e];
          if (label_[q] == label_[p] && mark_[q] != p) {
            mark_[q] = p;
            ring_.push_back(q);
          }
        }
      }
      begin = end;
    }
    fit_.clear();
    for (std::uint32_t v : ring_)
      if (ridge_.empty() || !ridge_[v])
        fit_.push_back(v);
    if (fit_.size() < kMinFit)
      return;
    const std::optional<Plane> plane =
        fitPlane(centredScatter(xyz_, fit_), kFaceFlatness, EigenSolve::kIterative);
    if (!plane)
      return;
    for (int d = 0; d < 3; ++d)
      normal_[3 * p + d] = static_cast<float>(plane->normal[d]);
  }

  const CsrGraph& graph_;
  const float* xyz_;
  const std::vector<std::uint32_t>& label_;
  const std::vector<bool>& ridge_;
  std::vector<float> normal_;
  std::vector<char> done_;
  std::vector<std::uint32_t> mark_, ring_, fit_;
};

bool isZero(const float* v) {
  return v[0] == 0.0f && v[1] == 0.0f && v[2] == 0.0f;
}

/// The median of values (reordered); 90 degrees for none. A few contact edges through points
/// that belong to neither face must not decide.
double medianAngle(std::vector<double>& values) {
  if (values.empty())
    return 90.0;
  const std::size_t mid = values.size() / 2;
  std::nth_element(values.begin(), values.begin() + mid, values.end());
  double median = values[mid];
  if (values.size() % 2 == 0)
    median = 0.5 * (median + *std::max_element(values.begin(), values.begin() + mid));
  return median;
}
} // namespace

std::map<std::pair<std::uint32_t, std::uint32_t>, double>
faceContactAngles(const CsrGraph& graph, const float* xyz, const std::vector<std::uint32_t>& label,
                  const std::vector<bool>& ridge) {
  const std::size_t n = graph.numVertices();
  FaceNormals normals(graph, xyz, label, ridge);
  std::map<std::pair<std::uint32_t, std::uint32_t>, std::vector<double>> samples;
  for (std::uint32_t p = 0; p < n; ++p)
    for (std::uint32_t e = graph.offsets[p]; e < graph.offsets[p + 1]; ++e) {
      const std::uint32_t q = graph.targets[e];
      if (label[q] <= label[p])
        continue; // each contact edge once, from its smaller label's side
      auto& entry = samples[{label[p], label[q]}];
      const float* a = normals.at(p);
      const float* b = normals.at(q);
      if (isZero(a) || isZero(b))
        continue;
      const double c = std::abs(double(a[0]) * b[0] + double(a[1]) * b[1] + double(a[2]) * b[2]);
      entry.push_back(std::acos(std::min(c, 1.0)) / kDegree);
    }
  std::map<std::pair<std::uint32_t, std::uint32_t>, double> angles;
  for (auto& [key, values] : samples)
    angles[key] = medianAngle(values);
  return angles;
}

WeightedGraph buildCadSupernodeGraph(const Supernodes& supernodes, const FeatureStats& stats,
                                     const Connectivity& conn, const Connectivity& face_angles,
                                     const SimilarityParams& params) {
  // The r_i - m_i edges of eq. (7) as in Sec. 5.1; the member edges are replaced.
  SimilarityParams base = params;
  base.adjacency = Adjacency::Saddles; // the member edges are replaced below
  WeightedGraph g = buildSupernodeGraph(supernodes, stats, conn, base);
  const auto l = static_cast<std::uint32_t>(supernodes.size());
  g.edges.erase(std::remove_if(g.edges.begin(), g.edges.end(),
                               [l](const WeightedGraph::Edge& edge) { return edge.a >= l; }),
                g.edges.end());
  // Sec. 7: supernodes are similar when the faces they represent have the same orientation
  // where they meet; every touching pair gets an edge, so a face split into several
  // supernodes is held together whether or not they met at a saddle.
  std::vector<double> boundary(l, 0.0); // conn of each supernode with all others
  for (const auto& [key, value] : conn)
    if (key.first != key.second) {
      boundary[key.first] += value;
      boundary[key.second] += value;
    }
  for (const auto& [key, theta] : face_angles) {
    const double x = theta / kFaceAngle;
    // ... scaled by the share of the smaller boundary they have in common (conn of eq. 8), so
    // that a short contact through a few misplaced points cannot glue two faces.
    auto it = conn.find(key);
    const double shared = it == conn.end() ? 0.0 : it->second;
    const double smaller = std::min(boundary[key.first], boundary[key.second]);
    const double w = std::exp(-x * x) * (smaller > 0.0 ? std::min(1.0, shared / smaller) : 0.0);
    g.edges.push_back({l + key.first, l + key.second, std::max(w, kMinWeight)});
  }
  return g;
}

namespace {
/// The off-ridge regions of splitAtRidges(): connected parts of a supernode's points off the
/// ridges, and the small ones merged into neighbours (a union-find over regions).
struct RidgeRegions {
  std::vector<std::uint32_t> region; ///< per vertex, its region; kNone on a ridge
  std::vector<std::uint32_t> size;   ///< per region, its points
  std::vector<std::uint32_t> target; ///< per region, the region it joined (itself: a root)
  std::vector<std::uint32_t> total;  ///< per root region, the points it holds

  std::uint32_t root(std::uint32_t i) {
    while (target[i] != i)
      i = target[i] = target[target[i]];
    return i;
  }
};

/// The connected parts of each supernode's points off the ridges (by depth-first search from
/// each unassigned point in order of ids).
RidgeRegions offRidgeRegions(const CsrGraph& graph, const std::vector<bool>& ridge,
                             const std::vector<std::uint32_t>& label) {
  const std::size_t n = graph.numVertices();
  RidgeRegions out;
  out.region.assign(n, kNone);
  std::vector<std::uint32_t> stack;
  for (std::uint32_t s = 0; s < n; ++s) {
    if (ridge[s] || out.region[s] != kNone)
      continue;
    const auto id = static_cast<std::uint32_t>(out.size.size());
    out.size.push_back(0);
    out.region[s] = id;
    stack.push_back(s);
    while (!stack.empty()) {
      const std::uint32_t v = stack.back();
      stack.pop_back();
      ++out.size[id];
      for (std::uint32_t e = graph.offsets[v]; e < graph.offsets[v + 1]; ++e) {
        const std::uint32_t q = graph.targets[e];
        if (!ridge[q] && out.region[q] == kNone && label[q] == label[v]) {
          out.region[q] = id;
          stack.push_back(q);
        }
      }
    }
  }
  out.target.resize(out.size.size());
  for (std::uint32_t i = 0; i < out.target.size(); ++i)
    out.target[i] = i;
  out.total = out.size;
  return out;
}

/// A region below min_points joins the off-ridge neighbouring region it shares most edges
/// with (the smallest first, so that chains of small regions end in a large one).
void mergeSmallRegions(const CsrGraph& graph, std::size_t min_points, RidgeRegions& regions) {
  const std::size_t r = regions.size.size();
  std::vector<std::uint32_t> order(r);
  for (std::uint32_t i = 0; i < r; ++i)
    order[i] = i;
  std::stable_sort(order.begin(), order.end(), [&](std::uint32_t a, std::uint32_t b) {
    return regions.size[a] < regions.size[b];
  });
  std::vector<std::vector<std::uint32_t>> members(r);
  for (std::uint32_t p = 0; p < regions.region.size(); ++p)
    if (regions.region[p] != kNone)
      members[regions.region[p]].push_back(p);
  for (std::uint32_t i : order) {
    if (regions.root(i) != i || regions.total[i] >= min_points)
      continue;
    std::map<std::uint32_t, std::size_t> shared;
    for (std::uint32_t p : members[i])
      for (std::uint32_t e = graph.offsets[p]; e < graph.offsets[p + 1]; ++e) {
        const std::uint32_t q = graph.targets[e];
        if (regions.region[q] != kNone && regions.root(regions.region[q]) != i)
          ++shared[regions.root(regions.region[q])];
      }
    std::uint32_t best = kNone;
    std::size_t best_count = 0;
    for (const auto& [j, count] : shared)
      if (count > best_count)
        best = j, best_count = count;
    if (best == kNone)
      continue; // enclosed by ridges: stays on its own
    regions.target[i] = best;
    regions.total[best] += regions.total[i];
    members[best].insert(members[best].end(), members[i].begin(), members[i].end());
    members[i].clear();
  }
}

/// The points that join a region by distance: the ridge points, and the points of a region
/// enclosed by ridges and smaller than two kNN neighbourhoods (twice the mean |N(p)|), a gap in
/// a ridge rather than a face.
std::vector<bool> loosePoints(const CsrGraph& graph, const std::vector<bool>& ridge,
                              RidgeRegions& regions) {
  const std::size_t n = graph.numVertices();
  const double tiny = n > 0 ? 2.0 * double(graph.numDirectedEdges()) / double(n) : 0.0;
  std::vector<bool> loose(ridge);
  for (std::uint32_t p = 0; p < n; ++p)
    if (regions.region[p] != kNone && regions.total[regions.root(regions.region[p])] < tiny)
      loose[p] = true;
  return loose;
}

/// Per vertex, the nearest region on the graph (a multi-source search from the regions'
/// points; kNone where none is reachable).
std::vector<std::uint32_t> nearestRegion(const CsrGraph& graph, const std::vector<bool>& loose,
                                         RidgeRegions& regions) {
  const std::size_t n = graph.numVertices();
  std::vector<float> dist(n, std::numeric_limits<float>::infinity());
  std::vector<std::uint32_t> owner(n, kNone), sources;
  for (std::uint32_t p = 0; p < n; ++p)
    if (!loose[p]) {
      owner[p] = regions.root(regions.region[p]);
      dist[p] = 0.0f;
      sources.push_back(p);
    }
  multiSourceDijkstra(graph, sources, dist.data(), AnyEdge(), ExpandAll(), owner.data());
  return owner;
}

/// Each loose point joins the face it lies on: among the regions that own a point within a few
/// kNN steps, the one whose plane, fitted to its off-ridge points there, passes nearest (the
/// nearest region alone would cut the corner of an acute face). Returns the owners refined.
std::vector<std::uint32_t> ridgePointFaces(const CsrGraph& graph, const float* xyz,
                                           const std::vector<bool>& loose,
                                           const std::vector<std::uint32_t>& owner) {
  constexpr int kHops = 4;
  constexpr std::size_t kMinFit = 6;
  const std::size_t n = graph.numVertices();
  std::vector<std::uint32_t> refined(owner);
  std::vector<std::uint32_t> seen(n, kNone), ring;
  std::map<std::uint32_t, std::vector<std::uint32_t>> near;
  for (std::uint32_t p = 0; p < n; ++p) {
    if (!loose[p] || owner[p] == kNone)
      continue;
    ring.assign(1, p);
    seen[p] = p;
    near.clear();
    for (int hop = 0, begin = 0; hop < kHops; ++hop) {
      const int end = static_cast<int>(ring.size());
      for (int i = begin; i < end; ++i)
        for (std::uint32_t e = graph.offsets[ring[i]]; e < graph.offsets[ring[i] + 1]; ++e) {
          const std::uint32_t q = graph.targets[e];
          if (seen[q] == p)
            continue;
          seen[q] = p;
          ring.push_back(q);
          if (!loose[q])
            near[owner[q]].push_back(q);
        }
      begin = end;
    }
    double best = std::numeric_limits<double>::infinity();
    const Eigen::Vector3d at(xyz[3 * p], xyz[3 * p + 1], xyz[3 * p + 2]);
    for (const auto& [region_id, points] : near) {
      if (points.size() < kMinFit)
        continue;
      const std::optional<Plane> plane =
          fitPlane(centredScatter(xyz, points), kFaceFlatness, EigenSolve::kIterative);
      if (!plane)
        continue; // collinear: no plane
      const double distance = std::abs(plane->normal.dot(at - plane->centroid));
      if (distance < best) {
        best = distance;
        refined[p] = region_id;
      }
    }
  }
  return refined;
}
} // namespace

Supernodes splitAtRidges(const CsrGraph& graph, const float* xyz, const std::vector<bool>& ridge,
                         const std::vector<std::uint32_t>& label, std::size_t min_points) {
  const std::size_t n = graph.numVertices();
  RidgeRegions regions = offRidgeRegions(graph, ridge, label);
  mergeSmallRegions(graph, min_points, regions);
  const std::vector<bool> loose = loosePoints(graph, ridge, regions);
  const std::vector<std::uint32_t> owner =
      ridgePointFaces(graph, xyz, loose, nearestRegion(graph, loose, regions));
  // Compact ids in order of each supernode's first point, which is its origin; a component
  // made of ridge points only keeps its old supernode (its key follows the regions' keys).
  const auto num_regions = static_cast<std::uint32_t>(regions.size.size());
  std::uint32_t num_labels = 0;
  std::vector<std::uint32_t> key(n);
  for (std::uint32_t p = 0; p < n; ++p) {
    key[p] = owner[p] != kNone ? owner[p] : num_regions + label[p];
    num_labels = std::max(num_labels, label[p] + 1);
  }
  Supernodes out;
  std::vector<std::uint32_t> id;
  out.origin = compactLabels(key, std::size_t{num_regions} + num_labels, id, out.label);
  out.at_saddle.assign(out.origin.size(), false);
  out.parent.assign(out.origin.size(), kNone);
  out.children.assign(out.origin.size(), {});
  return out;
}

CadGraph cadGraph(const CsrGraph& graph, const float* normals, float ridge_angle) {
  CadGraph out;
  const std::vector<float> smoothed = smoothNormals(graph, normals, kCadSmoothingIterations);
  out.ridge = ridgePoints(graph, smoothed, ridge_angle);
  const std::vector<float> phi = ridgeDistance(graph, out.ridge);
  out.graph = transformGraph(graph, phi, kRidgeShrink, kRidgeStretch);
  return out;
}

void cadFaces(Analysis& a, const CsrGraph& graph, const float* xyz, const std::vector<bool>& ridge,
              float area_fraction) {
  a.cad = true;
  // Faces end at ridges: no supernode crosses one (Sec. 7, "ridges to feature boundaries").
  const std::size_t min_points =
      static_cast<std::size_t>(std::ceil(area_fraction * double(graph.numVertices())));
  a.supernodes = splitAtRidges(graph, xyz, ridge, a.supernodes.label, min_points);
  a.stats = featureStats(a.supernodes, a.centrality.f, a.radii);
  a.conn = supernodeConnectivity(*a.graph, a.centrality.f, a.supernodes.label);
  a.face_angles = faceContactAngles(*a.graph, xyz, a.supernodes.label, ridge);
}

} // namespace pcl_ncut_seg
