/*
 * pcl_ncut_seg: the segmenters the evaluation compares against, over plain arrays of points
 * (x, y, z per point). Each returns one label per point, -1 for a point in no segment.
 */
#pragma once

#include <array>
#include <optional>
#include <string>
#include <vector>

namespace pcl_ncut_seg {

/** \brief Where LCCP's and CPC's normals come from. */
enum class PeerNormals {
  Estimated, ///< PCL's normal estimation, then oriented (towards the sensor, or outward)
  Mesh,      ///< the outward normals given with the points (a mesh's), as they are
};

/** \brief One setting for every model, in units of the model's bounding-box diagonal d. */
struct PeerParams {
  double voxel_fraction = 0.01; ///< supervoxel voxel resolution = voxel_fraction * d
  double seed_fraction = 0.05;  ///< supervoxel seed resolution = seed_fraction * d
  int normal_neighbours = 10;   ///< k of PCL's normal estimation
  PeerNormals normals = PeerNormals::Estimated;
  float concavity_tolerance = 10.0f; ///< degrees (LCCP and CPC)
  bool sanity_check = true;          ///< LCCP's sanity criterion (convexity needs consistency)
  float smoothness_threshold = 0.1f; ///< LCCP smoothness check
  unsigned min_segment_size = 0;     ///< supervoxels; smaller segments are merged (0 = off)
  unsigned cpc_max_cuts = 25;
  unsigned cpc_min_segments_to_cut = 10; ///< supervoxels a segment needs before it is cut
  float cpc_min_cut_score = 0.16f;
  bool cpc_local_constrain = true;
  bool cpc_directed_cutting = true;
  bool cpc_clean_cutting = true;
  unsigned cpc_ransac_iterations = 1000;
  /// Where the points were seen from (a sensor's origin): normals are oriented towards it, as
  /// PCL orients a view's normals.
  std::optional<std::array<float, 3>> viewpoint;
};

/** \brief LCCP's and CPC's settings on whole objects and on views: the file that
 * scripts/tune_peers.py writes (results/peer_settings.csv) from its grid on the dev split. */
struct PeerSettings {
  PeerParams lccp_whole, lccp_views, cpc_whole, cpc_views;

  PeerParams& of(bool cpc, bool view) {
    return cpc ? (view ? cpc_views : cpc_whole) : (view ? lccp_views : lccp_whole);
  }
  const PeerParams& of(bool cpc, bool view) const {
    return const_cast<PeerSettings*>(this)->of(cpc, view);
  }
};

/** \brief Read a settings file: a CSV header "peer,kind,voxel,seed,normals,concavity,
 * min_segment,cut_score,max_cuts", then a row per peer (lccp, cpc) and kind (whole, views).
 * Settings not in the file keep PeerParams' defaults.
 * \return false with a one-line reason on a file that cannot be read or a malformed row. */
bool readPeerSettings(const std::string& path, PeerSettings& settings, std::string* error);

/** \brief PCL's LCCP (cpc = false) or CPC (cpc = true) segmentation on supervoxels, with the
 * sanity criterion and the smoothness check as params say.
 * \param[in] xyz the points, x y z each
 * \param[in] outward if not null, an outward normal per point (x y z each, from the mesh the
 *            points lie on): used as the normals with PeerNormals::Mesh, else to orient PCL's
 *            estimated normals. Without it, estimated normals face params.viewpoint if given,
 *            else away from the points' centroid.
 * \param[out] labels a label per point; -1 where no supervoxel takes the point
 * \return false with a reason on failure. */
bool segmentWithPclPeer(const std::vector<float>& xyz, bool cpc, const PeerParams& params,
                        std::vector<int>& labels, std::string* error = nullptr,
                        const std::vector<float>* outward = nullptr);

/** \brief The eight octants around the centroid: a baseline that games the Rand index. */
std::vector<int> segmentOctants(const std::vector<float>& xyz);

} // namespace pcl_ncut_seg
