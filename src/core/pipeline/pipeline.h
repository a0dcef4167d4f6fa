/*
 * pcl_ncut_seg: the whole segmentation over plain arrays, in two stages (the paper's order),
 * the stages run by the orchestrator below on the data model (core/model/model.h).
 * Every stage, in the order it runs; [paper] is the paper's (section, equation), [ext] an
 * extension with the parameter that switches it (results/report.md says what each buys).
 *
 * Before the analysis (PointSegmenter, <pcl_ncut_seg/segment_points.h>):
 *   [ext]   max_points          an even subset of a dense cloud (core/graph/subsample.h)
 *   [paper] kNN                 Sec. 4.1, the k nearest neighbours (core/graph/knn.h)
 *
 * analyze(), the expensive stage, once per input (analysis_stages.h):
 *   [paper] kNN graph           Sec. 4.1 (graphStage())
 *   [ext]   denoise             noise detected and projected out (core/graph/denoise.h)
 *   [ext]   irregular_sampling  random sampling detected; f averaged (core/graph/denoise.h)
 *   [ext]   bridge_gap          components joined across sampling gaps (core/graph/bridging.h)
 *   [ext]   single_view         a view's rim from its sensor origin, or from a sensor
 *                               position read off the points (core/views/single_view.h,
 *                               core/views/view_origin.h)
 *   [paper] CAD graph           Sec. 7, CAD mode: the graph transformed by the distance from
 *                               the ridges (cadGraph(), core/cad/cad.h)
 *   [paper] centrality f        Sec. 4.1, eq. (1) (centralityStage()); [ext] centrality=fast
 *                               on a coarse graph (core/centrality/coarse_centrality.h);
 *                               [ext] starts: several (core/centrality/starts.h)
 *   [paper] supernodes          Sec. 4.2, gradient flow with saddles (supernodeStage())
 *   [paper] local refinement    Sec. 4.3 (refinementStage())
 *   [paper] CAD faces           Sec. 7, CAD mode: supernodes split at the ridges, the faces'
 *                               angles measured (cadFaces(), core/cad/cad.h); then no more
 *   [ext]   crease_split        supernodes split at concave creases (creaseStage(),
 *                               core/supernodes/crease_split.h)
 *   [ext]   contact concavity   for concavity and boundary_band (contactStage(),
 *                               core/cut/concavity.h)
 *   [ext]   thickness           medial balls from probes, each refined supernode's median
 *                               (contactStage(), core/cut/thickness.h); closed surfaces
 *
 * cut(), the cheap stage, repeatable on kept analyses (cut_stages.h), per start:
 *   [paper] similarity          Sec. 5.1, eqs. (7)-(9); [ext] normalize_width, adjacency,
 *                               concavity, thickness, flat_elongation
 *                               (core/cut/supernode_graph.h)
 *   [paper] hierarchy           Sec. 5.2, threshold rule; [ext] stopping=short_cut
 *                               (core/cut/short_cut.h), count: bottom-up merges
 *                               (core/cut/part_merge.h)
 *   [paper] point segments      footnote 6 (labelPoints())
 *   [ext]   boundary_band       point-level boundaries by minimum cuts
 *                               (core/cut/boundary_refinement.h)
 *   [ext]   rim_merge           open views: pieces the rim cut off merged
 *                               (core/views/rim_merge.h), then pieces below the paper's small
 *                               part (core/views/small_segments.h)
 * then, with several starts:
 *   [ext]   starts              the medoid of the starts' segmentations
 *                               (core/centrality/starts.h)
 */
#pragma once

#include "core/model/model.h"
#include <pcl_ncut_seg/analysis_report.h>
#include <pcl_ncut_seg/parameters.h>

namespace pcl_ncut_seg {

/** \brief What the cut stages with these parameters need the analysis to have measured. */
CutNeeds cutNeeds(const Parameters& params);

/** \brief Does the analysis hold what a cut with these parameters needs? */
bool serves(const Analysis& analysis, const Parameters& params);

/** \brief Run every analysis stage in order, once per start of eq. (1)'s sampling with samples
 * of its own. The graph's time (and CAD normals') counts as times.knn, as in Table 1. params
 * must be valid (validate()).
 * \param[in] points  consumed: its arrays are freed as soon as no stage needs them */
Analyses analyze(PointSet points, const Parameters& params, PhaseTimes& times,
                 const PhaseProgressFn& progress = nullptr);

/** \brief Run every cut stage in order on analyses that serve() the parameters. Segments are
 * numbered in order of their first vertex in Analysis::order. With several starts, each is cut
 * and the medoid of their segmentations is returned (core/centrality/starts.h). */
CutResult cut(const Analyses& analyses, const Parameters& params, PhaseTimes& times);

} // namespace pcl_ncut_seg
