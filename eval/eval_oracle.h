/*
 * pcl_ncut_seg_eval's oracles (issue 63): how much of the gap to people lies in the analysis
 * and how much in the choice of boundaries. A fine segmentation's segments are each merged into
 * the person's segment they overlap most, separately for each person, and scored against that
 * person. The oracle READS THE PEOPLE'S SEGMENTATIONS: it bounds what a choice among the fine
 * segmentation's boundaries could reach, it is not a method, and no default may be chosen by
 * it. Its control is the same merge of k-means with as many segments. Plain C++ (no PCL).
 */
#pragma once

#include "psb_metrics.h"

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

namespace pcl_ncut_seg {
namespace eval {

/** \brief The methods that read the people's answers (-methods): the finest level merged onto
 * each person ("oracle"), and k-means with the finest level's count merged likewise
 * ("kmeans_oracle"). Neither is among the default methods. */
extern const std::vector<const char*> kOracleMethods;
/** \brief Whether a method reads the people's answers. */
bool isOracleMethod(const std::string& method);
/** \brief The line the evaluator's output carries when an oracle was run. */
extern const char* const kOracleNote;

/** \brief Each segment of `segmentation` relabelled as the segment of `person` it overlaps
 * most by area (ties: the larger overlap in faces, then the smaller label of `person`). As in
 * compareSegmentations(), every negative label of either is one segment ("in no segment"), the
 * faces of zero area weigh nothing unless every face has zero area, and an empty `area` weighs
 * every face 1. The result refines nothing finer than `person`: it is a coarsening of
 * `segmentation` labelled with `person`'s labels.
 * \throws std::invalid_argument if the sizes differ. */
std::vector<int> mergeOnto(const std::vector<int>& segmentation, const std::vector<int>& person,
                           const std::vector<double>& area);

/** \brief The oracle's scores: the mean over the people of `segmentation` merged onto each
 * person (mergeOnto) and compared with that person. */
SegmentationScores oracleAgainstHumans(const std::vector<int>& segmentation,
                                       const std::vector<std::vector<int>>& humans,
                                       const std::vector<double>& area);

/** \brief k-means of the points (x, y, z per point) into min(k, n) segments, labels 0..: k-means++
 * seeding from a generator seeded by `seed`, then Lloyd's iterations until no point moves (at
 * most `max_iterations`). Deterministic on every platform: the draws use the generator's raw
 * bits, ties go to the lower cluster, and an emptied cluster restarts at the point farthest from
 * its centre. */
std::vector<int> kmeansLabels(const std::vector<float>& xyz, std::size_t k, std::uint64_t seed,
                              int max_iterations = 100);

} // namespace eval
} // namespace pcl_ncut_seg
