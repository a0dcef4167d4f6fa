/*
 * pcl_ncut_seg_eval's report: the scores of each method on each model, their means per
 * category, and the files models.csv, categories.csv and tables.md.
 */
#pragma once

#include "psb_metrics.h"

#include <cstddef>
#include <map>
#include <string>
#include <tuple>
#include <vector>

namespace pcl_ncut_seg {
namespace eval {

/** \brief One method's result on one model in one mode. */
struct Row {
  std::string method, mode, category;
  int id = 0;
  int draw = 0; ///< which draw of the samples (0 for the face centroids)
  std::size_t faces = 0;
  double segments = 0, seconds = 0;
  SegmentationScores scores;
  std::size_t humans = 0;
};

/** \brief The rows and what the tables are ordered by. */
struct Report {
  std::vector<Row> rows;
  std::vector<std::string> modes; ///< as given on the command line
  std::vector<int> ids;           ///< the models, in order
  int draws = 1;                  ///< draws per model (-draws)
  /// (method, mode, id) -> 1 - RI between the face labels of two draws, mean over the pairs
  std::map<std::tuple<std::string, std::string, int>, double> between_draws;
};

/** \brief models.csv: one line per row. */
std::string modelsCsv(const Report& report);
/** \brief categories.csv: the means per method, mode and category, and Overall. */
std::string categoriesCsv(const Report& report);
/** \brief tables.md: the overall table and one table per metric, per mode. */
std::string tablesMarkdown(const Report& report);
/** \brief One line per mode and method: the overall means (stdout). */
std::string summary(const Report& report);
/** \brief A model's results: each method's 1 - RI / Hamming, segments and time (stdout). */
std::string modelResults(const Report& report, int id);

/** \brief The six metrics by number: 1 - RI, Hamming, Rm, Rf, GCE, LCE. */
extern const char* const kMetricNames[6];
double metricValue(const SegmentationScores& s, int k);

/** \brief A mode of the view mode (-views): "view", "crop", "voxel" or "laser". */
bool isViewMode(const std::string& mode);

/** \brief Fixed-point text with this many digits. */
std::string fixed(double v, int digits = 3);

} // namespace eval
} // namespace pcl_ncut_seg
