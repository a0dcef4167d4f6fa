/*
 * pcl_ncut_seg Python module: Segmenter, a pcl::SupernodeNCutSegmentation<pcl::PointNormal>
 * over a numpy array of points (and one of normals, which CAD mode reads). The PCL class does the
 * work (the same labels, the same checks); this class converts the array, the parameters and the
 * results, and turns the library's status into a ValueError and RuntimeWarnings.
 */
#pragma once

#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>

#include "core/model/model.h" // the cut result
#include <pcl_ncut_seg/supernode_ncut_segmentation.h>

#include <atomic>
#include <cstdint>
#include <string>
#include <vector>

namespace pcl_ncut_seg_python {

namespace py = pybind11;

/** \brief The points of an (N, 3) float32 or float64 array (anything numpy.asarray turns into
 * one) as a cloud of N points in the same order, NaN rows kept, with the normals of an array of
 * the same shape (None: NaN normals, which CAD mode estimates), seen from sensor_origin (3
 * numbers, the sensor's position in the points' frame; None: the frame's origin, as PCL's
 * sensor_origin_); ValueError otherwise. */
pcl::PointCloud<pcl::PointNormal>::Ptr cloudFromArray(const py::handle& points,
                                                      const py::handle& normals,
                                                      const py::handle& sensor_origin = py::none());

class Segmenter {
public:
  /** \brief Parameters by keyword (applyKeywords()), the defaults otherwise. */
  explicit Segmenter(const py::dict& keywords);

  /** \brief Change parameters by keyword, all or nothing. */
  void set(const py::dict& keywords);
  /** \brief One parameter's value (by a row's name). */
  py::object get(const std::string& name) const;
  /** \brief Every parameter's value, by name. */
  py::dict parameters() const;

  /** \brief Segment points (None: the points of the last call again) after setting the
   * keywords, with the normals of the points (None: none) and the sensor's position (None: the
   * points' origin); the labels, 1-based, 0 for points in no segment. Reuses the expensive
   * stage when only cut parameters changed since the last call on the same points. */
  py::array_t<std::int32_t> segment(const py::object& points, const py::object& normals,
                                    const py::object& sensor_origin, const py::dict& keywords);

  /// Results of the last segment(); RuntimeError when there is none (no call yet, a failed
  /// one, or a change of an analysis parameter since).
  py::array_t<std::int32_t> labels() const;
  py::array_t<float> centrality() const;
  py::array_t<std::int32_t> supernodeLabels(bool refined) const;
  py::array_t<std::int64_t> localMaxima() const;
  py::array_t<std::int64_t> saddles() const;
  py::dict hierarchy() const;
  py::array_t<std::int32_t> supernodeSegments() const;
  py::dict supernodeGraph() const;
  std::size_t numSegments() const;
  std::size_t numSupernodes(bool refined) const;
  /** \brief The last analysis' noise test: residual_growth and projected (core/graph/denoise.h). */
  py::dict noiseTest() const;
  py::dict viewTest() const;

  /** \brief Seconds per phase of the last segment() (Table 1's columns); the analysis phases
   * are 0 when that call reused the kept analysis. */
  py::dict phaseTimes() const;
  /** \brief How many times this segmenter computed the expensive stage. */
  std::size_t analysisCount() const { return analyses_; }
  /** \brief Points of the current input (0 before the first segment()). */
  std::size_t numPoints() const { return cloud_ ? cloud_->size() : 0; }

  std::string repr() const;

private:
  /** \brief The PCL class, with its cut result (protected there) readable. */
  class Seg : public pcl::SupernodeNCutSegmentation<pcl::PointNormal> {
  public:
    const pcl_ncut_seg::CutResult& result() const { return segmenter_.result(); }
  };

  void checkIdle() const;
  void requireResult() const;

  Seg seg_;
  pcl::PointCloud<pcl::PointNormal>::Ptr cloud_;
  std::vector<std::int32_t> labels_;
  bool have_result_ = false;
  pcl_ncut_seg::PhaseTimes times_;
  std::size_t analyses_ = 0;
  std::atomic<bool> busy_{false}; ///< segment() runs without the GIL
};

} // namespace pcl_ncut_seg_python
