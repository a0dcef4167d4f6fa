// The segmentation of a plain array of points (see <pcl_ncut_seg/segment_points.h>): the
// prelude of the analysis (subset, order, neighbours, normals), then the core's pipeline.
#include <pcl_ncut_seg/segment_points.h>

#include "core/common/stopwatch.h"
#include "core/common/threads.h"
#include "core/graph/knn.h"
#include "core/graph/subsample.h"
#include "core/model/model.h"
#include "core/model/points.h"
#include "core/pipeline/pipeline.h"

#include <algorithm>
#include <array>
#include <string>

namespace pcl_ncut_seg {

struct PointSegmenter::Prepared {
  PreparedPoints points;
};

PointSegmenter::PointSegmenter()
    : prepared_(std::make_unique<Prepared>()), result_(std::make_unique<CutResult>()) {}
PointSegmenter::~PointSegmenter() = default;
PointSegmenter::PointSegmenter(const PointSegmenter& other)
    : prepared_(std::make_unique<Prepared>(*other.prepared_)), analyses_(other.analyses_),
      result_(std::make_unique<CutResult>(*other.result_)) {}
PointSegmenter::PointSegmenter(PointSegmenter&& other) noexcept : PointSegmenter() {
  *this = std::move(other);
}
PointSegmenter& PointSegmenter::operator=(const PointSegmenter& other) {
  if (this != &other)
    *this = PointSegmenter(other);
  return *this;
}
PointSegmenter& PointSegmenter::operator=(PointSegmenter&& other) noexcept {
  std::swap(prepared_, other.prepared_);
  std::swap(analyses_, other.analyses_);
  std::swap(result_, other.result_);
  return *this;
}

void PointSegmenter::reset() {
  prepared_->points = PreparedPoints();
  analyses_.reset();
  *result_ = CutResult();
}

PointSegmenter::VertexMap PointSegmenter::prepare(std::vector<float> xyz, const Parameters& params,
                                                  const float* sensor_origin) {
  reset();
  // A dense cloud: analysed at the resolution of max_points.
  PreparedPoints& prepared = prepared_->points;
  prepared = prepareAtResolution(
      std::move(xyz),
      params.graph.max_points ? static_cast<std::size_t>(*params.graph.max_points) : 0,
      usableThreads(params.execution.num_threads));
  // A view's normals face its sensor; is the cloud one view from it? (Not in CAD mode.)
  if (sensor_origin && !params.cad.enabled) {
    std::array<float, 3> origin;
    for (int d = 0; d < 3; ++d)
      origin[d] = static_cast<float>(sensor_origin[d] - prepared.centroid[d]);
    prepared.set.sensor_origin = origin;
  }
  VertexMap map;
  map.point.swap(prepared.point); // the caller's now: the analysis does not need them
  map.copies.swap(prepared.copies);
  return map;
}

std::size_t PointSegmenter::numVertices() const {
  return prepared_->points.raw.size() / 3;
}

Status PointSegmenter::analyze(const Parameters& params, PhaseTimes& times,
                               const PhaseProgressFn& progress, const NeighbourSearch& search,
                               const CadNormals& normals) {
  Stopwatch clock;
  PreparedPoints& prepared = prepared_->points;
  const std::size_t n = numVertices();
  if (n == 0) { // nothing prepared: no analysis (a misuse, not a crash)
    analyses_.reset();
    return Status::failure(StatusCode::NoInput, "no points prepared.");
  }
  Status status;
  if (progress)
    progress("kNN", 0.0);
  // Sec. 4.1: the k nearest neighbours of each point (fewer when there are fewer points).
  PointSet& set = prepared.set;
  set.k = std::min<std::size_t>(static_cast<std::size_t>(params.graph.k), n - 1);
  if (set.k < static_cast<std::size_t>(params.graph.k))
    status.warnings.push_back(
        {WarningCode::FewPoints, "only " + std::to_string(n) + " points: using " +
                                     std::to_string(set.k) + " neighbours instead of " +
                                     std::to_string(params.graph.k) + "."});
  set.knn.assign(n * std::max<std::size_t>(set.k, 1), kNone);
  const int threads = usableThreads(params.execution.num_threads);
  if (set.k > 0 && !search) // the default: FLANN's kd-tree as pcl::search::KdTree builds it
    kNearestNeighbours(prepared.raw.data(), n, set.k, threads, set.knn.data());
  else if (set.k > 0)
    search(set.k, threads, set.knn.data());
  std::vector<float>().swap(prepared.raw);
  if (params.cad.enabled && normals)
    set.normals = [normals](const CsrGraph& graph) {
      return normals(graph.offsets, graph.targets);
    };
  times.knn += clock.lap();
  analyses_ = std::make_shared<const Analyses>(
      pcl_ncut_seg::analyze(std::move(set), params, times, progress));
  prepared = PreparedPoints();
  return status;
}

bool PointSegmenter::serves(const Parameters& params) const {
  return analyses_ && pcl_ncut_seg::serves(analyses_->starts.at(0), params);
}

void PointSegmenter::cut(const Parameters& params, PhaseTimes& times) {
  *result_ = analyses_ ? pcl_ncut_seg::cut(*analyses_, params, times) : CutResult();
}

const std::vector<std::uint32_t>& PointSegmenter::pointSegments() const {
  return result_->point_segment;
}
std::size_t PointSegmenter::numSegments() const {
  return result_->num_segments;
}
std::size_t PointSegmenter::start() const {
  return result_->start;
}
SegmentTree PointSegmenter::hierarchy() const {
  const Hierarchy& h = result_->hierarchy;
  SegmentTree tree;
  tree.num_supernodes = result_->graph.num_vertices / 2; // G_s: r_i = i, m_i = l + i
  const auto l = static_cast<std::uint32_t>(tree.num_supernodes);
  tree.nodes.resize(h.nodes.size());
  for (std::size_t i = 0; i < h.nodes.size(); ++i) {
    const Hierarchy::Node& from = h.nodes[i];
    SegmentTree::Node& to = tree.nodes[i];
    to.parent = from.parent;
    to.left = from.left;
    to.right = from.right;
    if (from.has_split)
      to.ncut = from.ncut;
    to.vertices = from.vertices;
    for (const std::uint32_t v : from.vertices) // sorted: the members come last, sorted
      if (v >= l)
        to.supernodes.push_back(v - l);
  }
  const std::vector<std::uint32_t>& segment = result_->supernode_segment;
  tree.supernode_segment.reserve(segment.size());
  for (const std::uint32_t s : segment)
    tree.supernode_segment.push_back(s < result_->num_segments ? static_cast<int>(s) : -1);
  return tree;
}
SupernodeGraph PointSegmenter::supernodeGraph() const {
  const WeightedGraph& g = result_->graph;
  SupernodeGraph out;
  out.num_vertices = g.num_vertices;
  out.num_supernodes = g.num_vertices / 2;
  out.edges.reserve(g.edges.size());
  for (const WeightedGraph::Edge& e : g.edges)
    out.edges.push_back({e.a, e.b, e.w});
  return out;
}
const CutResult& PointSegmenter::result() const {
  return *result_;
}

void PointSegmenter::renumberSegments(const std::vector<std::uint32_t>& rank) {
  for (std::uint32_t& l : result_->point_segment)
    l = rank[l];
  for (std::uint32_t& l : result_->supernode_segment)
    if (l < rank.size())
      l = rank[l];
}

const std::vector<float>& PointSegmenter::centrality(std::size_t start) const {
  return analyses_->starts.at(start).centrality.f;
}
const std::vector<std::uint32_t>& PointSegmenter::supernodeLabels(std::size_t start,
                                                                  bool refined) const {
  const Analysis& a = analyses_->starts.at(start);
  return refined ? a.supernodes.label : a.raw_supernodes.label;
}
std::size_t PointSegmenter::numSupernodes(std::size_t start, bool refined) const {
  const Analysis& a = analyses_->starts.at(start);
  return refined ? a.supernodes.size() : a.raw_supernodes.size();
}
std::vector<std::uint32_t> PointSegmenter::localMaxima(std::size_t start) const {
  return analyses_->starts.at(start).raw_supernodes.localMaxima();
}
std::vector<std::uint32_t> PointSegmenter::saddles(std::size_t start) const {
  return analyses_->starts.at(start).raw_supernodes.saddles();
}
NoiseTest PointSegmenter::noiseTest() const {
  return analyses_ ? analyses_->starts.at(0).noise : NoiseTest{};
}
ViewTest PointSegmenter::viewTest() const {
  return analyses_ ? analyses_->starts.at(0).view : ViewTest{};
}
const Analysis* PointSegmenter::analysis() const {
  return analyses_ ? &analyses_->starts.at(0) : nullptr;
}

std::vector<std::uint32_t> segmentPoints(const float* xyz, std::size_t n, const Parameters& params,
                                         Status* status) {
  Status ignored;
  Status& out = status ? *status : ignored;
  std::string why;
  if (!validate(params, &why)) {
    out = Status::failure(StatusCode::BadParameter, why);
    return {};
  }
  if (n == 0) {
    out = Status::failure(StatusCode::NoFinitePoint, "the input has no finite point.");
    return {};
  }
  PointSegmenter segmenter;
  const PointSegmenter::VertexMap map =
      segmenter.prepare(std::vector<float>(xyz, xyz + 3 * n), params);
  PhaseTimes times;
  out = segmenter.analyze(params, times);
  if (!out.ok())
    return {};
  segmenter.cut(params, times);
  const std::vector<std::uint32_t>& segment = segmenter.pointSegments();
  std::vector<std::uint32_t> label(n);
  for (std::size_t v = 0; v < map.point.size(); ++v)
    label[map.point[v]] = segment[v];
  for (const auto& [copy, vertex] : map.copies)
    label[copy] = segment[vertex];
  return label;
}

} // namespace pcl_ncut_seg
