/*
 * pcl_ncut_seg: what an analysis reports besides its segments: what it found the input to be
 * (noisy, drawn at random, one view) and how long each phase of the paper's Table 1 took.
 * Plain structs, shared by the core, the PCL front end and the tools.
 */
#pragma once

#include <array>
#include <cstddef>
#include <functional>

namespace pcl_ncut_seg {

/** \brief Wall time of each phase in seconds, in the paper's Table 1 columns. */
struct PhaseTimes {
  double knn = 0, centrality = 0, supernodes = 0, refinement = 0, hierarchy = 0, points = 0;
  double total() const { return knn + centrality + supernodes + refinement + hierarchy + points; }
};

/** \brief Progress: a phase of Table 1 ("kNN", "Cen", "Snod", "LRef", "HSeg") and 0 at its
 * start, 1 at its end, the fraction done in between where known; from the calling thread. */
using PhaseProgressFn = std::function<void(const char* phase, double fraction)>;

/** \brief What the graph stage found out about noise (the core's graph/denoise.h). */
struct NoiseTest {
  double residual_growth = 0.0;       ///< residualGrowth(); 0 when it was not measured
  bool projected = false;             ///< the points were projected onto their local planes
  double sampling_irregularity = 0.0; ///< samplingIrregularity(); 0 when it was not measured
  bool irregular = false;             ///< at least graph.irregular_sampling: f is averaged once
};

/** \brief What the analysis found the points to be (a sensor origin, a view's rim; the core's
 * views/view_origin.h). */
struct ViewTest {
  bool view = false;             ///< one view: the points have a rim and the open-view stages run
  bool origin_estimated = false; ///< the sensor position was read off the points
  std::array<float, 3> origin{}; ///< the sensor position the view was seen from (when view)
  std::size_t rim_points = 0;    ///< points on the view's rim
};

} // namespace pcl_ncut_seg
