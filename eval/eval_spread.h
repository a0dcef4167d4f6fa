/*
 * pcl_ncut_seg_eval's spread report (-draws): how much each method's result on a model moves
 * from one draw of the samples to another, per model (spread.csv), and its means per method,
 * mode and category (a section of tables.md and a summary line per method).
 */
#pragma once

#include "eval_report.h"

#include <array>
#include <string>
#include <vector>

namespace pcl_ncut_seg {
namespace eval {

/** \brief One method's spread on one model in one mode, over its draws. */
struct Spread {
  std::string method, mode, category;
  int id = 0;
  int draws = 0;
  std::array<double, 6> range{}; ///< per metric (kMetricNames), max - min over draws
  double segments_min = 0, segments_max = 0;
  double between = 0; ///< 1 - RI between draws' face labels, mean over pairs
  bool countChanges() const { return segments_max != segments_min; }
};

/** \brief The spread of each (method, mode, model) with rows from two draws or more, in the
 * order of their first row (the human baseline, scored once per model, has none). */
std::vector<Spread> spreads(const Report& report);

/** \brief spread.csv: one line per method, mode and model. */
std::string spreadCsv(const Report& report);

/** \brief tables.md's spread section: per mode, the means over models of the per-model range
 * of each metric, the share of models whose segment count changes between draws and the
 * disagreement between draws; then the range of 1 - RI and the share per category. */
std::string spreadMarkdown(const Report& report);

/** \brief One line per mode and method: the mean ranges and the share (stdout). */
std::string spreadSummary(const Report& report);

} // namespace eval
} // namespace pcl_ncut_seg
