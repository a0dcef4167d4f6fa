// PCL's LCCP and CPC part segmenters on supervoxels (the heavy PCL templates live only here).
#include "psb_peers.h"

#include <pcl/features/normal_3d.h>
#include <pcl/point_cloud.h>
#include <pcl/point_types.h>
#include <pcl/search/kdtree.h>
#include <pcl/segmentation/cpc_segmentation.h>
#include <pcl/segmentation/lccp_segmentation.h>
#include <pcl/segmentation/supervoxel_clustering.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <fstream>
#include <limits>
#include <map>
#include <sstream>
#include <stdexcept>

namespace pcl_ncut_seg {
namespace {

using PointT = pcl::PointXYZRGBA;
using Normals = pcl::PointCloud<pcl::Normal>;

void setError(std::string* error, const char* message) {
  if (error)
    *error = message;
}

/** The normals LCCP and CPC see: the given outward ones, or PCL's estimate oriented by them, by
 * the viewpoint, or away from the centroid. */
Normals::Ptr peerNormals(const pcl::PointCloud<PointT>::Ptr& cloud, const PeerParams& params,
                         const std::vector<float>* outward, const Eigen::Vector3f& centroid) {
  Normals::Ptr normals(new Normals);
  const std::size_t n = cloud->size();
  if (outward && params.normals == PeerNormals::Mesh) {
    normals->resize(n);
    for (std::size_t i = 0; i < n; ++i)
      (*normals)[i].getNormalVector3fMap() =
          Eigen::Vector3f((*outward)[3 * i], (*outward)[3 * i + 1], (*outward)[3 * i + 2]);
    return normals;
  }
  pcl::NormalEstimation<PointT, pcl::Normal> estimation;
  estimation.setInputCloud(cloud);
  estimation.setSearchMethod(pcl::search::KdTree<PointT>::Ptr(new pcl::search::KdTree<PointT>));
  estimation.setKSearch(params.normal_neighbours);
  const Eigen::Vector3f vp =
      params.viewpoint
          ? Eigen::Vector3f((*params.viewpoint)[0], (*params.viewpoint)[1], (*params.viewpoint)[2])
          : centroid;
  estimation.setViewPoint(vp.x(), vp.y(), vp.z());
  estimation.compute(*normals);
  for (std::size_t i = 0; i < n; ++i) {
    auto nrm = (*normals)[i].getNormalVector3fMap();
    if (!nrm.allFinite()) {
      nrm = Eigen::Vector3f::UnitZ(); // degenerate neighbourhood: any unit vector
      (*normals)[i].curvature = 0.0f;
      continue;
    }
    // Towards the centroid (PCL's orientation to it) flipped: away from it.
    const bool flip = outward ? nrm.dot(Eigen::Vector3f((*outward)[3 * i], (*outward)[3 * i + 1],
                                                        (*outward)[3 * i + 2])) < 0
                              : !params.viewpoint;
    if (flip)
      nrm = -nrm;
  }
  return normals;
}

/** The settings both segmenters share, then the segmentation into the supervoxels' labels. */
template <typename Segmentation>
void segmentSupervoxels(Segmentation& seg, const PeerParams& params, float voxel, float seed,
                        const std::map<std::uint32_t, pcl::Supervoxel<PointT>::Ptr>& clusters,
                        const std::multimap<std::uint32_t, std::uint32_t>& adjacency,
                        pcl::PointCloud<pcl::PointXYZL>& labeled) {
  seg.setConcavityToleranceThreshold(params.concavity_tolerance);
  seg.setSanityCheck(params.sanity_check);
  seg.setSmoothnessCheck(true, voxel, seed, params.smoothness_threshold);
  seg.setKFactor(0);
  seg.setInputSupervoxels(clusters, adjacency);
  seg.setMinSegmentSize(params.min_segment_size);
  seg.segment();
  seg.relabelCloud(labeled);
}

} // namespace

namespace {

/** One row's settings over p; false if a field does not parse. */
bool parseSettingsRow(const std::vector<std::string>& f, PeerParams& p) {
  try {
    std::size_t used = 0;
    auto number = [&used](const std::string& text) {
      const double v = std::stod(text, &used);
      if (used != text.size() || !std::isfinite(v) || v < 0)
        throw std::invalid_argument(text);
      return v;
    };
    p.voxel_fraction = number(f[2]);
    p.seed_fraction = number(f[3]);
    if (f[4] != "estimated" && f[4] != "mesh")
      return false;
    p.normals = f[4] == "mesh" ? PeerNormals::Mesh : PeerNormals::Estimated;
    p.concavity_tolerance = static_cast<float>(number(f[5]));
    p.min_segment_size = static_cast<unsigned>(number(f[6]));
    p.cpc_min_cut_score = static_cast<float>(number(f[7]));
    p.cpc_max_cuts = static_cast<unsigned>(number(f[8]));
  } catch (const std::exception&) {
    return false;
  }
  return p.voxel_fraction > 0 && p.voxel_fraction < p.seed_fraction;
}

} // namespace

bool readPeerSettings(const std::string& path, PeerSettings& settings, std::string* error) {
  std::ifstream in(path);
  const std::string header = "peer,kind,voxel,seed,normals,concavity,min_segment,cut_score,"
                             "max_cuts";
  std::string line;
  if (!in || !std::getline(in, line) || line != header) {
    setError(error, "not a peer settings file (its first line is not the expected header)");
    return false;
  }
  PeerSettings read = settings;
  for (int row = 2; std::getline(in, line); ++row) {
    std::vector<std::string> f;
    std::stringstream fields(line);
    for (std::string field; std::getline(fields, field, ',');)
      f.push_back(field);
    const bool known_peer =
        f.size() == 9 && (f[0] == "lccp" || f[0] == "cpc") && (f[1] == "whole" || f[1] == "views");
    PeerParams* p = known_peer ? &read.of(f[0] == "cpc", f[1] == "views") : nullptr;
    if (!p || !parseSettingsRow(f, *p)) {
      if (error)
        *error = "bad row " + std::to_string(row) + " in the peer settings";
      return false;
    }
  }
  settings = read;
  return true;
}

bool segmentWithPclPeer(const std::vector<float>& xyz, bool cpc, const PeerParams& params,
                        std::vector<int>& labels, std::string* error,
                        const std::vector<float>* outward) {
  const std::size_t n = xyz.size() / 3;
  if (n < 3) {
    setError(error, "fewer than 3 points");
    return false;
  }
  if (outward && outward->size() != xyz.size()) {
    setError(error, "not one normal per point");
    return false;
  }
  pcl::PointCloud<PointT>::Ptr cloud(new pcl::PointCloud<PointT>);
  cloud->resize(n);
  Eigen::Vector3f lo = Eigen::Vector3f::Constant(std::numeric_limits<float>::max());
  Eigen::Vector3f hi = -lo;
  Eigen::Vector3d sum = Eigen::Vector3d::Zero();
  for (std::size_t i = 0; i < n; ++i) {
    PointT& p = (*cloud)[i];
    p.getVector3fMap() = Eigen::Vector3f(xyz[3 * i], xyz[3 * i + 1], xyz[3 * i + 2]);
    p.rgba = 0xffffffff;
    lo = lo.cwiseMin(p.getVector3fMap());
    hi = hi.cwiseMax(p.getVector3fMap());
    sum += p.getVector3fMap().cast<double>();
  }
  const double diagonal = (hi - lo).cast<double>().norm();
  if (!(diagonal > 0)) {
    setError(error, "the points have no extent");
    return false;
  }
  const Eigen::Vector3f centroid = (sum / static_cast<double>(n)).cast<float>();

  const auto voxel = static_cast<float>(params.voxel_fraction * diagonal);
  const auto seed = static_cast<float>(params.seed_fraction * diagonal);
  pcl::SupervoxelClustering<PointT> supervoxels(voxel, seed);
  supervoxels.setUseSingleCameraTransform(false);
  supervoxels.setInputCloud(cloud);
  supervoxels.setNormalCloud(peerNormals(cloud, params, outward, centroid));
  supervoxels.setColorImportance(0.0f);
  supervoxels.setSpatialImportance(1.0f);
  supervoxels.setNormalImportance(4.0f);
  std::map<std::uint32_t, pcl::Supervoxel<PointT>::Ptr> clusters;
  supervoxels.extract(clusters);
  if (clusters.empty()) {
    setError(error, "no supervoxels");
    return false;
  }
  std::multimap<std::uint32_t, std::uint32_t> adjacency;
  supervoxels.getSupervoxelAdjacency(adjacency);
  pcl::PointCloud<pcl::PointXYZL>::Ptr labeled = supervoxels.getLabeledCloud();
  if (labeled->size() != n) {
    setError(error, "supervoxel labels do not match the points");
    return false;
  }

  if (cpc) {
    pcl::CPCSegmentation<PointT> seg;
    seg.setCutting(params.cpc_max_cuts, params.cpc_min_segments_to_cut, params.cpc_min_cut_score,
                   params.cpc_local_constrain, params.cpc_directed_cutting,
                   params.cpc_clean_cutting);
    seg.setRANSACIterations(params.cpc_ransac_iterations);
    segmentSupervoxels(seg, params, voxel, seed, clusters, adjacency, *labeled);
  } else {
    pcl::LCCPSegmentation<PointT> seg;
    segmentSupervoxels(seg, params, voxel, seed, clusters, adjacency, *labeled);
  }
  labels.assign(n, -1);
  for (std::size_t i = 0; i < n; ++i)
    if ((*labeled)[i].label != 0)
      labels[i] = static_cast<int>((*labeled)[i].label);
  return true;
}

std::vector<int> segmentOctants(const std::vector<float>& xyz) {
  const std::size_t n = xyz.size() / 3;
  double c[3] = {0, 0, 0};
  for (std::size_t i = 0; i < n; ++i)
    for (int d = 0; d < 3; ++d)
      c[d] += xyz[3 * i + d];
  for (double& v : c)
    v /= std::max<std::size_t>(n, 1);
  std::vector<int> labels(n);
  for (std::size_t i = 0; i < n; ++i)
    labels[i] = (xyz[3 * i] > c[0]) | (xyz[3 * i + 1] > c[1]) << 1 | (xyz[3 * i + 2] > c[2]) << 2;
  return labels;
}

} // namespace pcl_ncut_seg
