/*
 * pcl_ncut_seg: points prepared for analyze() (core/pipeline/pipeline.h): distinct positions
 * in Morton order (every phase then reads its neighbours from nearby memory), centred. The
 * resolution of the analysis (core/graph/subsample.h) builds on it.
 */
#pragma once

#include "core/common/morton.h"
#include "core/model/model.h"

#include <cstdint>
#include <utility>
#include <vector>

namespace pcl_ncut_seg {

/** \brief Points prepared for analyze(): the distinct positions of an array of points in
 * Morton order, centred. */
struct PreparedPoints {
  PointSet set;                     ///< without knn
  std::vector<std::uint32_t> point; ///< per vertex, the index of its (first) input point
  /// (index of a point at an earlier point's position, its vertex)
  std::vector<std::pair<std::uint32_t, std::uint32_t>> copies;
  std::vector<float> raw;         ///< the input's x, y, z in vertex order (not centred)
  double centroid[3] = {0, 0, 0}; ///< set.xyz = raw - centroid
};

/** \brief Set set.xyz to raw relative to the centroid of raw (summed in double, so that a model
 * far from the origin keeps its float precision), and centroid to it. */
void centrePoints(PreparedPoints& prepared);

/** \brief Order, deduplicate and centre points (3 floats each, finite). The centroid is
 * taken in double, so that a model far from the origin keeps its float precision.
 * \param[in] xyz  consumed (freed before the centred copy is made)
 * \param[in] box  the Morton grid's cube (default: the points' own; see mortonCodes()) */
PreparedPoints preparePoints(std::vector<float> xyz, const MortonBox* box = nullptr);

} // namespace pcl_ncut_seg
