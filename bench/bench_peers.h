/*
 * pcl_ncut_seg benchmarks: what more than one bench program segments or runs, set up once.
 */
#pragma once

#include "depth_view_pcl.h"

#include <pcl/segmentation/lccp_segmentation.h>
#include <pcl/segmentation/supervoxel_clustering.h>

#include <cmath>
#include <cstdint>
#include <map>

namespace pcl_ncut_seg_bench {

/// PCL's part segmenter on a whole model as its tutorial runs it: supervoxels (with their own
/// normal estimate per voxel), then LCCP over their adjacency; voxels of `voxel`, seeds of four
/// voxels. One label per point of the cloud.
inline pcl::PointCloud<pcl::PointXYZL>::Ptr
lccpWholeModel(const pcl::PointCloud<pcl::PointXYZ>::Ptr& cloud, float voxel) {
  pcl::SupervoxelClustering<pcl::PointXYZ> super(voxel, 4.0f * voxel);
  super.setUseSingleCameraTransform(false);
  super.setInputCloud(cloud);
  super.setColorImportance(0.0f);
  super.setSpatialImportance(1.0f);
  super.setNormalImportance(4.0f);
  std::map<std::uint32_t, pcl::Supervoxel<pcl::PointXYZ>::Ptr> clusters;
  super.extract(clusters);
  std::multimap<std::uint32_t, std::uint32_t> adjacency;
  super.getSupervoxelAdjacency(adjacency);
  pcl::LCCPSegmentation<pcl::PointXYZ> lccp;
  lccp.setConcavityToleranceThreshold(10.0f);
  lccp.setSmoothnessCheck(true, voxel, 4.0f * voxel, 0.1f);
  lccp.setKFactor(0);
  lccp.setInputSupervoxels(clusters, adjacency);
  lccp.segment();
  pcl::PointCloud<pcl::PointXYZL>::Ptr labels = super.getLabeledCloud();
  lccp.relabelCloud(*labels);
  return labels;
}

/// One object alone in a depth camera's frame (the views bench's "(a)"): the default camera
/// moved to the distance that gives the object about `pixels` valid pixels.
inline pcl_ncut_seg::DepthView objectView(const pcl_ncut_seg::TriangleMesh& mesh,
                                          std::size_t pixels) {
  pcl_ncut_seg::CameraSettings cam;
  const std::uint64_t seed = pcl_ncut_seg::viewSeed(1, 0);
  const auto first = pcl_ncut_seg::renderView(mesh, cam, seed);
  // The image of an object shrinks with the square of its distance.
  cam.distance *= std::sqrt(static_cast<double>(first.validPixels()) / pixels);
  return pcl_ncut_seg::renderView(mesh, cam, seed);
}

} // namespace pcl_ncut_seg_bench
