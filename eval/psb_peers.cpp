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
#include <limits>
#include <map>

namespace pcl_ncut_seg {

bool segmentWithPclPeer(const std::vector<float>& xyz, bool cpc, const PeerParams& params,
                        std::vector<int>& labels, std::string* error) {
  using PointT = pcl::PointXYZRGBA;
  const std::size_t n = xyz.size() / 3;
  if (n < 3) {
    if (error)
      *error = "fewer than 3 points";
    return false;
  }
  pcl::PointCloud<PointT>::Ptr cloud(new pcl::PointCloud<PointT>);
  cloud->resize(n);
  Eigen::Vector3d lo = Eigen::Vector3d::Constant(std::numeric_limits<double>::max());
  Eigen::Vector3d hi = -lo, centroid = Eigen::Vector3d::Zero();
  for (std::size_t i = 0; i < n; ++i) {
    PointT& p = (*cloud)[i];
    p.x = xyz[3 * i];
    p.y = xyz[3 * i + 1];
    p.z = xyz[3 * i + 2];
    p.rgba = 0xffffffff;
    const Eigen::Vector3d v(p.x, p.y, p.z);
    lo = lo.cwiseMin(v);
    hi = hi.cwiseMax(v);
    centroid += v;
  }
  centroid /= static_cast<double>(n);
  const double diagonal = (hi - lo).norm();
  if (!(diagonal > 0)) {
    if (error)
      *error = "the points have no extent";
    return false;
  }

  // Normals, oriented towards the viewpoint, or away from the centroid (towards it, flipped).
  pcl::PointCloud<pcl::Normal>::Ptr normals(new pcl::PointCloud<pcl::Normal>);
  pcl::NormalEstimation<PointT, pcl::Normal> estimation;
  estimation.setInputCloud(cloud);
  estimation.setSearchMethod(pcl::search::KdTree<PointT>::Ptr(new pcl::search::KdTree<PointT>));
  estimation.setKSearch(params.normal_neighbours);
  const auto& vp = params.viewpoint;
  estimation.setViewPoint(vp ? (*vp)[0] : static_cast<float>(centroid.x()),
                          vp ? (*vp)[1] : static_cast<float>(centroid.y()),
                          vp ? (*vp)[2] : static_cast<float>(centroid.z()));
  estimation.compute(*normals);
  for (auto& nrm : *normals) {
    if (!vp) {
      nrm.normal_x = -nrm.normal_x;
      nrm.normal_y = -nrm.normal_y;
      nrm.normal_z = -nrm.normal_z;
    }
    if (!std::isfinite(nrm.normal_x) || !std::isfinite(nrm.normal_y) ||
        !std::isfinite(nrm.normal_z)) {
      nrm.normal_x = nrm.normal_y = 0.0f; // degenerate neighbourhood: any unit vector
      nrm.normal_z = 1.0f;
      nrm.curvature = 0.0f;
    }
  }

  const auto voxel = static_cast<float>(params.voxel_fraction * diagonal);
  const auto seed = static_cast<float>(params.seed_fraction * diagonal);
  pcl::SupervoxelClustering<PointT> supervoxels(voxel, seed);
  supervoxels.setUseSingleCameraTransform(false);
  supervoxels.setInputCloud(cloud);
  supervoxels.setNormalCloud(normals);
  supervoxels.setColorImportance(0.0f);
  supervoxels.setSpatialImportance(1.0f);
  supervoxels.setNormalImportance(4.0f);
  std::map<std::uint32_t, pcl::Supervoxel<PointT>::Ptr> clusters;
  supervoxels.extract(clusters);
  if (clusters.empty()) {
    if (error)
      *error = "no supervoxels";
    return false;
  }
  std::multimap<std::uint32_t, std::uint32_t> adjacency;
  supervoxels.getSupervoxelAdjacency(adjacency);
  pcl::PointCloud<pcl::PointXYZL>::Ptr labeled = supervoxels.getLabeledCloud();
  if (labeled->size() != n) {
    if (error)
      *error = "supervoxel labels do not match the points";
    return false;
  }

  if (cpc) {
    pcl::CPCSegmentation<PointT> seg;
    seg.setConcavityToleranceThreshold(params.concavity_tolerance);
    seg.setSanityCheck(false);
    seg.setSmoothnessCheck(true, voxel, seed, params.smoothness_threshold);
    seg.setKFactor(0);
    seg.setInputSupervoxels(clusters, adjacency);
    seg.setMinSegmentSize(params.min_segment_size);
    seg.setCutting(params.cpc_max_cuts, params.cpc_min_segments_to_cut, params.cpc_min_cut_score,
                   params.cpc_local_constrain, params.cpc_directed_cutting,
                   params.cpc_clean_cutting);
    seg.setRANSACIterations(params.cpc_ransac_iterations);
    seg.segment();
    seg.relabelCloud(*labeled);
  } else {
    pcl::LCCPSegmentation<PointT> seg;
    seg.setConcavityToleranceThreshold(params.concavity_tolerance);
    seg.setSanityCheck(false);
    seg.setSmoothnessCheck(true, voxel, seed, params.smoothness_threshold);
    seg.setKFactor(0);
    seg.setInputSupervoxels(clusters, adjacency);
    seg.setMinSegmentSize(params.min_segment_size);
    seg.segment();
    seg.relabelCloud(*labeled);
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
