/*
 * pcl_ncut_seg tools: the algorithm's parameters as flags, the same in every tool. Each row of
 * pcl_ncut_seg::parameterTable() is a flag, "-" + its name, with its help, range and default;
 * -paper starts from Parameters::paper() instead of the defaults, and the flags given apply on
 * top of it.
 */
#pragma once

#include "cli/flags.h"

#include <pcl_ncut_seg/parameters.h>
#include <pcl_ncut_seg/supernode_ncut_segmentation.h>

#include <pcl/point_types.h>

#include <vector>

namespace pcl_ncut_seg {
namespace tool {

using Segmenter = pcl::SupernodeNCutSegmentation<pcl::PointXYZ>;

/** \brief -paper, the shorthands (-exact) and one flag per parameter, grouped by stage. The
 * help gives each default as in base, and its value under -paper where that differs. */
std::vector<Flag> algorithmFlags(const Parameters& base = Parameters());

/** \brief The parameters the flags ask for: Parameters::paper() with -paper, else base, then
 * every parameter flag given, in command-line order. False with one error line when flags
 * contradict each other (-segments with -threshold, -exact with -centrality, ...). */
bool parametersFromFlags(const Flags& flags, const Parameters& base, Parameters& params);

/** \brief parametersFromFlags, then the segmenter set to them; false with one error line. */
bool applyAlgorithmFlags(const Flags& flags, Segmenter& seg, const Parameters& base = Parameters());

} // namespace tool
} // namespace pcl_ncut_seg
