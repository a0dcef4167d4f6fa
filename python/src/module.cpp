/*
 * pcl_ncut_seg Python module (pcl_ncut_seg._pcl_ncut_seg, which the package pcl_ncut_seg wraps):
 * segment(points, normals=None, **parameters) and the Segmenter class over
 * pcl::SupernodeNCutSegmentation<pcl::PointNormal>. Parameters go by the names of the table in
 * pcl_ncut_seg/parameter_table.h (the tools' flags without the '-').
 */
#include "files.h"
#include "segmenter.h"
#include "values.h"

#include <pybind11/stl.h>

#include <deque>
#include <stdexcept>

namespace py = pybind11;
using pcl_ncut_seg_python::Segmenter;

namespace {

const char* const kModuleDoc = R"doc(Segmenting point-sampled surfaces (Yamazaki et al.) with PCL.

    labels = pcl_ncut_seg.segment(points, segments=6)

points is an (N, 3) float32 or float64 array; rows with NaN are in no segment. The result is
N int32 labels: 1 to t for the t segments (numbered by their first point), 0 for points in no
segment: the labels of pcl::SupernodeNCutSegmentation and of the pcl_ncut_seg tool.

Parameters go by the tool's flag names without the '-' (k=12, threshold=0.1, segments=6,
crease_split=0.5, ...); parameter_table() lists them. None turns an
optional extension off (or to auto), True/False are on/off, paper=True starts from the paper
to the letter instead of the project's defaults. A bad array or parameter raises ValueError
with the library's reason. Segmenter keeps the expensive stage between calls.)doc";

const char* const kSegmentDoc =
    R"doc(segment(points, normals=None, sensor_origin=None, **parameters) -> numpy.ndarray

Segment points, an (N, 3) float32 or float64 array (NaN rows allowed) or a depth image's
(H, W, 3) points (NaN where nothing came back; an organized cloud, whose rim is known), with
the project's defaults changed by the keyword parameters (paper=True: the paper's settings).
normals, an array of the points' shape, are the normals CAD mode (cad=True) reads in place of
estimating them (NaN rows: estimated).
sensor_origin, the (x, y, z) of the sensor that saw the points, in their frame (None: the
frame's origin, as PCL's sensor_origin_; a view's points in the camera's frame need none),
tells a single view from where it was seen; when it cannot be the sensor, the position is
read off the points.
Returns N (or H x W) int32 labels, 1-based, 0 for points in no segment. ValueError on a bad array, no finite point or a
bad parameter; library warnings (fewer points than k + 1, ...) are RuntimeWarnings.)doc";

const char* const kSegmenterDoc = R"doc(Segmenter(**parameters)

A segmenter that keeps its work between calls. Every parameter is an attribute of the same
name (seg.k, seg.threshold, seg.segments, ...; parameter_table() describes them); set() changes
several at once. segment(points) segments; segment() with no points segments the last points
again, and when only cut parameters (similarity, stopping, boundary stages) changed it reuses
the expensive stage (kNN graph, centrality, supernodes): analysis_count does not grow and
phase_times shows 0 s for those phases.

The intermediate results of the last segment() are numpy arrays: get_centrality(),
get_supernode_labels(), get_local_maxima(), get_saddles(), get_hierarchy(),
get_supernode_segments(), get_supernode_graph().)doc";

std::string propertyDoc(const pcl_ncut_seg::ParameterInfo& row) {
  const pcl_ncut_seg::Parameters defaults, paper = pcl_ncut_seg::Parameters::paper();
  return row.help + ".\n\n" + row.range + "; default " + row.get(defaults) + ", paper " +
         row.get(paper) + "; stage " + pcl_ncut_seg::stageName(row.stage) + " (" +
         (pcl_ncut_seg::isAnalysisStage(row.stage) ? "analysis" : "cut") + ")";
}

/** \brief One property per row of the table, by its name. */
void addParameterProperties(py::class_<Segmenter>& cls) {
  static std::deque<std::string> docs; // the docstrings must outlive the module
  for (const pcl_ncut_seg::ParameterInfo& row : pcl_ncut_seg::parameterTable()) {
    if (py::hasattr(cls, row.name.c_str()))
      throw std::logic_error("pcl_ncut_seg: parameter " + row.name +
                             " has the name of a Segmenter attribute");
    const std::string name = row.name;
    docs.push_back(propertyDoc(row));
    cls.def_property(
        name.c_str(), [name](const Segmenter& s) { return s.get(name); },
        [name](Segmenter& s, const py::object& value) {
          py::dict keywords;
          keywords[py::str(name)] = value;
          s.set(keywords);
        },
        docs.back().c_str());
  }
}

py::list shorthandList() {
  py::list out;
  for (const pcl_ncut_seg::Shorthand& s : pcl_ncut_seg::parameterShorthands()) {
    py::dict d;
    d["name"] = s.name;
    d["parameter"] = s.parameter;
    d["value"] = s.value;
    d["help"] = s.help;
    out.append(d);
  }
  return out;
}

} // namespace

PYBIND11_MODULE(_pcl_ncut_seg, m) {
  m.doc() = kModuleDoc;
  m.attr("__version__") = PCL_NCUT_SEG_VERSION;
  pcl_ncut_seg_python::defineFiles(m);

  m.def(
      "segment",
      [](const py::object& points, const py::object& normals, const py::object& sensor_origin,
         const py::kwargs& parameters) {
        Segmenter seg{py::dict()};
        return seg.segment(points, normals, sensor_origin, parameters);
      },
      py::arg("points"), py::arg("normals") = py::none(), py::arg("sensor_origin") = py::none(),
      kSegmentDoc);
  m.def("parameter_table", &pcl_ncut_seg_python::parameterTableList,
        "parameter_table() -> list of dict\n\nEvery parameter: name, field, stage, "
        "analysis (whether changing it recomputes the expensive stage), kind, range, help, off "
        "(the word None stands for), choices, default, paper_value, in_paper.");
  m.def("parameter_shorthands", &shorthandList,
        "parameter_shorthands() -> list of dict\n\nThe keywords that stand for one parameter's "
        "value (exact=True is centrality='exact'), as the tools' shorthand flags: name, "
        "parameter, value, help. They take True only.");
  m.def(
      "default_parameters",
      [](bool paper) {
        return pcl_ncut_seg_python::parameterDict(paper ? pcl_ncut_seg::Parameters::paper()
                                                        : pcl_ncut_seg::Parameters::defaults());
      },
      py::arg("paper") = false,
      "default_parameters(paper=False) -> dict\n\nThe project's defaults (paper=True: the "
      "paper's settings) by name.");

  py::class_<Segmenter> cls(m, "Segmenter", kSegmenterDoc);
  cls.def(py::init([](const py::kwargs& parameters) { return new Segmenter(parameters); }))
      .def(
          "set", [](Segmenter& s, const py::kwargs& parameters) { s.set(parameters); },
          "set(**parameters)\n\nChange parameters by name, all or none (ValueError). "
          "paper=True/False first resets every parameter but threads to the paper's settings "
          "or the defaults.")
      .def("get", &Segmenter::get, py::arg("name"), "The value of a parameter by name.")
      .def_property_readonly("parameters", &Segmenter::parameters,
                             "Every parameter's value, by name (a new dict).")
      .def(
          "segment",
          [](Segmenter& s, const py::object& points, const py::object& normals,
             const py::object& sensor_origin, const py::kwargs& parameters) {
            return s.segment(points, normals, sensor_origin, parameters);
          },
          py::arg("points") = py::none(), py::arg("normals") = py::none(),
          py::arg("sensor_origin") = py::none(),
          "segment(points=None, normals=None, sensor_origin=None, **parameters) -> "
          "numpy.ndarray\n\nSet the parameters (as set()), then segment points (None: the "
          "points of the last call, reusing the expensive stage when only cut parameters "
          "changed), with their normals for CAD mode (None: estimated), seen from sensor_origin "
          "(None: the points' origin). Returns N int32 labels (H x W for an (H, W, 3) image), "
          "1-based, 0 for points in no segment.")
      .def("get_labels", &Segmenter::labels, "The labels of the last segment() (int32, N).")
      .def("get_centrality", &Segmenter::centrality,
           "Centrality f(p) of eq. (1) per point (float32, N), on a noisy whole surface after "
           "the neighbourhood mean (the denoise parameter; not on an open view); NaN for points "
           "not segmented.")
      .def("get_supernode_labels", &Segmenter::supernodeLabels, py::arg("refined") = true,
           "Supernode of each point (int32, N), after local refinement (refined=False: "
           "before); -1 for points not segmented.")
      .def("get_local_maxima", &Segmenter::localMaxima,
           "Indices of the points where supernodes were born (int64).")
      .def("get_saddles", &Segmenter::saddles, "Indices of the saddle points (int64).")
      .def("get_hierarchy", &Segmenter::hierarchy,
           "The hierarchy of bisections (Sec. 5.2) as arrays over its M nodes (node 0: all of "
           "G_s): parent, left, right (int32, -1 for none; a leaf has left == -1), ncut "
           "(float64, the NCut of the node's best bisection, NaN if it has none), segment "
           "(int32, a leaf's segment label, 0 for inner nodes) and vertices (bool, M x 2l: the "
           "vertices of G_s in the node; column i < l is refined supernode i's representative "
           "vertex, column l + i its member vertex).")
      .def("get_supernode_segments", &Segmenter::supernodeSegments,
           "The segment label of each refined supernode (int32, l), as the hierarchy "
           "assigned it (before the point-level boundary refinement).")
      .def("get_supernode_graph", &Segmenter::supernodeGraph,
           "The supernode graph G_s (Sec. 5.1): num_vertices (2l), edges (int64, E x 2), "
           "weights (float64, E).")
      .def_property_readonly("num_points", &Segmenter::numPoints,
                             "Points of the current input, NaN rows included.")
      .def_property_readonly("num_segments", &Segmenter::numSegments,
                             "t: segments of the last segment().")
      .def_property_readonly(
          "num_supernodes", [](const Segmenter& s) { return s.numSupernodes(false); },
          "m: supernodes before local refinement.")
      .def_property_readonly(
          "num_refined_supernodes", [](const Segmenter& s) { return s.numSupernodes(true); },
          "l: supernodes after local refinement.")
      .def_property_readonly("noise_test", &Segmenter::noiseTest,
                             "The last analysis' noise test (the denoise parameter): "
                             "residual_growth of the local plane fits (about 1 for noise, 4 "
                             "for curvature; 0 when not measured) and whether the points were "
                             "projected onto their local planes; sampling_irregularity (the "
                             "irregular_sampling parameter: about 0.45 for points drawn at "
                             "random, 0.05-0.2 for even ones; 0 when not measured) and whether "
                             "the centrality was averaged for it (irregular).")
      .def_property_readonly("view_test", &Segmenter::viewTest,
                             "The last analysis' view test (the single_view parameter): "
                             "whether the points were one view (view), the sensor position "
                             "they were seen from, relative to their centroid (origin), "
                             "whether it was read off the points (origin_estimated), and "
                             "the points on the view's rim (rim_points).")
      .def_property_readonly("phase_times", &Segmenter::phaseTimes,
                             "Seconds per phase of the last segment() (knn, centrality, "
                             "supernodes, refinement, hierarchy, points, total); the analysis "
                             "phases are 0 when the call reused the kept analysis.")
      .def_property_readonly("analysis_count", &Segmenter::analysisCount,
                             "How many times this segmenter computed the expensive stage.")
      .def("__repr__", &Segmenter::repr);
  addParameterProperties(cls);
}
