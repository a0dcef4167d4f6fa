/*
 * pcl_ncut_seg: the PCL front end. It checks the input, builds the kNN graph with the search
 * method, and hands plain arrays to the pipeline in pcl_ncut_seg/core.
 */
#pragma once

#include <pcl_ncut_seg/supernode_ncut_segmentation.h>

#include <pcl/common/point_tests.h>
#include <pcl/console/print.h>
#include <pcl/features/normal_3d.h>
#include <pcl/search/kdtree.h>

#include <pcl_ncut_seg/core/bridging.h>
#include <pcl_ncut_seg/core/concavity.h>
#include <pcl_ncut_seg/core/crease_split.h>
#include <pcl_ncut_seg/core/morton.h>
#include <pcl_ncut_seg/core/knn.h>
#include <pcl_ncut_seg/core/threads.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <iterator>
#include <limits>
#include <tuple>

template <typename PointT>
pcl::SupernodeNCutSegmentation<PointT>::SupernodeNCutSegmentation() = default;

template <typename PointT>
pcl::SupernodeNCutSegmentation<PointT>::~SupernodeNCutSegmentation() = default;

template <typename PointT> void pcl::SupernodeNCutSegmentation<PointT>::invalidate() {
  analysis_.reset();
  point_index_.clear();
  duplicates_.clear();
  result_ = pcl_ncut_seg::CutResult();
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

// Setters: reject bad values with PCL_ERROR and keep the old value. Analysis parameters
// invalidate the expensive stage; cut parameters do not.
template <typename PointT>
void pcl::SupernodeNCutSegmentation<PointT>::setNumberOfNeighbours(int k) {
  if (k < 2) {
    PCL_ERROR("[pcl::SupernodeNCutSegmentation::setNumberOfNeighbours] k must be >= 2, got "
              "%d; keeping %d.\n",
              k, k_);
    return;
  }
  if (k != k_)
    invalidate();
  k_ = k;
}

template <typename PointT>
void pcl::SupernodeNCutSegmentation<PointT>::setNumberOfSamples(int samples) {
  if (samples < 0) {
    PCL_ERROR("[pcl::SupernodeNCutSegmentation::setNumberOfSamples] samples must be >= 0 (0: "
              "ceil(sqrt(n))), got %d; keeping %d.\n",
              samples, num_samples_);
    return;
  }
  if (samples != num_samples_)
    invalidate();
  num_samples_ = samples;
}

template <typename PointT>
void pcl::SupernodeNCutSegmentation<PointT>::setCentralityMode(pcl_ncut_seg::CentralityMode mode) {
  if (mode != pcl_ncut_seg::CentralityMode::Exact && mode != pcl_ncut_seg::CentralityMode::Fast) {
    PCL_ERROR("[pcl::SupernodeNCutSegmentation::setCentralityMode] unknown mode %d; keeping "
              "%d.\n",
              static_cast<int>(mode), static_cast<int>(centrality_mode_));
    return;
  }
  if (mode != centrality_mode_)
    invalidate();
  centrality_mode_ = mode;
}

template <typename PointT>
void pcl::SupernodeNCutSegmentation<PointT>::setNumberOfRepresentatives(int representatives) {
  if (representatives < 100) {
    PCL_ERROR("[pcl::SupernodeNCutSegmentation::setNumberOfRepresentatives] representatives "
              "must be >= 100, got %d; keeping %d.\n",
              representatives, num_representatives_);
    return;
  }
  if (representatives != num_representatives_)
    invalidate();
  num_representatives_ = representatives;
}

namespace pcl {
namespace ncut_detail {
inline bool checkFraction(const char* method, float value, float old) {
  if (!(value >= 0.0f && value <= 1.0f)) {
    PCL_ERROR("[pcl::SupernodeNCutSegmentation::%s] fraction must be in [0, 1], got %g; "
              "keeping %g.\n",
              method, value, old);
    return false;
  }
  return true;
}
inline bool checkPositive(const char* method, double value, double old) {
  if (!(value > 0.0) || !std::isfinite(value)) {
    PCL_ERROR("[pcl::SupernodeNCutSegmentation::%s] value must be finite and > 0, got %g; "
              "keeping %g.\n",
              method, value, old);
    return false;
  }
  return true;
}
} // namespace ncut_detail
} // namespace pcl

template <typename PointT>
void pcl::SupernodeNCutSegmentation<PointT>::setCrossingFraction(float fraction) {
  if (!ncut_detail::checkFraction("setCrossingFraction", fraction, crossing_fraction_))
    return;
  if (fraction != crossing_fraction_)
    invalidate();
  crossing_fraction_ = fraction;
}

template <typename PointT>
void pcl::SupernodeNCutSegmentation<PointT>::setAreaFraction(float fraction) {
  if (!ncut_detail::checkFraction("setAreaFraction", fraction, area_fraction_))
    return;
  if (fraction != area_fraction_)
    invalidate();
  area_fraction_ = fraction;
}

template <typename PointT>
void pcl::SupernodeNCutSegmentation<PointT>::setHeightFraction(float fraction) {
  if (!ncut_detail::checkFraction("setHeightFraction", fraction, height_fraction_))
    return;
  if (fraction != height_fraction_)
    invalidate();
  height_fraction_ = fraction;
}

template <typename PointT> void pcl::SupernodeNCutSegmentation<PointT>::setBeta(double beta) {
  if (ncut_detail::checkPositive("setBeta", beta, similarity_.beta))
    similarity_.beta = beta;
}

template <typename PointT> void pcl::SupernodeNCutSegmentation<PointT>::setAlpha1(double alpha1) {
  if (ncut_detail::checkPositive("setAlpha1", alpha1, similarity_.alpha1))
    similarity_.alpha1 = alpha1;
}

template <typename PointT> void pcl::SupernodeNCutSegmentation<PointT>::setAlpha2(double alpha2) {
  if (ncut_detail::checkPositive("setAlpha2", alpha2, similarity_.alpha2))
    similarity_.alpha2 = alpha2;
}

template <typename PointT>
void pcl::SupernodeNCutSegmentation<PointT>::setThreshold(double threshold) {
  if (!(threshold >= 0.0) || !std::isfinite(threshold)) {
    PCL_ERROR("[pcl::SupernodeNCutSegmentation::setThreshold] threshold must be finite and >= "
              "0, got %g; keeping %g.\n",
              threshold, cut_.threshold);
    return;
  }
  cut_.threshold = threshold;
}

template <typename PointT>
void pcl::SupernodeNCutSegmentation<PointT>::setMinSegmentFraction(double fraction) {
  if (!(fraction >= 0.0 && fraction <= 0.5)) {
    PCL_ERROR("[pcl::SupernodeNCutSegmentation::setMinSegmentFraction] fraction must be in "
              "[0, 0.5], got %g; keeping %g.\n",
              fraction, cut_.min_segment_fraction);
    return;
  }
  cut_.min_segment_fraction = fraction;
}

template <typename PointT>
void pcl::SupernodeNCutSegmentation<PointT>::setLargestGapStopping(bool enable) {
  cut_.largest_gap = enable;
}

template <typename PointT>
void pcl::SupernodeNCutSegmentation<PointT>::setMaxSegments(int segments) {
  if (segments < 1) {
    PCL_ERROR("[pcl::SupernodeNCutSegmentation::setMaxSegments] segments must be >= 1, got %d; "
              "keeping %d.\n",
              segments, cut_.max_segments);
    return;
  }
  cut_.max_segments = segments;
}

template <typename PointT>
void pcl::SupernodeNCutSegmentation<PointT>::setGapFloor(double floor) {
  if (!(floor > 0.0) || !std::isfinite(floor)) {
    PCL_ERROR("[pcl::SupernodeNCutSegmentation::setGapFloor] floor must be finite and > 0, got "
              "%g; keeping %g.\n",
              floor, cut_.gap_floor);
    return;
  }
  cut_.gap_floor = floor;
}

template <typename PointT>
void pcl::SupernodeNCutSegmentation<PointT>::setNeckExponent(double exponent) {
  if (!(exponent >= 0.0) || !std::isfinite(exponent)) {
    PCL_ERROR("[pcl::SupernodeNCutSegmentation::setNeckExponent] exponent must be finite and "
              ">= 0, got %g; keeping %g.\n",
              exponent, cut_.neck_exponent);
    return;
  }
  cut_.neck_exponent = exponent;
}

template <typename PointT> void pcl::SupernodeNCutSegmentation<PointT>::setNeckBound(double bound) {
  if (!(bound > 0.0) || !std::isfinite(bound)) {
    PCL_ERROR("[pcl::SupernodeNCutSegmentation::setNeckBound] bound must be finite and > 0, got "
              "%g; keeping %g.\n",
              bound, cut_.neck_bound);
    return;
  }
  cut_.neck_bound = bound;
}

template <typename PointT>
void pcl::SupernodeNCutSegmentation<PointT>::setNumberOfSegments(int segments) {
  if (segments < 0) {
    PCL_ERROR("[pcl::SupernodeNCutSegmentation::setNumberOfSegments] segments must be >= 0 "
              "(0: use the threshold), got %d; keeping %d.\n",
              segments, cut_.num_segments);
    return;
  }
  cut_.num_segments = segments;
}

template <typename PointT>
void pcl::SupernodeNCutSegmentation<PointT>::setNumberOfSplitValues(int values) {
  if (values < 1) {
    PCL_ERROR("[pcl::SupernodeNCutSegmentation::setNumberOfSplitValues] values must be >= 1, "
              "got %d; keeping %d.\n",
              values, cut_.num_splits);
    return;
  }
  cut_.num_splits = values;
}

template <typename PointT>
void pcl::SupernodeNCutSegmentation<PointT>::setNormalizeWidth(bool normalize) {
  similarity_.normalize_width = normalize;
}

template <typename PointT>
void pcl::SupernodeNCutSegmentation<PointT>::setConnectAdjacentTrees(bool connect) {
  similarity_.connect_adjacent_trees = connect;
}

template <typename PointT>
void pcl::SupernodeNCutSegmentation<PointT>::setConnectAllAdjacent(bool connect) {
  similarity_.connect_all_adjacent = connect;
}

template <typename PointT>
void pcl::SupernodeNCutSegmentation<PointT>::setBridgeGap(double radii) {
  if (!(radii >= 0.0) || !std::isfinite(radii)) {
    PCL_ERROR("[pcl::SupernodeNCutSegmentation::setBridgeGap] radii must be finite and >= 0, "
              "got %g; keeping %g.\n",
              radii, bridge_gap_);
    return;
  }
  if (radii != bridge_gap_)
    invalidate();
  bridge_gap_ = radii;
}

template <typename PointT>
void pcl::SupernodeNCutSegmentation<PointT>::setConcavityWeight(double weight) {
  if (!(weight >= 0.0) || !std::isfinite(weight)) {
    PCL_ERROR("[pcl::SupernodeNCutSegmentation::setConcavityWeight] weight must be finite and "
              ">= 0, got %g; keeping %g.\n",
              weight, similarity_.concavity_weight);
    return;
  }
  if ((weight > 0.0) != (similarity_.concavity_weight > 0.0))
    invalidate(); // the contact concavity is measured in the expensive stage only when used
  similarity_.concavity_weight = weight;
}

template <typename PointT>
void pcl::SupernodeNCutSegmentation<PointT>::setFlatElongation(double elongation) {
  if (!(elongation >= 0.0) || !std::isfinite(elongation)) {
    PCL_ERROR("[pcl::SupernodeNCutSegmentation::setFlatElongation] elongation must be finite "
              "and >= 0, got %g; keeping %g.\n",
              elongation, similarity_.flat_elongation);
    return;
  }
  similarity_.flat_elongation = elongation;
}

template <typename PointT>
void pcl::SupernodeNCutSegmentation<PointT>::setBoundaryBand(double fraction) {
  if (!(fraction >= 0.0 && fraction <= 0.5)) {
    PCL_ERROR("[pcl::SupernodeNCutSegmentation::setBoundaryBand] fraction must be in [0, 0.5], "
              "got %g; keeping %g.\n",
              fraction, boundary_.band_fraction);
    return;
  }
  if ((fraction > 0.0) != (boundary_.band_fraction > 0.0))
    invalidate(); // the edges' creases are kept from the expensive stage only when used
  boundary_.band_fraction = fraction;
}

template <typename PointT>
void pcl::SupernodeNCutSegmentation<PointT>::setBoundaryCreaseWeight(double weight) {
  if (!(weight >= 0.0) || !std::isfinite(weight)) {
    PCL_ERROR("[pcl::SupernodeNCutSegmentation::setBoundaryCreaseWeight] weight must be finite "
              "and >= 0, got %g; keeping %g.\n",
              weight, boundary_.crease_weight);
    return;
  }
  boundary_.crease_weight = weight;
}

template <typename PointT>
void pcl::SupernodeNCutSegmentation<PointT>::setCreaseSplit(double concavity) {
  if (!(concavity >= 0.0) || !std::isfinite(concavity)) {
    PCL_ERROR("[pcl::SupernodeNCutSegmentation::setCreaseSplit] concavity must be finite and "
              ">= 0, got %g; keeping %g.\n",
              concavity, crease_split_);
    return;
  }
  if (concavity != crease_split_)
    invalidate();
  crease_split_ = concavity;
}

template <typename PointT>
void pcl::SupernodeNCutSegmentation<PointT>::setCreaseCut(double share) {
  if (!(share >= 0.0 && share <= 1.0)) {
    PCL_ERROR("[pcl::SupernodeNCutSegmentation::setCreaseCut] share must be in [0, 1], got %g; "
              "keeping %g.\n",
              share, crease_cut_);
    return;
  }
  if (share != crease_cut_)
    invalidate();
  crease_cut_ = share;
}

template <typename PointT>
void pcl::SupernodeNCutSegmentation<PointT>::setAdjacentShare(double share) {
  if (!(share >= 0.0 && share <= 1.0)) {
    PCL_ERROR("[pcl::SupernodeNCutSegmentation::setAdjacentShare] share must be in [0, 1], got "
              "%g; keeping %g.\n",
              share, similarity_.adjacent_share);
    return;
  }
  similarity_.adjacent_share = share;
}

template <typename PointT>
void pcl::SupernodeNCutSegmentation<PointT>::setNumberOfThreads(unsigned threads) {
  num_threads_ = threads; // output does not depend on it, so nothing to invalidate
}

template <typename PointT> void pcl::SupernodeNCutSegmentation<PointT>::setCadMode(bool cad) {
  if (cad != cad_mode_)
    invalidate();
  cad_mode_ = cad;
}

template <typename PointT>
void pcl::SupernodeNCutSegmentation<PointT>::setFaceAngle(float degrees) {
  if (!(degrees > 0.0f && degrees <= 90.0f)) {
    PCL_ERROR("[pcl::SupernodeNCutSegmentation::setFaceAngle] angle must be in (0, 90] "
              "degrees, got %g; keeping %g.\n",
              degrees, cad_.face_angle);
    return;
  }
  if (degrees != cad_.face_angle)
    invalidate();
  cad_.face_angle = degrees;
}

namespace pcl {
namespace ncut_detail {
/// CAD mode: the input's own normal when the point type has one and it is finite and non-zero.
template <typename PointT>
bool inputNormal(const PointT& p, float* n) {
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
} // namespace ncut_detail
} // namespace pcl

template <typename PointT> bool pcl::SupernodeNCutSegmentation<PointT>::analyze() {
  const auto start = std::chrono::steady_clock::now();
  // Valid points: in range, finite, each once; sorted so that graph order is cloud order.
  const std::size_t cloud_size = input_->size();
  std::vector<int> valid;
  valid.reserve(indices_->size());
  for (const auto idx : *indices_) {
    if (idx < 0 || static_cast<std::size_t>(idx) >= cloud_size) {
      PCL_ERROR("[pcl::SupernodeNCutSegmentation::extract] index %d is out of range for a "
                "cloud of %zu points.\n",
                static_cast<int>(idx), cloud_size);
      return false;
    }
    if (pcl::isXYZFinite((*input_)[idx]))
      valid.push_back(static_cast<int>(idx));
  }
  if (!std::is_sorted(valid.begin(), valid.end())) // the usual indices are sorted already
    std::sort(valid.begin(), valid.end());
  const std::size_t before = valid.size();
  valid.erase(std::unique(valid.begin(), valid.end()), valid.end());
  if (valid.size() < before)
    PCL_WARN("[pcl::SupernodeNCutSegmentation::extract] %zu repeated indices ignored.\n",
             before - valid.size());
  // Points at exactly the position of an earlier one are analysed once and share its segment:
  // copies would fill each other's k nearest neighbours with zero-length edges.
  // Graph vertices are numbered along a Morton (Z-order) curve: every phase then reads its
  // neighbours from nearby memory (2-4x faster on large clouds than the input order). Results
  // are reported per input point; segments are numbered by their smallest input index.
  // Ties in the centrality go by input order, so the numbering does not change results.
  if (valid.size() > std::numeric_limits<std::uint32_t>::max() / 64) {
    PCL_ERROR("[pcl::SupernodeNCutSegmentation::extract] too many points (%zu).\n",
              valid.size());
    return false;
  }
  duplicates_.clear();
  std::vector<std::uint32_t> tie_rank;
  std::vector<float> raw; // the input's own coordinates, in vertex order: the kd-tree's points
  {
    const std::size_t m = valid.size();
    raw.resize(3 * m);
    for (std::size_t i = 0; i < m; ++i) {
      const PointT& p = (*input_)[valid[i]];
      raw[3 * i + 0] = p.x;
      raw[3 * i + 1] = p.y;
      raw[3 * i + 2] = p.z;
    }
    pcl_ncut_seg::DistinctMortonOrder order = pcl_ncut_seg::distinctMortonOrder(raw.data(), m);
    std::vector<int> reordered(order.point.size());
    std::vector<float> reordered_raw(3 * order.point.size());
    for (std::size_t v = 0; v < order.point.size(); ++v) {
      reordered[v] = valid[order.point[v]];
      for (std::size_t d = 0; d < 3; ++d) // (no library call per point)
        reordered_raw[3 * v + d] = raw[3 * std::size_t(order.point[v]) + d];
    }
    for (const auto& c : order.copies)
      duplicates_.emplace_back(valid[c.first], c.second);
    valid.swap(reordered);
    raw.swap(reordered_raw);
    tie_rank = std::move(order.rank);
  }
  const std::size_t n = valid.size();
  if (n == 0) {
    PCL_ERROR("[pcl::SupernodeNCutSegmentation::extract] the input has no finite point.\n");
    return false;
  }

  // Coordinates relative to the centroid, in double first, so that a model far from the
  // origin keeps its float precision.
  // (raw holds the input's x, y, z in vertex order.)
  double c[3] = {0, 0, 0};
  for (std::size_t i = 0; i < n; ++i)
    for (int d = 0; d < 3; ++d)
      c[d] += raw[3 * i + d];
  for (double& v : c)
    v /= static_cast<double>(n);
  std::vector<float> xyz(3 * n);
  for (std::size_t i = 0; i < 3 * n; ++i)
    xyz[i] = static_cast<float>(raw[i] - c[i % 3]);

  if (progress_)
    progress_("kNN", 0.0);
  // Sec. 4.1: the k nearest neighbours of each point (fewer when there are fewer points).
  const std::size_t k = std::min<std::size_t>(static_cast<std::size_t>(k_), n - 1);
  if (k < static_cast<std::size_t>(k_))
    PCL_WARN("[pcl::SupernodeNCutSegmentation::extract] only %zu points: using %zu "
             "neighbours instead of %d.\n",
             n, k, k_);
  std::vector<std::uint32_t> knn(n * std::max<std::size_t>(k, 1),
                                 std::numeric_limits<std::uint32_t>::max());
  const int threads = pcl_ncut_seg::usableThreads(num_threads_);
  if (k > 0 && !search_) {
    // The default: FLANN's kd-tree as pcl::search::KdTree builds it, over a compact copy of
    // the points in vertex order, queried in parallel without PCL's per-query wrapping.
    pcl_ncut_seg::kNearestNeighbours(raw.data(), n, k, threads, knn.data());
  } else if (k > 0) {
    pcl::IndicesPtr valid_ptr(new pcl::Indices(valid.begin(), valid.end()));
    search_->setInputCloud(input_, valid_ptr);
    std::vector<std::int64_t> local(cloud_size, -1);
    for (std::size_t i = 0; i < n; ++i)
      local[valid[i]] = static_cast<std::int64_t>(i);
    // Queries in vertex (Morton) order visit the search tree coherently.
#pragma omp parallel num_threads(threads)
    {
      pcl::Indices nn;
      std::vector<float> sqr;
#pragma omp for schedule(dynamic, 256)
      for (std::ptrdiff_t qi = 0; qi < static_cast<std::ptrdiff_t>(n); ++qi) {
        const auto i = static_cast<std::size_t>(qi);
        nn.clear();
        search_->nearestKSearch((*input_)[valid[i]], static_cast<int>(k + 1), nn, sqr);
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
  std::vector<float>().swap(raw);
  pcl_ncut_seg::CsrGraph graph =
      pcl_ncut_seg::buildSymmetricKnnGraph(xyz.data(), n, knn.data(), k, threads);
  std::vector<std::uint32_t>().swap(knn); // free before the expensive stage
  if (bridge_gap_ > 0.0)
    pcl_ncut_seg::bridgeComponents(graph, xyz.data(), bridge_gap_);
  const bool refine_boundaries = !cad_mode_ && boundary_.band_fraction > 0.0;
  if (!cad_mode_ && !(similarity_.concavity_weight > 0.0) && !refine_boundaries &&
      !(crease_split_ > 0.0) && !(crease_cut_ > 0.0)) // still needed by these
    std::vector<float>().swap(xyz);
  times_ = pcl_ncut_seg::PhaseTimes();
  times_.knn = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  if (progress_)
    progress_("kNN", 1.0);

  pcl_ncut_seg::AnalysisParams params;
  params.num_samples = static_cast<std::size_t>(num_samples_);
  params.centrality_mode = centrality_mode_;
  params.num_representatives = static_cast<std::size_t>(num_representatives_);
  params.crossing_fraction = crossing_fraction_;
  params.refinement.area_fraction = area_fraction_;
  params.refinement.height_fraction = height_fraction_;
  params.num_threads = num_threads_;
  params.progress = progress_;
  params.tie_rank = std::move(tie_rank);
  if (cad_mode_) {
    // Sec. 7: approximate normals, from the input or fitted by PCL over p and N(p); their time
    // counts as kNN time, as in the paper's Table 1.
    const auto normals_start = std::chrono::steady_clock::now();
    std::vector<float> normals(3 * n, std::numeric_limits<float>::quiet_NaN());
    pcl::Indices neighbourhood;
    Eigen::Vector4f plane;
    float curvature;
    for (std::size_t i = 0; i < n; ++i) {
      if (ncut_detail::inputNormal((*input_)[valid[i]], &normals[3 * i]))
        continue;
      neighbourhood.assign(1, valid[i]);
      for (std::uint32_t e = graph.offsets[i]; e < graph.offsets[i + 1]; ++e)
        neighbourhood.push_back(valid[graph.targets[e]]);
      if (neighbourhood.size() >= 3 &&
          pcl::computePointNormal(*input_, neighbourhood, plane, curvature))
        for (int d = 0; d < 3; ++d)
          normals[3 * i + d] = plane[d];
    }
    times_.knn +=
        std::chrono::duration<double>(std::chrono::steady_clock::now() - normals_start).count();
    analysis_ = std::make_shared<pcl_ncut_seg::Analysis>(
        pcl_ncut_seg::analyzeCad(graph, xyz.data(), normals.data(), params, cad_, times_));
  } else {
    analysis_ = std::make_shared<pcl_ncut_seg::Analysis>(
        pcl_ncut_seg::analyze(std::move(graph), params, times_));
    std::vector<float> normals;
    double typical_bend = 0.0; // meanAbsBend(), computed once for the three users below
    if (crease_split_ > 0.0 || crease_cut_ > 0.0) {
      // Split supernodes along concave creases (core/crease_split.h): refinement time.
      const auto crease_start = std::chrono::steady_clock::now();
      pcl_ncut_seg::Analysis& a = *analysis_;
      normals = pcl_ncut_seg::orientedNormals(a.graph, xyz.data(), num_threads_);
      typical_bend = pcl_ncut_seg::meanAbsBend(a.graph, xyz.data(), normals, num_threads_);
      pcl_ncut_seg::CreaseSplitParams crease;
      crease.typical_bend = typical_bend;
      crease.min_concavity = crease_split_;
      crease.cut_concavity = crease_cut_;
      crease.area_fraction = area_fraction_;
      crease.num_threads = num_threads_;
      std::size_t splits = 0;
      a.supernodes = pcl_ncut_seg::splitAtCreases(a.graph, xyz.data(), normals, a.centrality.f,
                                                  a.radii, a.supernodes, crease, &splits);
      if (splits > 0) {
        a.stats = pcl_ncut_seg::featureStats(a.supernodes, a.centrality.f, a.radii);
        a.conn =
            pcl_ncut_seg::supernodeConnectivity(a.graph, a.centrality.f, a.supernodes.label,
                                                num_threads_);
      }
      times_.refinement +=
          std::chrono::duration<double>(std::chrono::steady_clock::now() - crease_start).count();
    }
    if (similarity_.concavity_weight > 0.0 || refine_boundaries) {
      // Measured between the supernodes, like eq. (8): its time counts as refinement time.
      const auto concavity_start = std::chrono::steady_clock::now();
      if (normals.empty()) {
        normals = pcl_ncut_seg::orientedNormals(analysis_->graph, xyz.data(), num_threads_);
        typical_bend =
            pcl_ncut_seg::meanAbsBend(analysis_->graph, xyz.data(), normals, num_threads_);
      }
      if (similarity_.concavity_weight > 0.0)
        analysis_->concavity =
            pcl_ncut_seg::contactConcavity(analysis_->graph, xyz.data(), normals,
                                           analysis_->supernodes.label, typical_bend);
      if (refine_boundaries)
        analysis_->crease = pcl_ncut_seg::edgeCreases(analysis_->graph, xyz.data(), normals,
                                                      num_threads_, typical_bend);
      times_.refinement +=
          std::chrono::duration<double>(std::chrono::steady_clock::now() - concavity_start)
              .count();
    }
  }
  point_index_ = std::move(valid);
  return true;
}

template <typename PointT>
void pcl::SupernodeNCutSegmentation<PointT>::extract(std::vector<pcl::PointIndices>& segments) {
  segments.clear();
  have_result_ = false;
  if (!initCompute()) {
    PCL_ERROR("[pcl::SupernodeNCutSegmentation::extract] no input cloud.\n");
    return;
  }
  if (!analysis_ && !analyze()) {
    invalidate();
    deinitCompute();
    return;
  }
  if (progress_)
    progress_("HSeg", 0.0);
  result_ = pcl_ncut_seg::cut(*analysis_, similarity_, cut_, times_);
  if (!analysis_->cad && boundary_.band_fraction > 0.0) {
    // Point-level boundaries (core/boundary_refinement.h): point segmentation time.
    const auto boundary_start = std::chrono::steady_clock::now();
    pcl_ncut_seg::refineBoundaries(analysis_->graph, analysis_->radii, analysis_->crease,
                                   boundary_, result_.point_segment, result_.num_segments);
    times_.points +=
        std::chrono::duration<double>(std::chrono::steady_clock::now() - boundary_start).count();
  }
  // Number segments in order of their smallest input index (vertices are in Morton order).
  std::vector<int> smallest(result_.num_segments, std::numeric_limits<int>::max());
  for (std::size_t i = 0; i < point_index_.size(); ++i) {
    int& m = smallest[result_.point_segment[i]];
    m = std::min(m, point_index_[i]);
  }
  std::vector<std::uint32_t> by_smallest(result_.num_segments), rank(result_.num_segments);
  for (std::uint32_t s = 0; s < by_smallest.size(); ++s)
    by_smallest[s] = s;
  std::sort(by_smallest.begin(), by_smallest.end(),
            [&](std::uint32_t a, std::uint32_t b) { return smallest[a] < smallest[b]; });
  for (std::uint32_t r = 0; r < by_smallest.size(); ++r)
    rank[by_smallest[r]] = r;
  for (auto& s : result_.point_segment)
    s = rank[s];
  for (auto& s : result_.supernode_segment)
    if (s < rank.size())
      s = rank[s];
  if (progress_)
    progress_("HSeg", 1.0);
  segments.resize(result_.num_segments);
  for (std::size_t i = 0; i < point_index_.size(); ++i)
    segments[result_.point_segment[i]].indices.push_back(point_index_[i]);
  for (const auto& d : duplicates_)
    segments[result_.point_segment[d.second]].indices.push_back(d.first);
  for (auto& s : segments)
    std::sort(s.indices.begin(), s.indices.end());
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
    segmentColor(result_.point_segment[i], q.r, q.g, q.b);
  }
  for (const auto& d : duplicates_) {
    auto& q = (*out)[d.first];
    segmentColor(result_.point_segment[d.second], q.r, q.g, q.b);
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
    (*out)[point_index_[i]].label = result_.point_segment[i] + 1;
  for (const auto& d : duplicates_)
    (*out)[d.first].label = result_.point_segment[d.second] + 1;
  return out;
}

template <typename PointT>
std::vector<float> pcl::SupernodeNCutSegmentation<PointT>::getCentrality() const {
  std::vector<float> out(input_ ? input_->size() : 0, std::numeric_limits<float>::quiet_NaN());
  if (analysis_)
    for (std::size_t i = 0; i < point_index_.size(); ++i)
      out[point_index_[i]] = analysis_->centrality.f[i];
  if (analysis_)
    for (const auto& d : duplicates_)
      out[d.first] = analysis_->centrality.f[d.second];
  return out;
}

template <typename PointT>
std::vector<int> pcl::SupernodeNCutSegmentation<PointT>::getLocalMaxima() const {
  std::vector<int> out;
  if (analysis_)
    for (std::uint32_t v : analysis_->raw_supernodes.localMaxima())
      out.push_back(point_index_[v]);
  return out;
}

template <typename PointT>
std::vector<int> pcl::SupernodeNCutSegmentation<PointT>::getSaddles() const {
  std::vector<int> out;
  if (analysis_)
    for (std::uint32_t v : analysis_->raw_supernodes.saddles())
      out.push_back(point_index_[v]);
  return out;
}

template <typename PointT>
std::vector<int> pcl::SupernodeNCutSegmentation<PointT>::getSupernodeLabels(bool refined) const {
  std::vector<int> out(input_ ? input_->size() : 0, -1);
  if (analysis_) {
    const auto& label = refined ? analysis_->supernodes.label : analysis_->raw_supernodes.label;
    for (std::size_t i = 0; i < point_index_.size(); ++i)
      out[point_index_[i]] = static_cast<int>(label[i]);
    for (const auto& d : duplicates_)
      out[d.first] = static_cast<int>(label[d.second]);
  }
  return out;
}

template <typename PointT>
std::size_t pcl::SupernodeNCutSegmentation<PointT>::getNumberOfSupernodes(bool refined) const {
  if (!analysis_)
    return 0;
  return refined ? analysis_->supernodes.size() : analysis_->raw_supernodes.size();
}

#define PCL_INSTANTIATE_SupernodeNCutSegmentation(T)                                               \
  template class PCL_EXPORTS pcl::SupernodeNCutSegmentation<T>;
