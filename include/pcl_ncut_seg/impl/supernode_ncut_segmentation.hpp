/*
 * pcl_ncut_seg: the PCL front end. It validates the input, turns the cloud into arrays,
 * supplies the search method's neighbours and CAD mode's normals and maps the results back;
 * the arrays' segmentation is PointSegmenter's (<pcl_ncut_seg/segment_points.h>).
 */
#pragma once

#include <pcl_ncut_seg/supernode_ncut_segmentation.h>

#include <pcl/common/point_tests.h>
#include <pcl/console/print.h>
#include <pcl/features/normal_3d.h>
#include <pcl/search/kdtree.h>

#include <pcl_ncut_seg/impl/supernode_ncut_segmentation_parameters.hpp>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <numeric>
#include <string>
#include <utility>

template <typename PointT>
pcl::SupernodeNCutSegmentation<PointT>::SupernodeNCutSegmentation() = default;

template <typename PointT>
pcl::SupernodeNCutSegmentation<PointT>::~SupernodeNCutSegmentation() = default;

template <typename PointT> void pcl::SupernodeNCutSegmentation<PointT>::invalidate() {
  segmenter_.reset();
  point_index_.clear();
  duplicates_.clear();
  have_result_ = false;
}

template <typename PointT>
void pcl::SupernodeNCutSegmentation<PointT>::setInputCloud(const PointCloudConstPtr& cloud) {
  PCLBase<PointT>::setInputCloud(cloud);
  invalidate();
}

template <typename PointT>
void pcl::SupernodeNCutSegmentation<PointT>::setIndices(const IndicesPtr& indices) {
  PCLBase<PointT>::setIndices(indices);
  invalidate();
}

template <typename PointT>
void pcl::SupernodeNCutSegmentation<PointT>::setIndices(const IndicesConstPtr& indices) {
  PCLBase<PointT>::setIndices(indices);
  invalidate();
}

template <typename PointT>
void pcl::SupernodeNCutSegmentation<PointT>::setIndices(const PointIndicesConstPtr& indices) {
  PCLBase<PointT>::setIndices(indices);
  invalidate();
}

template <typename PointT>
void pcl::SupernodeNCutSegmentation<PointT>::setSearchMethod(const KdTreePtr& search) {
  search_ = search;
  invalidate();
}

namespace pcl {
namespace ncut_detail {
/// CAD mode: the input's own normal when the point type has one and it is finite and non-zero.
template <typename PointT> bool inputNormal(const PointT& p, float* n) {
  if constexpr (pcl::traits::has_normal<PointT>::value) {
    n[0] = p.normal_x;
    n[1] = p.normal_y;
    n[2] = p.normal_z;
    return std::isfinite(n[0]) && std::isfinite(n[1]) && std::isfinite(n[2]) &&
           n[0] * n[0] + n[1] * n[1] + n[2] * n[2] > 0.0f;
  } else {
    (void)p;
    (void)n;
    return false;
  }
}
/// Points farther from the origin are in no segment, as non-finite ones: the kNN search and
/// the analysis square coordinate differences in float, which overflows beyond about 5e18.
constexpr float kMaxCoordinate = 1e18f;
} // namespace ncut_detail
} // namespace pcl

template <typename PointT>
void pcl::SupernodeNCutSegmentation<PointT>::fail(pcl_ncut_seg::StatusCode code,
                                                  std::string message) {
  if (console_messages_)
    PCL_ERROR("[pcl::SupernodeNCutSegmentation::extract] %s\n", message.c_str());
  status_.code = code;
  status_.message = std::move(message);
}

template <typename PointT>
void pcl::SupernodeNCutSegmentation<PointT>::warn(pcl_ncut_seg::WarningCode code,
                                                  std::string message) {
  if (console_messages_)
    PCL_WARN("[pcl::SupernodeNCutSegmentation::extract] %s\n", message.c_str());
  status_.warnings.push_back({code, std::move(message)});
}

template <typename PointT>
bool pcl::SupernodeNCutSegmentation<PointT>::validIndices(std::vector<int>& valid) {
  using pcl_ncut_seg::StatusCode;
  const std::size_t cloud_size = input_->size();
  valid.reserve(indices_->size());
  std::size_t too_far = 0;
  for (const auto idx : *indices_) {
    if (idx < 0 || static_cast<std::size_t>(idx) >= cloud_size) {
      fail(StatusCode::IndexOutOfRange, "index " + std::to_string(idx) +
                                            " is out of range for a cloud of " +
                                            std::to_string(cloud_size) + " points.");
      return false;
    }
    const PointT& p = (*input_)[idx];
    if (!pcl::isXYZFinite(p))
      continue;
    if (std::abs(p.x) <= ncut_detail::kMaxCoordinate &&
        std::abs(p.y) <= ncut_detail::kMaxCoordinate &&
        std::abs(p.z) <= ncut_detail::kMaxCoordinate)
      valid.push_back(static_cast<int>(idx));
    else
      ++too_far;
  }
  if (too_far > 0)
    warn(pcl_ncut_seg::WarningCode::DistantPoints,
         std::to_string(too_far) + " points with a coordinate beyond 1e18 are in no segment: "
                                   "their squared distances overflow a float.");
  if (!std::is_sorted(valid.begin(), valid.end())) // the usual indices are sorted already
    std::sort(valid.begin(), valid.end());
  const std::size_t before = valid.size();
  valid.erase(std::unique(valid.begin(), valid.end()), valid.end());
  if (valid.size() < before)
    warn(pcl_ncut_seg::WarningCode::RepeatedIndices,
         std::to_string(before - valid.size()) + " repeated indices ignored.");
  if (valid.size() > std::numeric_limits<std::uint32_t>::max() / 64) {
    fail(StatusCode::TooManyPoints, "too many points (" + std::to_string(valid.size()) + ").");
    return false;
  }
  if (valid.empty()) {
    fail(StatusCode::NoFinitePoint, std::string("the input has no finite point") +
                                        (too_far > 0 ? " within 1e18 of the origin." : "."));
    return false;
  }
  return true;
}

template <typename PointT>
void pcl::SupernodeNCutSegmentation<PointT>::searchNeighbours(const std::vector<int>& vertex_index,
                                                              std::size_t k, int threads,
                                                              std::uint32_t* knn) {
  const std::size_t cloud_size = input_->size(), n = vertex_index.size();
  pcl::IndicesPtr indices(new pcl::Indices(vertex_index.begin(), vertex_index.end()));
  search_->setInputCloud(input_, indices);
  std::vector<std::int64_t> local(cloud_size, -1);
  for (std::size_t i = 0; i < n; ++i)
    local[vertex_index[i]] = static_cast<std::int64_t>(i);
    // Queries in vertex (Morton) order visit the search tree coherently.
#pragma omp parallel num_threads(threads)
  {
    pcl::Indices nn;
    std::vector<float> sqr;
#pragma omp for schedule(dynamic, 256)
    for (std::ptrdiff_t qi = 0; qi < static_cast<std::ptrdiff_t>(n); ++qi) {
      const auto i = static_cast<std::size_t>(qi);
      nn.clear();
      search_->nearestKSearch((*input_)[vertex_index[i]], static_cast<int>(k + 1), nn, sqr);
      std::size_t j = 0;
      for (const auto q : nn) {
        if (j == k)
          break;
        if (q < 0 || static_cast<std::size_t>(q) >= cloud_size)
          continue;
        const std::int64_t lq = local[q];
        if (lq < 0 || static_cast<std::size_t>(lq) == i)
          continue;
        knn[i * k + j++] = static_cast<std::uint32_t>(lq);
      }
    }
  }
}

template <typename PointT>
std::vector<float> pcl::SupernodeNCutSegmentation<PointT>::cadNormals(
    const std::vector<std::uint32_t>& offsets, const std::vector<std::uint32_t>& targets) const {
  // Sec. 7: approximate normals, from the input or fitted by PCL over p and N(p).
  const std::size_t n = point_index_.size();
  std::vector<float> normals(3 * n, std::numeric_limits<float>::quiet_NaN());
  pcl::Indices neighbourhood;
  Eigen::Vector4f plane;
  float curvature;
  for (std::size_t i = 0; i < n; ++i) {
    if (ncut_detail::inputNormal((*input_)[point_index_[i]], &normals[3 * i]))
      continue;
    neighbourhood.assign(1, point_index_[i]);
    for (std::uint32_t e = offsets[i]; e < offsets[i + 1]; ++e)
      neighbourhood.push_back(point_index_[targets[e]]);
    if (neighbourhood.size() >= 3 &&
        pcl::computePointNormal(*input_, neighbourhood, plane, curvature))
      for (int d = 0; d < 3; ++d)
        normals[3 * i + d] = plane[d];
  }
  return normals;
}

template <typename PointT> bool pcl::SupernodeNCutSegmentation<PointT>::analyze() {
  const auto start = std::chrono::steady_clock::now();
  std::vector<int> valid; // in range, finite, each once, sorted: graph order is cloud order
  if (!validIndices(valid))
    return false;
  // Points at exactly the position of an earlier one are analysed once and share its segment:
  // copies would fill each other's k nearest neighbours with zero-length edges. Vertices are
  // numbered along a Morton curve; ties go by the distance from the centroid, so the order of
  // the points changes only the segments' numbers (PointSegmenter::prepare()).
  std::vector<float> xyz(3 * valid.size());
  for (std::size_t i = 0; i < valid.size(); ++i) {
    const PointT& p = (*input_)[valid[i]];
    xyz[3 * i + 0] = p.x;
    xyz[3 * i + 1] = p.y;
    xyz[3 * i + 2] = p.z;
  }
  // The rim of an open view (not in CAD mode), whether or not the open-view stages run: it
  // decides how the view is analysed (one start, f without the noise's mean), which the cut
  // parameters must not change. A view's normals face the sensor.
  const float origin[3] = {input_->sensor_origin_[0], input_->sensor_origin_[1],
                           input_->sensor_origin_[2]};
  pcl_ncut_seg::PointSegmenter::VertexMap map = segmenter_.prepare(std::move(xyz), params_, origin);
  const std::size_t n = map.point.size();
  point_index_.resize(n);
  for (std::size_t v = 0; v < n; ++v)
    point_index_[v] = valid[map.point[v]];
  duplicates_.clear();
  for (const auto& c : map.copies)
    duplicates_.emplace_back(valid[c.first], c.second);
  std::vector<int>().swap(valid); // free before the expensive stage, as the map
  map = pcl_ncut_seg::PointSegmenter::VertexMap();

  // Sec. 4.1: the k nearest neighbours of each point (fewer when there are fewer points, with
  // a warning from the analysis).
  pcl_ncut_seg::PointSegmenter::NeighbourSearch search;
  if (search_) // else FLANN's kd-tree as pcl::search::KdTree builds it
    search = [this](std::size_t neighbours, int threads, std::uint32_t* knn) {
      searchNeighbours(point_index_, neighbours, threads, knn);
    };
  pcl_ncut_seg::PointSegmenter::CadNormals normals;
  if (params_.cad.enabled)
    normals = [this](const std::vector<std::uint32_t>& offsets,
                     const std::vector<std::uint32_t>& targets) {
      return cadNormals(offsets, targets);
    };
  times_ = pcl_ncut_seg::PhaseTimes();
  times_.knn = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  const pcl_ncut_seg::Status analysed =
      segmenter_.analyze(params_, times_, progress_, search, normals);
  for (const pcl_ncut_seg::Warning& w : analysed.warnings)
    warn(w.code, w.message);
  if (!analysed.ok())
    fail(analysed.code, analysed.message);
  return analysed.ok();
}

template <typename PointT>
void pcl::SupernodeNCutSegmentation<PointT>::extract(std::vector<pcl::PointIndices>& segments) {
  segments.clear();
  have_result_ = false;
  status_ = pcl_ncut_seg::Status();
  if (!initCompute()) {
    fail(pcl_ncut_seg::StatusCode::NoInput, "no input cloud.");
    return;
  }
  if (segmenter_.analysed() && !segmenter_.serves(params_))
    invalidate(); // the cut asks for a measurement the kept analysis did not make
  if (!segmenter_.analysed() && !analyze()) {
    invalidate();
    deinitCompute();
    return;
  }
  if (progress_)
    progress_("HSeg", 0.0);
  segmenter_.cut(params_, times_);
  if (progress_)
    progress_("HSeg", 1.0);
  // Each point's segment, then one pass in index order: every segment's indices come out
  // sorted with no sort. The cut numbers segments by their first analysed point; a point carried
  // to its nearest analysed one (max_points) can come earlier. Segments are renumbered by their
  // smallest point index, in the result too, so that labels and colours agree with their order.
  constexpr std::uint32_t kNoSegment = std::numeric_limits<std::uint32_t>::max();
  const std::vector<std::uint32_t>& point_segment = segmenter_.pointSegments();
  std::vector<std::uint32_t> label(input_->size(), kNoSegment);
  for (std::size_t i = 0; i < point_index_.size(); ++i)
    label[point_index_[i]] = point_segment[i];
  for (const auto& d : duplicates_)
    label[d.first] = point_segment[d.second];
  std::vector<std::uint32_t> rank(segmenter_.numSegments(), kNoSegment);
  std::vector<std::size_t> size(segmenter_.numSegments(), 0);
  std::uint32_t next = 0;
  for (const std::uint32_t l : label)
    if (l != kNoSegment) {
      if (rank[l] == kNoSegment)
        rank[l] = next++;
      ++size[l];
    }
  for (std::uint32_t& r : rank) // (a segment with no point: none is expected)
    if (r == kNoSegment)
      r = next++;
  segments.resize(segmenter_.numSegments());
  for (std::size_t s = 0; s < rank.size(); ++s)
    segments[rank[s]].indices.reserve(size[s]);
  for (std::size_t idx = 0; idx < label.size(); ++idx)
    if (label[idx] != kNoSegment)
      segments[rank[label[idx]]].indices.push_back(static_cast<pcl::index_t>(idx));
  if (!std::is_sorted(rank.begin(), rank.end()))
    segmenter_.renumberSegments(rank);
  for (auto& s : segments)
    s.header = input_->header;
  have_result_ = true;
  deinitCompute();
}

template <typename PointT>
void pcl::SupernodeNCutSegmentation<PointT>::segmentColor(std::size_t i, std::uint8_t& r,
                                                          std::uint8_t& g, std::uint8_t& b) {
  // Golden-ratio hue steps: neighbouring ids get far-apart hues; value cycles for many ids.
  const double h = std::fmod(0.1 + 0.618033988749895 * static_cast<double>(i), 1.0) * 6.0;
  const double s = 0.75, v = (i / 7) % 2 ? 0.7 : 0.95;
  const int sector = static_cast<int>(h);
  const double frac = h - sector;
  const double p = v * (1 - s), q = v * (1 - s * frac), t = v * (1 - s * (1 - frac));
  double rgb[3];
  switch (sector) {
  case 0:
    rgb[0] = v, rgb[1] = t, rgb[2] = p;
    break;
  case 1:
    rgb[0] = q, rgb[1] = v, rgb[2] = p;
    break;
  case 2:
    rgb[0] = p, rgb[1] = v, rgb[2] = t;
    break;
  case 3:
    rgb[0] = p, rgb[1] = q, rgb[2] = v;
    break;
  case 4:
    rgb[0] = t, rgb[1] = p, rgb[2] = v;
    break;
  default:
    rgb[0] = v, rgb[1] = p, rgb[2] = q;
    break;
  }
  r = static_cast<std::uint8_t>(std::lround(rgb[0] * 255));
  g = static_cast<std::uint8_t>(std::lround(rgb[1] * 255));
  b = static_cast<std::uint8_t>(std::lround(rgb[2] * 255));
}

namespace pcl {
namespace ncut_detail {
/// A copy of the input's x, y, z and layout into another point type.
template <typename OutT, typename InT>
typename pcl::PointCloud<OutT>::Ptr copyXyz(const pcl::PointCloud<InT>& in) {
  typename pcl::PointCloud<OutT>::Ptr out(new pcl::PointCloud<OutT>);
  out->header = in.header;
  out->resize(in.size());
  out->width = in.width;
  out->height = in.height;
  out->is_dense = in.is_dense;
  for (std::size_t i = 0; i < in.size(); ++i) {
    (*out)[i].x = in[i].x;
    (*out)[i].y = in[i].y;
    (*out)[i].z = in[i].z;
  }
  return out;
}
} // namespace ncut_detail
} // namespace pcl

template <typename PointT>
pcl::PointCloud<pcl::PointXYZRGB>::Ptr
pcl::SupernodeNCutSegmentation<PointT>::getColoredCloud() const {
  if (!have_result_ || !input_)
    return pcl::PointCloud<pcl::PointXYZRGB>::Ptr(new pcl::PointCloud<pcl::PointXYZRGB>);
  auto out = ncut_detail::copyXyz<pcl::PointXYZRGB>(*input_);
  for (auto& q : *out)
    q.r = q.g = q.b = 0; // points in no segment are black
  for (std::size_t i = 0; i < point_index_.size(); ++i) {
    auto& q = (*out)[point_index_[i]];
    segmentColor(segmenter_.pointSegments()[i], q.r, q.g, q.b);
  }
  for (const auto& d : duplicates_) {
    auto& q = (*out)[d.first];
    segmentColor(segmenter_.pointSegments()[d.second], q.r, q.g, q.b);
  }
  return out;
}

template <typename PointT>
pcl::PointCloud<pcl::PointXYZL>::Ptr
pcl::SupernodeNCutSegmentation<PointT>::getLabeledCloud() const {
  if (!have_result_ || !input_)
    return pcl::PointCloud<pcl::PointXYZL>::Ptr(new pcl::PointCloud<pcl::PointXYZL>);
  auto out = ncut_detail::copyXyz<pcl::PointXYZL>(*input_);
  for (auto& q : *out)
    q.label = 0; // points in no segment
  for (std::size_t i = 0; i < point_index_.size(); ++i)
    (*out)[point_index_[i]].label = segmenter_.pointSegments()[i] + 1;
  for (const auto& d : duplicates_)
    (*out)[d.first].label = segmenter_.pointSegments()[d.second] + 1;
  return out;
}

template <typename PointT>
std::vector<float> pcl::SupernodeNCutSegmentation<PointT>::getCentrality() const {
  std::vector<float> out(input_ ? input_->size() : 0, std::numeric_limits<float>::quiet_NaN());
  if (segmenter_.analysed()) {
    const std::vector<float>& f = segmenter_.centrality(shownStart());
    for (std::size_t i = 0; i < point_index_.size(); ++i)
      out[point_index_[i]] = f[i];
    for (const auto& d : duplicates_)
      out[d.first] = f[d.second];
  }
  return out;
}

template <typename PointT>
std::vector<int> pcl::SupernodeNCutSegmentation<PointT>::getLocalMaxima() const {
  std::vector<int> out;
  if (segmenter_.analysed())
    for (std::uint32_t v : segmenter_.localMaxima(shownStart()))
      out.push_back(point_index_[v]);
  return out;
}

template <typename PointT>
std::vector<int> pcl::SupernodeNCutSegmentation<PointT>::getSaddles() const {
  std::vector<int> out;
  if (segmenter_.analysed())
    for (std::uint32_t v : segmenter_.saddles(shownStart()))
      out.push_back(point_index_[v]);
  return out;
}

template <typename PointT>
std::vector<int> pcl::SupernodeNCutSegmentation<PointT>::getSupernodeLabels(bool refined) const {
  std::vector<int> out(input_ ? input_->size() : 0, -1);
  if (segmenter_.analysed()) {
    const auto& label = segmenter_.supernodeLabels(shownStart(), refined);
    for (std::size_t i = 0; i < point_index_.size(); ++i)
      out[point_index_[i]] = static_cast<int>(label[i]);
    for (const auto& d : duplicates_)
      out[d.first] = static_cast<int>(label[d.second]);
  }
  return out;
}

template <typename PointT>
std::size_t pcl::SupernodeNCutSegmentation<PointT>::getNumberOfSupernodes(bool refined) const {
  return segmenter_.analysed() ? segmenter_.numSupernodes(shownStart(), refined) : 0;
}

template <typename PointT>
pcl_ncut_seg::NoiseTest pcl::SupernodeNCutSegmentation<PointT>::getNoiseTest() const {
  return segmenter_.noiseTest();
}

template <typename PointT>
pcl_ncut_seg::ViewTest pcl::SupernodeNCutSegmentation<PointT>::getViewTest() const {
  return segmenter_.viewTest();
}

#define PCL_INSTANTIATE_SupernodeNCutSegmentation(T)                                               \
  template class PCL_EXPORTS pcl::SupernodeNCutSegmentation<T>;
