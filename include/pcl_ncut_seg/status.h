/*
 * pcl_ncut_seg: the outcome of a segmentation as a value. The PCL class prints its errors and
 * warnings with PCL_ERROR and PCL_WARN; the same reasons, without the "[pcl::Class::method] "
 * prefix, come back in a Status (SupernodeNCutSegmentation::getStatus(), segmentPoints(),
 * PointSegmenter::analyze()), so that a front end (Python, ROS, a GUI) can report them without
 * reading the console.
 */
#pragma once

#include <string>
#include <utility>
#include <vector>

namespace pcl_ncut_seg {

/** \brief Why a segmentation gave no segments (Ok: it gave some). */
enum class StatusCode {
  Ok,              ///< segmented
  NoInput,         ///< no input cloud, or nothing prepared (PointSegmenter::analyze())
  IndexOutOfRange, ///< an index outside the input cloud
  NoFinitePoint,   ///< no finite point (within the indices)
  TooManyPoints,   ///< more points than the graph's 32-bit indices can hold
  BadParameter     ///< a parameter out of its range (segmentPoints())
};

/** \brief What a segmentation that went on anyway warns about. */
enum class WarningCode {
  RepeatedIndices, ///< repeated indices, each point taken once
  FewPoints,       ///< fewer distinct points than k + 1: fewer neighbours than k used
  DistantPoints    ///< points with a coordinate beyond 1e18, in no segment as NaN points are
};

/** \brief One warning, with its message as PCL_WARN prints it (no prefix, no newline). */
struct Warning {
  WarningCode code = WarningCode::FewPoints;
  std::string message;
};

/** \brief The outcome of a segmentation: ok, or the reason it failed, and its warnings either
 * way. The messages are the text PCL_ERROR and PCL_WARN print, without the
 * "[pcl::SupernodeNCutSegmentation::extract] " prefix and the newline, e.g. "the input has no
 * finite point.". */
struct Status {
  StatusCode code = StatusCode::Ok;
  std::string message;           ///< why it failed; empty when ok()
  std::vector<Warning> warnings; ///< in the order they were found

  /** \brief Whether the segmentation gave segments. */
  bool ok() const { return code == StatusCode::Ok; }
  explicit operator bool() const { return ok(); }

  /** \brief A failure with its reason.
   * \param[in] code     not StatusCode::Ok
   * \param[in] message  the reason */
  static Status failure(StatusCode code, std::string message) {
    Status s;
    s.code = code;
    s.message = std::move(message);
    return s;
  }
  /** \brief The first warning of this code, or nullptr.
   * \param[in] code  the warning's code */
  const Warning* find(WarningCode code) const {
    for (const Warning& w : warnings)
      if (w.code == code)
        return &w;
    return nullptr;
  }
};

/** \brief The code's name ("ok", "no_input", "index_out_of_range", "no_finite_point",
 * "too_many_points", "bad_parameter").
 * \param[in] code  the code */
inline const char* statusCodeName(StatusCode code) {
  switch (code) {
  case StatusCode::Ok:
    return "ok";
  case StatusCode::NoInput:
    return "no_input";
  case StatusCode::IndexOutOfRange:
    return "index_out_of_range";
  case StatusCode::NoFinitePoint:
    return "no_finite_point";
  case StatusCode::TooManyPoints:
    return "too_many_points";
  default:
    return "bad_parameter";
  }
}

/** \brief The warning's name ("repeated_indices", "few_points", "distant_points").
 * \param[in] code  the code */
inline const char* warningCodeName(WarningCode code) {
  switch (code) {
  case WarningCode::RepeatedIndices:
    return "repeated_indices";
  case WarningCode::FewPoints:
    return "few_points";
  default:
    return "distant_points";
  }
}

} // namespace pcl_ncut_seg
