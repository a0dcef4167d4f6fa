/*
 * pcl_ncut_seg: the stages of the cheap cut, each a named step, run in this order by cut()
 * (core/pipeline/pipeline.h) on a kept analysis.
 */
#pragma once

#include "core/model/model.h"
#include <pcl_ncut_seg/parameters.h>

namespace pcl_ncut_seg {

/** \brief Similarity stage (Sec. 5.1): G_s with the weights of eqs. (7) and (9), or in CAD
 * mode those of the faces' orientations (Sec. 7). */
WeightedGraph similarityStage(const Analysis& analysis, const SimilarityParams& params);

/** \brief Stopping stage (Sec. 5.2): the hierarchy of bisections of G_s under the stopping
 * rule; the short-cut rule measures each split's boundary on the kNN graph. */
Hierarchy hierarchyStage(const Analysis& analysis, const WeightedGraph& graph,
                         const StoppingParams& params);

/** \brief Point segments: each supernode follows its member vertex m_i into a leaf of the
 * hierarchy (footnote 6), each point its supernode. Writes point_segment, supernode_segment
 * and num_segments, numbered in order of their smallest vertex. */
void labelPoints(const Analysis& analysis, CutResult& result);

/** \brief Boundary stage (extension): recut the boundary between each pair of touching
 * segments by a minimum cut on the kNN graph (core/cut/boundary_refinement.h). No effect in CAD
 * mode or with the band off. */
void boundaryStage(const Analysis& analysis, const BoundaryParams& params, CutResult& result);

/** \brief The width of each side of a boundary that the rim stage measures: half the width
 * of a part of the paper's small size (1% of the object's feature area, Sec. 4.3; the object
 * taken as twice the view). A length of the surface: the same at any density.
 * \param[in] radii  per point r(p) (pointRadii()), of the view's points
 * \return the width, in the points' units */
double rimBandWidth(const std::vector<float>& radii);

/** \brief Rim stage (extension, open views): merge segments that only the view's rim cut
 * apart (core/views/rim_merge.h), then join the pieces smaller than the paper's small part that no
 * limb's neck holds (core/views/small_segments.h). No effect in CAD mode, with rim_merge off or
 * without a rim. */
void rimStage(const Analysis& analysis, const BoundaryParams& params, CutResult& result);

/** \brief Renumber the segments in order of their first vertex in order (empty: by vertex). */
void numberSegments(const std::vector<std::uint32_t>& order, CutResult& result);

} // namespace pcl_ncut_seg
