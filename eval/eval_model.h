/*
 * pcl_ncut_seg_eval: one benchmark model as the evaluator scores it, and the helpers that both
 * the whole-object scoring (pcl_ncut_seg_eval.cpp) and the view mode (eval_views.cpp) use.
 */
#pragma once

#include "psb_metrics.h"
#include <surfaces/mesh_sampling.h>

#include <pcl/PointIndices.h>

#include <chrono>
#include <cstddef>
#include <string>
#include <vector>

namespace pcl_ncut_seg {
namespace eval {

/** \brief One model: its mesh, its points at the face centroids, the face areas and the
 * human labels. */
struct Model {
  int id = 0;
  std::string name, category;
  TriangleMesh mesh;
  std::vector<float> xyz;
  std::vector<double> area;
  std::size_t n = 0;
  std::vector<std::vector<int>> humans;
  int given = 0; ///< the benchmark's count, 0 for none
};

/** \brief Mean of the scores against every human segmentation. */
SegmentationScores againstHumans(const std::vector<int>& labels,
                                 const std::vector<std::vector<int>>& humans,
                                 const std::vector<double>& area);

/** \brief Each person against the others, averaged (needs two people or more). */
SegmentationScores humansAgainstEachOther(const std::vector<std::vector<int>>& humans,
                                          const std::vector<double>& area, double* segments);

/** \brief The number of distinct labels, all negative ones counting as one. */
std::size_t countSegments(const std::vector<int>& labels);

double secondsSince(std::chrono::steady_clock::time_point since);

/** \brief A label per point from the segments' indices (-1 for points in none). */
std::vector<int> segmentsToLabels(const std::vector<pcl::PointIndices>& segments, std::size_t n);

} // namespace eval
} // namespace pcl_ncut_seg
