/*
 * pcl_ncut_seg: the single-parameter setters of the PCL front end, each a thin wrapper of
 * setParameters(): the table in parameter_table.h validates every value.
 */
#pragma once

#include <pcl_ncut_seg/supernode_ncut_segmentation.h>

#include <pcl/console/print.h>

#include <pcl_ncut_seg/parameter_table.h>

#include <optional>

template <typename PointT>
bool pcl::SupernodeNCutSegmentation<PointT>::update(const pcl_ncut_seg::Parameters& params,
                                                    const char* method) {
  std::string why;
  if (!pcl_ncut_seg::validate(params, &why)) {
    if (console_messages_)
      PCL_ERROR("[pcl::SupernodeNCutSegmentation::%s] %s; keeping the previous value.\n", method,
                why.c_str());
    return false;
  }
  if (pcl_ncut_seg::analysisDiffers(params_, params))
    invalidate();
  params_ = params;
  return true;
}

template <typename PointT>
bool pcl::SupernodeNCutSegmentation<PointT>::setParameters(const pcl_ncut_seg::Parameters& params) {
  return update(params, "setParameters");
}

// One wrapper per setter: copy the parameters, change one field, take them if valid.
#define PCL_NCUT_SEG_SETTER(Method, Type, assignment)                                              \
  template <typename PointT> void pcl::SupernodeNCutSegmentation<PointT>::Method(Type value) {     \
    pcl_ncut_seg::Parameters p = params_;                                                          \
    assignment;                                                                                    \
    update(p, #Method);                                                                            \
  }

PCL_NCUT_SEG_SETTER(setNumberOfNeighbours, int, p.graph.k = value)
PCL_NCUT_SEG_SETTER(setNumberOfSamples, std::optional<int>, p.centrality.samples = value)
PCL_NCUT_SEG_SETTER(setCentralityMode, pcl_ncut_seg::CentralityMode, p.centrality.mode = value)
PCL_NCUT_SEG_SETTER(setStarts, int, p.centrality.starts = value)
PCL_NCUT_SEG_SETTER(setCrossingFraction, float, p.supernodes.crossing_fraction = value)
PCL_NCUT_SEG_SETTER(setAreaFraction, float, p.refinement.area_fraction = value)
PCL_NCUT_SEG_SETTER(setHeightFraction, float, p.refinement.height_fraction = value)
PCL_NCUT_SEG_SETTER(setCreaseSplit, std::optional<double>, p.refinement.crease_split = value)
PCL_NCUT_SEG_SETTER(setBridgeGap, std::optional<double>, p.graph.bridge_gap = value)
PCL_NCUT_SEG_SETTER(setDenoise, std::optional<double>, p.graph.denoise = value)
PCL_NCUT_SEG_SETTER(setIrregularSampling, std::optional<double>, p.graph.irregular_sampling = value)
PCL_NCUT_SEG_SETTER(setMaxPoints, std::optional<int>, p.graph.max_points = value)
PCL_NCUT_SEG_SETTER(setCadMode, bool, p.cad.enabled = value)
PCL_NCUT_SEG_SETTER(setBeta, double, p.similarity.beta = value)
PCL_NCUT_SEG_SETTER(setAlpha1, double, p.similarity.alpha1 = value)
PCL_NCUT_SEG_SETTER(setAlpha2, double, p.similarity.alpha2 = value)
PCL_NCUT_SEG_SETTER(setNormalizeWidth, bool, p.similarity.normalize_width = value)
PCL_NCUT_SEG_SETTER(setAdjacency, pcl_ncut_seg::Adjacency, p.similarity.adjacency = value)
PCL_NCUT_SEG_SETTER(setConcavityWeight, std::optional<double>, p.similarity.concavity = value)
PCL_NCUT_SEG_SETTER(setThickness, bool, p.similarity.thickness = value)
PCL_NCUT_SEG_SETTER(setFlatElongation, std::optional<double>, p.similarity.flat_elongation = value)
PCL_NCUT_SEG_SETTER(setStoppingRule, pcl_ncut_seg::StoppingRule, p.stopping.rule = value)
PCL_NCUT_SEG_SETTER(setThreshold, double, p.stopping.threshold = value)
PCL_NCUT_SEG_SETTER(setMaxSegments, int, p.stopping.max_segments = value)
PCL_NCUT_SEG_SETTER(setNeckBound, double, p.stopping.neck_bound = value)
PCL_NCUT_SEG_SETTER(setBoundaryBand, std::optional<double>, p.boundary.band = value)
PCL_NCUT_SEG_SETTER(setRimMerge, std::optional<double>, p.boundary.rim_merge = value)
PCL_NCUT_SEG_SETTER(setNumberOfThreads, unsigned, p.execution.num_threads = value)

#undef PCL_NCUT_SEG_SETTER

// Asking for a number of segments is choosing the count rule (as the table's "segments").
template <typename PointT>
void pcl::SupernodeNCutSegmentation<PointT>::setNumberOfSegments(int segments) {
  pcl_ncut_seg::Parameters p = params_;
  p.stopping.segments = segments;
  p.stopping.rule = pcl_ncut_seg::StoppingRule::Count;
  update(p, "setNumberOfSegments");
}
