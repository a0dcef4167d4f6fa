#include "segmenter.h"

#include "values.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>
#include <optional>
#include <sstream>

namespace pcl_ncut_seg_python {

namespace {

std::string shapeText(const py::array& a) {
  std::string s = "(";
  for (py::ssize_t d = 0; d < a.ndim(); ++d)
    s += (d ? ", " : "") + std::to_string(a.shape(d));
  return s + (a.ndim() == 1 ? ",)" : ")");
}

/** \brief Copies an (N, 3) or (H, W, 3) array of T into the cloud's x, y, z (normals false) or
 * normal_x, normal_y, normal_z (normals true), in order. */
template <typename T>
void fillCloud(const py::array& a, bool normals, pcl::PointCloud<pcl::PointNormal>& cloud) {
  // C-contiguous, native byte order; a copy only when the array is not already so.
  const auto data = py::array_t<T, py::array::c_style | py::array::forcecast>::ensure(a);
  const T* p = data.data();
  for (std::size_t i = 0; i < cloud.size(); ++i, p += 3) {
    float* q = normals ? cloud[i].normal : cloud[i].data;
    for (int d = 0; d < 3; ++d)
      q[d] = static_cast<float>(p[d]);
  }
}

/** \brief obj as an (N, 3) or (H, W, 3) array of float32 or float64; ValueError naming what
 * otherwise. */
py::array floatArray(const py::handle& obj, const char* what) {
  const py::array a = py::module_::import("numpy").attr("asarray")(obj);
  const py::dtype dtype = a.dtype();
  const bool is_float = dtype.kind() == 'f' && (dtype.itemsize() == 4 || dtype.itemsize() == 8);
  // (H, W, 3): a depth image's points, an organized cloud (its rim is known,
  // core/views/rim_merge.h).
  const bool image = a.ndim() == 3 && a.shape(0) > 0 && a.shape(1) > 0 && a.shape(2) == 3;
  if (!(image || (a.ndim() == 2 && a.shape(1) == 3)) || !is_float)
    throw py::value_error(std::string(what) +
                          " must be an (N, 3) or (H, W, 3) array of float32 or float64, got " +
                          dtype.attr("name").cast<std::string>() + " of shape " + shapeText(a));
  return a;
}

template <typename T> py::array_t<T> toArray(const std::vector<T>& v) {
  py::array_t<T> out(static_cast<py::ssize_t>(v.size()));
  if (!v.empty())
    std::memcpy(out.mutable_data(), v.data(), v.size() * sizeof(T));
  return out;
}

py::array_t<std::int64_t> indexArray(const std::vector<int>& v) {
  return toArray(std::vector<std::int64_t>(v.begin(), v.end()));
}

/** \brief Clears a flag when it leaves scope (also by an exception). */
struct BusyGuard {
  std::atomic<bool>& flag;
  explicit BusyGuard(std::atomic<bool>& f) : flag(f) { flag = true; }
  ~BusyGuard() { flag = false; }
};

} // namespace

pcl::PointCloud<pcl::PointNormal>::Ptr cloudFromArray(const py::handle& points,
                                                      const py::handle& normals,
                                                      const py::handle& sensor_origin) {
  Eigen::Vector4f origin = Eigen::Vector4f::Zero(); // PCL's default: the frame's origin
  if (!sensor_origin.is_none()) {
    const py::array o = py::module_::import("numpy").attr("asarray")(sensor_origin);
    const bool numeric =
        o.dtype().kind() == 'f' || o.dtype().kind() == 'i' || o.dtype().kind() == 'u';
    if (!numeric || o.ndim() != 1 || o.shape(0) != 3)
      throw py::value_error("sensor_origin must be 3 numbers (x, y, z), got " +
                            o.dtype().attr("name").cast<std::string>() + " of shape " +
                            shapeText(o));
    const auto xyz = o.attr("astype")("float64").cast<py::array_t<double>>();
    for (int i = 0; i < 3; ++i) {
      if (!std::isfinite(xyz.at(i)))
        throw py::value_error("sensor_origin must be finite, got " +
                              py::repr(sensor_origin).cast<std::string>());
      origin[i] = static_cast<float>(xyz.at(i));
    }
  }
  const py::array a = floatArray(points, "points");
  std::optional<py::array> n; // none: NaN normals
  if (!normals.is_none()) {
    n = floatArray(normals, "normals");
    if (n->ndim() != a.ndim() || n->shape(0) != a.shape(0) || n->shape(1) != a.shape(1))
      throw py::value_error("normals must have the shape of the points, " + shapeText(a) +
                            ", got " + shapeText(*n));
  }
  pcl::PointCloud<pcl::PointNormal>::Ptr cloud(new pcl::PointCloud<pcl::PointNormal>);
  const bool image = a.ndim() == 3;
  const auto height = static_cast<std::uint32_t>(image ? a.shape(0) : 1);
  const auto width = static_cast<std::uint32_t>(image ? a.shape(1) : a.shape(0));
  pcl::PointNormal nan_normal; // NaN normals: none given (CAD mode estimates them)
  nan_normal.normal_x = nan_normal.normal_y = nan_normal.normal_z =
      std::numeric_limits<float>::quiet_NaN();
  cloud->resize(std::size_t(width) * height, nan_normal);
  cloud->width = width;
  cloud->height = height;
  if (a.dtype().itemsize() == 4)
    fillCloud<float>(a, false, *cloud);
  else
    fillCloud<double>(a, false, *cloud);
  if (n && n->dtype().itemsize() == 4)
    fillCloud<float>(*n, true, *cloud);
  else if (n)
    fillCloud<double>(*n, true, *cloud);
  cloud->is_dense = std::all_of(cloud->begin(), cloud->end(), [](const pcl::PointNormal& p) {
    return std::isfinite(p.x) && std::isfinite(p.y) && std::isfinite(p.z);
  });
  cloud->sensor_origin_ = origin;
  return cloud;
}

Segmenter::Segmenter(const py::dict& keywords) {
  seg_.setConsoleMessages(false); // the status is raised and warned in Python instead
  set(keywords);
  // The front end announces the kNN phase once per analysis: count them.
  seg_.setProgressCallback([this](const char* phase, double fraction) {
    if (fraction == 0.0 && std::strcmp(phase, "kNN") == 0)
      ++analyses_;
  });
}

void Segmenter::checkIdle() const {
  if (busy_)
    throw std::runtime_error("the Segmenter is segmenting in another thread");
}

void Segmenter::set(const py::dict& keywords) {
  checkIdle();
  pcl_ncut_seg::Parameters params = seg_.getParameters();
  applyKeywords(params, keywords);
  seg_.setParameters(params); // valid: applyKeywords checked them
}

py::object Segmenter::get(const std::string& name) const {
  const pcl_ncut_seg::ParameterInfo* row = pcl_ncut_seg::findParameter(name);
  if (!row)
    throw py::value_error("unknown parameter '" + name + "'");
  return parameterObject(*row, seg_.getParameters());
}

py::dict Segmenter::parameters() const {
  return parameterDict(seg_.getParameters());
}

py::array_t<std::int32_t> Segmenter::segment(const py::object& points, const py::object& normals,
                                             const py::object& sensor_origin,
                                             const py::dict& keywords) {
  checkIdle();
  if (!points.is_none()) {
    // Before any change: bad points change nothing.
    auto cloud = cloudFromArray(points, normals, sensor_origin);
    set(keywords);
    cloud_ = cloud;
    seg_.setInputCloud(cloud_);
  } else {
    if (!cloud_)
      throw py::value_error("no points: give an (N, 3) array of float32 or float64");
    if (!normals.is_none())
      throw py::value_error("normals without points: give the points they belong to");
    if (!sensor_origin.is_none())
      throw py::value_error("sensor_origin without points: give the points it belongs to");
    set(keywords);
  }
  have_result_ = false;
  labels_.clear();
  const std::size_t analyses_before = analyses_;
  std::vector<pcl::PointIndices> segments;
  {
    BusyGuard busy(busy_);
    py::gil_scoped_release release; // other threads' segmenters run meanwhile
    seg_.extract(segments);
  }
  // The library's status: its reason is the ValueError's, its warnings are Python's.
  const pcl_ncut_seg::Status& status = seg_.getStatus();
  if (!status.ok() || segments.empty())
    throw py::value_error(status.message.empty() ? "the segmentation failed" : status.message);
  const py::object warn = py::module_::import("warnings").attr("warn");
  for (const pcl_ncut_seg::Warning& w : status.warnings)
    warn(w.message, py::module_::import("builtins").attr("RuntimeWarning"), 1);

  const auto labeled = seg_.getLabeledCloud();
  labels_.resize(labeled->size());
  for (std::size_t i = 0; i < labeled->size(); ++i)
    labels_[i] = static_cast<std::int32_t>((*labeled)[i].label);
  times_ = seg_.getPhaseTimes();
  if (analyses_ == analyses_before) // the kept analysis: its phases cost nothing this time
    times_.knn = times_.centrality = times_.supernodes = times_.refinement = 0.0;
  have_result_ = true;
  return labels();
}

void Segmenter::requireResult() const {
  checkIdle();
  if (!have_result_)
    throw std::runtime_error("no result: call segment(points) first");
  if (!seg_.getAnalysis())
    throw std::runtime_error("no result: an analysis parameter changed since the last "
                             "segment(); call segment() again");
}

py::array_t<std::int32_t> Segmenter::labels() const {
  requireResult();
  py::array_t<std::int32_t> flat = toArray(labels_);
  if (cloud_ && cloud_->height > 1) // as the points came: an image's labels
    return flat.reshape({py::ssize_t(cloud_->height), py::ssize_t(cloud_->width)});
  return flat;
}

py::array_t<float> Segmenter::centrality() const {
  requireResult();
  return toArray(seg_.getCentrality());
}

py::array_t<std::int32_t> Segmenter::supernodeLabels(bool refined) const {
  requireResult();
  const std::vector<int> label = seg_.getSupernodeLabels(refined);
  return toArray(std::vector<std::int32_t>(label.begin(), label.end()));
}

py::array_t<std::int64_t> Segmenter::localMaxima() const {
  requireResult();
  return indexArray(seg_.getLocalMaxima());
}

py::array_t<std::int64_t> Segmenter::saddles() const {
  requireResult();
  return indexArray(seg_.getSaddles());
}

py::dict Segmenter::hierarchy() const {
  requireResult();
  const pcl_ncut_seg::SegmentTree h = seg_.getHierarchy();
  const std::size_t m = h.nodes.size(), columns = 2 * h.num_supernodes;
  const std::vector<int>& supernode_segment = h.supernode_segment;
  py::array_t<std::int32_t> parent(m), left(m), right(m), segment(m);
  py::array_t<double> ncut(m);
  py::array_t<bool> vertices({m, columns});
  auto pa = parent.mutable_unchecked<1>(), le = left.mutable_unchecked<1>();
  auto ri = right.mutable_unchecked<1>(), se = segment.mutable_unchecked<1>();
  auto nc = ncut.mutable_unchecked<1>();
  auto ve = vertices.mutable_unchecked<2>();
  for (std::size_t i = 0; i < m; ++i) {
    const pcl_ncut_seg::SegmentTree::Node& node = h.nodes[i];
    const auto k = static_cast<py::ssize_t>(i);
    pa(k) = node.parent;
    le(k) = node.left;
    ri(k) = node.right;
    nc(k) = node.ncut; // NaN where no bisection exists
    se(k) = 0;
    for (std::size_t c = 0; c < columns; ++c)
      ve(k, static_cast<py::ssize_t>(c)) = false;
    for (std::uint32_t v : node.vertices)
      ve(k, v) = true;
    for (std::uint32_t s : node.supernodes) // a leaf's segment: that of its supernodes
      if (node.isLeaf() && s < supernode_segment.size())
        se(k) = static_cast<std::int32_t>(supernode_segment[s] + 1);
  }
  py::dict d;
  d["parent"] = parent;
  d["left"] = left;
  d["right"] = right;
  d["ncut"] = ncut;
  d["vertices"] = vertices;
  d["segment"] = segment;
  return d;
}

py::array_t<std::int32_t> Segmenter::supernodeSegments() const {
  requireResult();
  std::vector<std::int32_t> out;
  for (std::uint32_t s : seg_.result().supernode_segment)
    out.push_back(static_cast<std::int32_t>(s + 1));
  return toArray(out);
}

py::dict Segmenter::supernodeGraph() const {
  requireResult();
  const pcl_ncut_seg::SupernodeGraph g = seg_.getSupernodeGraph();
  const std::size_t e = g.edges.size();
  py::array_t<std::int64_t> edges({e, std::size_t(2)});
  py::array_t<double> weights(e);
  auto ed = edges.mutable_unchecked<2>();
  auto we = weights.mutable_unchecked<1>();
  for (std::size_t i = 0; i < e; ++i) {
    const auto k = static_cast<py::ssize_t>(i);
    ed(k, 0) = g.edges[i].source;
    ed(k, 1) = g.edges[i].target;
    we(k) = g.edges[i].weight;
  }
  py::dict d;
  d["num_vertices"] = g.num_vertices;
  d["edges"] = edges;
  d["weights"] = weights;
  return d;
}

std::size_t Segmenter::numSegments() const {
  requireResult();
  return seg_.result().num_segments;
}

std::size_t Segmenter::numSupernodes(bool refined) const {
  requireResult();
  return seg_.getNumberOfSupernodes(refined);
}

py::dict Segmenter::noiseTest() const {
  requireResult();
  const pcl_ncut_seg::NoiseTest test = seg_.getNoiseTest();
  py::dict d;
  d["residual_growth"] = test.residual_growth;
  d["sampling_irregularity"] = test.sampling_irregularity;
  d["irregular"] = test.irregular;
  d["projected"] = test.projected;
  return d;
}

py::dict Segmenter::viewTest() const {
  requireResult();
  const pcl_ncut_seg::ViewTest test = seg_.getViewTest();
  py::dict d;
  d["view"] = test.view;
  d["origin_estimated"] = test.origin_estimated;
  d["origin"] = py::make_tuple(test.origin[0], test.origin[1], test.origin[2]);
  d["rim_points"] = test.rim_points;
  return d;
}

py::dict Segmenter::phaseTimes() const {
  requireResult();
  py::dict d;
  d["knn"] = times_.knn;
  d["centrality"] = times_.centrality;
  d["supernodes"] = times_.supernodes;
  d["refinement"] = times_.refinement;
  d["hierarchy"] = times_.hierarchy;
  d["points"] = times_.points;
  d["total"] = times_.total();
  return d;
}

std::string Segmenter::repr() const {
  // The parameters that differ from the defaults, as keywords.
  std::ostringstream s;
  s << "pcl_ncut_seg.Segmenter(";
  const pcl_ncut_seg::Parameters defaults;
  bool first = true;
  for (const pcl_ncut_seg::ParameterInfo* r : keywordOrder()) {
    if (r->get(seg_.getParameters()) == r->get(defaults))
      continue;
    s << (first ? "" : ", ") << r->name << "="
      << py::repr(parameterObject(*r, seg_.getParameters())).cast<std::string>();
    first = false;
  }
  s << ")";
  return s.str();
}

} // namespace pcl_ncut_seg_python
