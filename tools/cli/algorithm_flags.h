/*
 * pcl_ncut_seg tools: the algorithm's parameters as flags, the same in every tool, and their
 * values applied to a segmenter.
 */
#pragma once

#include "cli/flags.h"

#include <pcl_ncut_seg/supernode_ncut_segmentation.h>

#include <pcl/point_types.h>

#include <vector>

namespace pcl_ncut_seg {
namespace tool {

using Segmenter = pcl::SupernodeNCutSegmentation<pcl::PointXYZ>;

/** \brief The algorithm's parameters as flags, with the library's defaults. */
std::vector<Flag> algorithmFlags();

/** \brief Set the segmenter's parameters from the algorithm flags given; false with one error
 * line when they contradict each other. */
bool applyAlgorithmFlags(const Flags& flags, Segmenter& seg);

} // namespace tool
} // namespace pcl_ncut_seg
