/*
 * pcl_ncut_seg: the Princeton Segmentation Benchmark's metrics (Chen, Golovinskiy, Funkhouser,
 * "A Benchmark for 3D Mesh Segmentation", SIGGRAPH 2009), comparing two labelings of a mesh's
 * faces. Plain C++ (no PCL).
 */
#pragma once

#include <cstddef>
#include <string>
#include <vector>

namespace pcl_ncut_seg {

/** \brief How far one segmentation is from another; every value in [0, 1], 0 = identical. */
struct SegmentationScores {
  double rand_index_error = 0; ///< 1 - Rand index over pairs of faces (faces count equally)
  double hamming = 0;          ///< Hamming distance, (Rm + Rf) / 2, area-weighted
  double hamming_rm = 0;       ///< missing rate: of the reference's segments, what is missed
  double hamming_rf = 0;       ///< false-alarm rate: of the segmentation's segments, what is extra
  double gce = 0;              ///< global consistency error, area-weighted
  double lce = 0;              ///< local consistency error, area-weighted
};

/** \brief Compare a segmentation with a reference, face by face.
 *
 * Labels are arbitrary integers. A negative label means "in no segment": all such faces of a
 * labeling together form one more segment (an unassigned face is neither right nor wrong by
 * itself; grouping them is what a user of the output sees, one "unlabelled" part).
 * Definitions, with |X| the area of a set of faces and A the total area (Chen et al. 2009,
 * Sec. 4; Huang and Dom 1995; Martin et al. 2001):
 * - Rand index: the fraction of unordered pairs of distinct faces on which both labelings
 *   agree (same segment in both, or different in both). Faces count equally.
 * - Directional Hamming distance D(S1 => S2) = sum over segments R2 of S2 of
 *   |R2 \ R1*| with R1* the segment of S1 overlapping R2 the most.
 *   Rm = D(segmentation => reference) / A, Rf = D(reference => segmentation) / A.
 * - E(S1, S2, f) = |R(S1, f) \ R(S2, f)| / |R(S1, f)|, R(S, f) the segment of S holding f.
 *   GCE = min(sum_f a_f E(S1, S2, f), sum_f a_f E(S2, S1, f)) / A,
 *   LCE = sum_f a_f min(E(S1, S2, f), E(S2, S1, f)) / A.
 * Faces of zero area weigh nothing in the area-weighted metrics; if every face has zero area,
 * every face weighs 1 instead.
 * \param[in] segmentation the labels under test, one per face
 * \param[in] reference the reference labels (a human segmentation), one per face
 * \param[in] area each face's area (>= 0); empty means every face weighs 1
 * \throws std::invalid_argument if the sizes differ or there are no faces. */
SegmentationScores compareSegmentations(const std::vector<int>& segmentation,
                                        const std::vector<int>& reference,
                                        const std::vector<double>& area);

/** \brief Element-wise sum and scaling, for averaging scores. */
SegmentationScores& operator+=(SegmentationScores& a, const SegmentationScores& b);
SegmentationScores operator/(SegmentationScores a, double d);

/** \brief The benchmark's 19 categories of the 20 ids each (1-20 Human, ..., 381-400
 * Fourleg; 261-280 Spring, excluded by the benchmark, is named too). Empty outside 1-400. */
std::string psbCategory(int id);

} // namespace pcl_ncut_seg
