/*
 * pcl_ncut_seg_eval's view mode (-views V): each model seen by a depth camera from V seeded
 * directions (depth_view.h), each view segmented by every method and scored on the faces that
 * at least one of its pixels sees, against the people's segmentations restricted to those
 * faces. 'ours whole' is this project on the whole object (points at the face centroids, as
 * without -views) scored on the same faces: the gap between a view and the whole object.
 */
#pragma once

#include "eval_model.h"
#include "eval_options.h"
#include "eval_report.h"

namespace pcl_ncut_seg {
namespace eval {

/** \brief One row per method for the model (mode "view"): the means over its views of the
 * scores, the segments and the seconds per view, and the faces seen per view.
 * \return the mean number of valid points (pixels that hit the surface) per view. */
double scoreViews(const Model& m, const Options& opt, Report& report);

} // namespace eval
} // namespace pcl_ncut_seg
