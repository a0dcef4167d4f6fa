/*
 * pcl_ncut_seg benchmarks: what more than one bench program segments or runs, set up once.
 */
#pragma once

#include "psb_peers.h"
#include <surfaces/depth_view_pcl.h>

#include <pcl/point_cloud.h>
#include <pcl/point_types.h>

#include <array>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <optional>
#include <string>
#include <vector>

namespace pcl_ncut_seg_bench {

/// LCCP's settings on whole objects (view false) or views, as results/peer_settings.csv holds
/// them (chosen on the benchmark's dev split by scripts/tune_peers.sh); exits with a one-line
/// reason when the file cannot be read.
inline pcl_ncut_seg::PeerParams chosenLccp(bool view) {
  pcl_ncut_seg::PeerSettings settings;
  std::string error;
  if (!pcl_ncut_seg::readPeerSettings(PCL_NCUT_SEG_PEER_SETTINGS, settings, &error)) {
    std::fprintf(stderr, "%s: %s\n", PCL_NCUT_SEG_PEER_SETTINGS, error.c_str());
    std::exit(2);
  }
  return settings.of(false, view);
}

/// PCL's part segmenter as a user who tuned it runs it (PCL's normals, supervoxels, LCCP with
/// the sanity criterion, at chosenLccp(view)); normals face the viewpoint if given, else away
/// from the centroid. One label per point, 0 for none; exits when LCCP fails.
inline pcl::PointCloud<pcl::PointXYZL>::Ptr
lccpLabels(const pcl::PointCloud<pcl::PointXYZ>& cloud, bool view,
           std::optional<std::array<float, 3>> viewpoint = std::nullopt) {
  std::vector<float> xyz;
  xyz.reserve(3 * cloud.size());
  for (const auto& p : cloud)
    xyz.insert(xyz.end(), {p.x, p.y, p.z});
  pcl_ncut_seg::PeerParams params = chosenLccp(view);
  params.viewpoint = viewpoint;
  std::vector<int> labels;
  std::string error;
  if (!pcl_ncut_seg::segmentWithPclPeer(xyz, false, params, labels, &error)) {
    std::fprintf(stderr, "LCCP failed: %s\n", error.c_str());
    std::exit(2);
  }
  pcl::PointCloud<pcl::PointXYZL>::Ptr out(new pcl::PointCloud<pcl::PointXYZL>);
  out->resize(cloud.size());
  for (std::size_t i = 0; i < cloud.size(); ++i) {
    pcl::PointXYZL& q = (*out)[i];
    q.x = cloud[i].x, q.y = cloud[i].y, q.z = cloud[i].z;
    q.label = labels[i] < 0 ? 0u : static_cast<std::uint32_t>(labels[i]);
  }
  return out;
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
