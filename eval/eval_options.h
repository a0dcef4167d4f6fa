/*
 * pcl_ncut_seg_eval's command line: its flags (what to run, on which models, the sweeps of
 * 'ours', and the algorithm's own), the help, and the options read from them; and Failure,
 * the reason to stop that every step throws.
 */
#pragma once

#include "eval_sampling.h"
#include "psb_peers.h"
#include <cli/flags.h>
#include <surfaces/depth_view.h>

#include <pcl_ncut_seg/parameters.h>

#include <algorithm>
#include <stdexcept>
#include <string>
#include <vector>

namespace pcl_ncut_seg {
namespace eval {

/** A reason to stop, thrown by a step and printed as one line by main(). */
struct Failure : std::runtime_error {
  using std::runtime_error::runtime_error;
};

/** The methods and the modes of -methods and -modes. */
extern const std::vector<std::string> kAllMethods;
/** The methods of the finest level, run only when -methods names them (issue 63's diagnostic):
 * "finest" (the cut asked for -oracle_segments parts, scored as it is), "oracle" and
 * "kmeans_oracle" (eval_oracle.h: they read the people's answers). */
extern const std::vector<std::string> kFinestMethods;
extern const std::vector<std::string> kAllModes;
/** The forms of a view of -view_forms, as their modes are called in the reports. */
extern const std::vector<std::string> kViewForms;

/** Every flag of the evaluator. */
std::vector<tool::Flag> evalFlags();

/** The help: the syntax, what the evaluator writes, and every flag. */
void printHelp();

/** What to run, and the parameters of 'ours'. */
struct Options {
  std::string psb_dir, out_dir;
  std::vector<std::string> methods = kAllMethods, modes = kAllModes;
  std::vector<int> ids;           ///< empty: every off/<id>.off
  std::vector<double> thresholds; ///< auto mode; empty: the parameters' threshold
  SamplingOptions sampling;       ///< the points of each model; default: the face centroids
  bool quiet = false;
  int oracle_segments = 30; ///< the finest level: the cut asked for this many parts
  int views = 0;            ///< depth-camera views per model; 0: the whole objects
  /// How each view reaches the segmenters (-view_forms): modes "view" (the organized frame),
  /// "crop", "voxel", "laser" (eval_views.h).
  std::vector<std::string> view_forms = {"view"};
  bool view_origin_known = true; ///< false: sensor_origin_ left at 0 (-view_origin unknown)
  pcl_ncut_seg::PeerSettings peer_settings; ///< -peer_settings FILE, or PeerParams' defaults
  tool::Flags peer_flags;                   ///< the other -peer_* flags, over peer_settings
  pcl_ncut_seg::CameraSettings camera;      ///< the views' camera (-resolution, -range_noise)
  pcl_ncut_seg::Parameters params;          ///< -paper or the defaults, and the algorithm flags

  /** LCCP's (cpc false) or CPC's settings on whole objects or views: peer_settings, with the
   * other -peer_* flags given applied over them. */
  pcl_ncut_seg::PeerParams peerParams(bool cpc, bool view) const;

  bool has(const std::string& method) const {
    return std::find(methods.begin(), methods.end(), method) != methods.end();
  }
  /** Whether a method of the finest level (kFinestMethods) is to run. */
  bool hasFinest() const {
    for (const auto& m : kFinestMethods)
      if (has(m))
        return true;
    return false;
  }
  bool hasMode(const std::string& mode) const {
    return std::find(modes.begin(), modes.end(), mode) != modes.end();
  }
};

/** The options from the flags (whose values the table has checked). */
Options readOptions(const tool::Flags& flags);

} // namespace eval
} // namespace pcl_ncut_seg
