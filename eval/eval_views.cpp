#include "eval_views.h"

#include "eval_sampling.h"
#include "psb_peers.h"
#include "view_scoring.h"
#include <cli/algorithm_flags.h>
#include <surfaces/depth_view_pcl.h>

#include <pcl/console/print.h>
#include <pcl/filters/voxel_grid.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <string>
#include <utility>

namespace pcl_ncut_seg {
namespace eval {

namespace {

using Clock = std::chrono::steady_clock;

/** One view and what it is scored on: its seen faces, their areas and the people's labels. */
struct ScoredView {
  DepthView view;
  std::size_t index = 0;                         ///< which view of the model
  const std::vector<float>* centroids = nullptr; ///< the mesh's face centroids (mesh frame)
  std::vector<std::size_t> seen;
  std::vector<double> area;
  std::vector<std::vector<int>> humans;
};

ScoredView makeView(const Model& m, const Options& opt, int v) {
  ScoredView s;
  s.view = renderView(m.mesh, opt.camera,
                      viewSeed(static_cast<std::uint64_t>(m.id), static_cast<std::uint64_t>(v)));
  s.seen = seenFaces(s.view.face);
  if (s.seen.empty())
    throw Failure("view " + std::to_string(v) + " of model " + m.name + " sees no face");
  s.area = restrictToFaces(m.area, s.seen);
  for (const auto& h : m.humans)
    s.humans.push_back(restrictToFaces(h, s.seen));
  return s;
}

/** A method's sums over a model's views. */
struct Sums {
  SegmentationScores scores;
  double segments = 0, seconds = 0;
  int views = 0;
};

/** Per method, in the order of the first view. */
struct ModelSums {
  std::vector<std::string> order;
  std::map<std::string, Sums> by_method;
  double faces = 0, points = 0;

  void add(const std::string& method, const SegmentationScores& s, double segments,
           double seconds) {
    if (!by_method.count(method))
      order.push_back(method);
    Sums& sum = by_method[method];
    sum.scores += s;
    sum.segments += segments;
    sum.seconds += seconds;
    ++sum.views;
  }
};

/** One form of a view as a segmenter gets it (-view_forms): the cloud, its finite points
 * and, per point of the cloud, the face it lies on (-1 for none). */
struct FormCloud {
  pcl::PointCloud<pcl::PointXYZ>::Ptr cloud;
  std::vector<std::size_t> finite;      ///< the cloud's finite points
  std::vector<float> xyz;               ///< their x, y, z
  std::vector<std::int64_t> point_face; ///< per point of the cloud, where by_pixels
  bool by_pixels = true; ///< scored by the pixels' votes (else each face by its nearest point)
};

void collectFinite(FormCloud& f) {
  f.finite.clear();
  f.xyz.clear();
  for (std::size_t i = 0; i < f.cloud->size(); ++i) {
    const pcl::PointXYZ& p = (*f.cloud)[i];
    if (std::isfinite(p.x) && std::isfinite(p.y) && std::isfinite(p.z)) {
      f.finite.push_back(i);
      f.xyz.insert(f.xyz.end(), {p.x, p.y, p.z});
    }
  }
}

/** An unorganized cloud of the points with the view's pose. */
pcl::PointCloud<pcl::PointXYZ>::Ptr unorganized(const std::vector<float>& xyz,
                                                const pcl::PointCloud<pcl::PointXYZ>& like) {
  pcl::PointCloud<pcl::PointXYZ>::Ptr cloud(new pcl::PointCloud<pcl::PointXYZ>);
  for (std::size_t i = 0; i + 2 < xyz.size(); i += 3)
    cloud->push_back(pcl::PointXYZ(xyz[i], xyz[i + 1], xyz[i + 2]));
  cloud->sensor_origin_ = like.sensor_origin_;
  cloud->sensor_orientation_ = like.sensor_orientation_;
  return cloud;
}

double diagonalOf(const std::vector<float>& xyz) {
  float lo[3] = {1e30f, 1e30f, 1e30f}, hi[3] = {-1e30f, -1e30f, -1e30f};
  for (std::size_t i = 0; i < xyz.size(); ++i) {
    lo[i % 3] = std::min(lo[i % 3], xyz[i]);
    hi[i % 3] = std::max(hi[i % 3], xyz[i]);
  }
  return std::sqrt(double(hi[0] - lo[0]) * (hi[0] - lo[0]) +
                   double(hi[1] - lo[1]) * (hi[1] - lo[1]) +
                   double(hi[2] - lo[2]) * (hi[2] - lo[2]));
}

/** The points drawn uniformly by area on the seen faces, in the view's world frame, with
 * isotropic noise of 0.002 diagonals (a laser scanner's view of the same surface). */
std::vector<float> laserPoints(const Model& m, const ScoredView& s, std::size_t n,
                               double diagonal) {
  TriangleMesh seen;
  seen.vertices = m.mesh.vertices;
  seen.num_original_faces = m.mesh.num_original_faces;
  std::vector<std::uint8_t> is_seen(m.mesh.num_original_faces, 0);
  for (const std::size_t f : s.seen)
    is_seen[f] = 1;
  for (std::size_t t = 0; t < m.mesh.numTriangles(); ++t)
    if (is_seen[m.mesh.original_face[t]]) {
      seen.faces.insert(seen.faces.end(), m.mesh.faces.begin() + 3 * t,
                        m.mesh.faces.begin() + 3 * t + 3);
      seen.original_face.push_back(m.mesh.original_face[t]);
    }
  const std::uint64_t seed = drawSeed(m.id, static_cast<int>(s.index), 7);
  std::vector<float> xyz = sampleSurface(seen, n, seed);
  for (std::size_t i = 0; i < xyz.size(); ++i)
    xyz[i] = static_cast<float>(s.view.scale * (xyz[i] - s.view.centre[i % 3]));
  addNoise(xyz, 0.002 * diagonal, seed + 1);
  return xyz;
}

/** The view in one form (kViewForms). */
FormCloud makeForm(const Model& m, const ScoredView& s, const std::string& form,
                   const Options& opt) {
  FormCloud f;
  f.cloud = toPclCloud(s.view);
  if (!opt.view_origin_known) {
    f.cloud->sensor_origin_ = Eigen::Vector4f::Zero();
    f.cloud->sensor_orientation_ = Eigen::Quaternionf::Identity();
  }
  f.point_face = s.view.face;
  if (form != "view") {
    collectFinite(f);
    std::vector<std::int64_t> face;
    for (const std::size_t i : f.finite)
      face.push_back(f.point_face[i]);
    f.point_face = std::move(face);
    const double diagonal = diagonalOf(f.xyz);
    if (form == "voxel") {
      pcl::VoxelGrid<pcl::PointXYZ> grid;
      grid.setInputCloud(unorganized(f.xyz, *f.cloud));
      const float leaf = static_cast<float>(0.01 * diagonal);
      grid.setLeafSize(leaf, leaf, leaf);
      pcl::PointCloud<pcl::PointXYZ>::Ptr out(new pcl::PointCloud<pcl::PointXYZ>);
      grid.filter(*out);
      out->sensor_origin_ = f.cloud->sensor_origin_;
      out->sensor_orientation_ = f.cloud->sensor_orientation_;
      f.cloud = out;
      f.by_pixels = false;
    } else if (form == "laser") {
      f.cloud = unorganized(laserPoints(m, s, f.finite.size(), diagonal), *f.cloud);
      f.by_pixels = false;
    } else {
      f.cloud = unorganized(f.xyz, *f.cloud);
    }
  }
  collectFinite(f);
  return f;
}

/** The seen faces' labels from the labels of a form's points. */
std::vector<int> faceLabelsOf(const FormCloud& f, const ScoredView& s,
                              const std::vector<int>& labels) {
  if (f.by_pixels)
    return faceLabelsFromPixels(f.point_face, labels, s.seen);
  // Each seen face takes the label of the point nearest to its centroid.
  std::vector<float> centroids;
  for (const std::size_t face : s.seen)
    for (int d = 0; d < 3; ++d)
      centroids.push_back(
          static_cast<float>(s.view.scale * ((*s.centroids)[3 * face + d] - s.view.centre[d])));
  std::vector<int> finite_labels;
  for (const std::size_t i : f.finite)
    finite_labels.push_back(labels[i]);
  return faceLabels(finite_labels, nearestPoints(f.xyz, centroids));
}

/** 'ours' on the form's cloud: a label per point of the cloud. */
std::vector<int> oursOnForm(const FormCloud& f, const Options& opt, double* seconds) {
  tool::Segmenter seg;
  if (!seg.setParameters(opt.params))
    throw Failure("the segmenter refused the parameters");
  seg.setInputCloud(f.cloud);
  std::vector<pcl::PointIndices> segments;
  const auto start = Clock::now();
  seg.extract(segments);
  *seconds = secondsSince(start);
  return segmentsToLabels(segments, f.cloud->size());
}

/** 'ours' on the whole object (the face centroids): a label per face. */
std::vector<int> oursOnWhole(const Model& m, const Options& opt, double* seconds) {
  pcl::PointCloud<pcl::PointXYZ>::Ptr cloud(new pcl::PointCloud<pcl::PointXYZ>);
  cloud->resize(m.n);
  for (std::size_t i = 0; i < m.n; ++i)
    (*cloud)[i] = pcl::PointXYZ(m.xyz[3 * i], m.xyz[3 * i + 1], m.xyz[3 * i + 2]);
  tool::Segmenter seg;
  if (!seg.setParameters(opt.params))
    throw Failure("the segmenter refused the parameters");
  seg.setInputCloud(cloud);
  std::vector<pcl::PointIndices> segments;
  const auto start = Clock::now();
  seg.extract(segments);
  *seconds = secondsSince(start);
  return segmentsToLabels(segments, m.n);
}

/** LCCP or CPC on the form's finite points: a label per point of the cloud. With the origin
 * known, normals face the sensor; else away from the points' centroid. */
std::vector<int> peerOnForm(const FormCloud& f, bool cpc, const Options& opt,
                            const std::string& model, double* seconds) {
  PeerParams params = opt.peerParams(cpc, true);
  if (opt.view_origin_known) {
    const auto& o = f.cloud->sensor_origin_;
    params.viewpoint = std::array<float, 3>{{o[0], o[1], o[2]}};
  }
  std::vector<int> labels;
  std::string error;
  const auto start = Clock::now();
  // CPC reports every failed RANSAC draw as an error; they are part of how it works.
  pcl::console::setVerbosityLevel(pcl::console::L_ALWAYS);
  const bool ok = segmentWithPclPeer(f.xyz, cpc, params, labels, &error);
  pcl::console::setVerbosityLevel(pcl::console::L_WARN);
  *seconds = secondsSince(start);
  if (!ok)
    throw Failure(std::string(cpc ? "cpc" : "lccp") + " on a view of model " + model + ": " +
                  error);
  std::vector<int> out(f.cloud->size(), -1);
  for (std::size_t i = 0; i < f.finite.size(); ++i)
    out[f.finite[i]] = labels[i];
  return out;
}

/** A method's point labels scored on the view's seen faces. */
void addMethod(const std::string& method, const std::string& mode, const FormCloud& f,
               const ScoredView& s, const std::vector<int>& labels, double seconds,
               ModelSums& sums) {
  const std::vector<int> faces = faceLabelsOf(f, s, labels);
  const double segments = static_cast<double>(countSegments(restrictToFaces(labels, f.finite)));
  sums.add(method + "\t" + mode, againstHumans(faces, s.humans, s.area), segments, seconds);
}

/** Every method of the options on one form of one view. */
void scoreForm(const Model& m, const Options& opt, const ScoredView& s, const std::string& form,
               ModelSums& sums) {
  const FormCloud f = makeForm(m, s, form, opt);
  double secs = 0;
  if (opt.has("ours")) {
    const std::vector<int> labels = oursOnForm(f, opt, &secs);
    addMethod("ours", form, f, s, labels, secs, sums);
  }
  for (const char* peer : {"lccp", "cpc"})
    if (opt.has(peer)) {
      const std::vector<int> labels = peerOnForm(f, std::string(peer) == "cpc", opt, m.name, &secs);
      addMethod(peer, form, f, s, labels, secs, sums);
    }
  if (opt.has("one"))
    addMethod("one", form, f, s, std::vector<int>(f.cloud->size(), 0), 0, sums);
  if (opt.has("octants")) {
    const auto start = Clock::now();
    const std::vector<int> finite = segmentOctants(f.xyz);
    secs = secondsSince(start);
    std::vector<int> labels(f.cloud->size(), -1);
    for (std::size_t i = 0; i < f.finite.size(); ++i)
      labels[f.finite[i]] = finite[i];
    addMethod("octants", form, f, s, labels, secs, sums);
  }
}

/** Every form of one view, and what does not depend on the form (ours whole, the people). */
void scoreView(const Model& m, const Options& opt, const ScoredView& s,
               const std::vector<int>& whole, double whole_seconds, ModelSums& sums) {
  for (const std::string& form : opt.view_forms) {
    scoreForm(m, opt, s, form, sums);
    if (opt.has("whole")) {
      const std::vector<int> seen = restrictToFaces(whole, s.seen);
      sums.add("ours whole\t" + form, againstHumans(seen, s.humans, s.area),
               static_cast<double>(countSegments(seen)), whole_seconds);
    }
    if (opt.has("human") && s.humans.size() >= 2) {
      double segments = 0;
      const SegmentationScores h = humansAgainstEachOther(s.humans, s.area, &segments);
      sums.add("human\t" + form, h, segments, 0);
    }
  }
  sums.faces += static_cast<double>(s.seen.size());
  sums.points += static_cast<double>(s.view.validPixels());
}

} // namespace

double scoreViews(const Model& m, const Options& opt, Report& report) {
  double whole_seconds = 0;
  std::vector<int> whole;
  if (opt.has("whole"))
    whole = oursOnWhole(m, opt, &whole_seconds);
  ModelSums sums;
  const std::vector<float> centroids = faceCentroids(m.mesh);
  for (int v = 0; v < opt.views; ++v) {
    ScoredView s = makeView(m, opt, v);
    s.index = static_cast<std::size_t>(v);
    s.centroids = &centroids;
    scoreView(m, opt, s, whole, whole_seconds, sums);
  }
  for (const std::string& key : sums.order) {
    const Sums& s = sums.by_method.at(key);
    const std::size_t tab = key.find('\t');
    Row r;
    r.id = m.id;
    r.category = m.category;
    r.faces = static_cast<std::size_t>(sums.faces / opt.views + 0.5);
    r.humans = m.humans.size();
    r.method = key.substr(0, tab);
    r.mode = key.substr(tab + 1);
    const double n = static_cast<double>(s.views);
    r.scores = s.scores / n;
    r.segments = s.segments / n;
    r.seconds = s.seconds / n;
    report.rows.push_back(r);
  }
  return sums.points / opt.views;
}

} // namespace eval
} // namespace pcl_ncut_seg
