#include "eval_views.h"

#include "cli/algorithm_flags.h"
#include "depth_view_pcl.h"
#include "psb_peers.h"
#include "view_scoring.h"

#include <pcl/console/print.h>

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

/** The valid pixels' indices and their x, y, z. */
std::vector<std::size_t> validPixels(const DepthView& view, std::vector<float>& xyz) {
  std::vector<std::size_t> pixels;
  xyz.clear();
  for (std::size_t i = 0; i < view.face.size(); ++i)
    if (view.face[i] >= 0) {
      pixels.push_back(i);
      xyz.insert(xyz.end(), view.xyz.begin() + 3 * i, view.xyz.begin() + 3 * i + 3);
    }
  return pixels;
}

/** Labels of the valid points spread onto the pixels (-1 elsewhere). */
std::vector<int> toPixels(const std::vector<int>& labels, const std::vector<std::size_t>& pixels,
                          std::size_t size) {
  std::vector<int> out(size, -1);
  for (std::size_t i = 0; i < pixels.size(); ++i)
    out[pixels[i]] = labels[i];
  return out;
}

/** The labels of the valid pixels only (what the segments per view count). */
std::vector<int> onValid(const std::vector<int>& pixel_labels, const std::vector<std::size_t>& px) {
  return restrictToFaces(pixel_labels, px);
}

/** 'ours' on the organized cloud, NaNs and sensor pose included: a label per pixel. */
std::vector<int> oursOnView(const DepthView& view, const Options& opt, double* seconds) {
  tool::Segmenter seg;
  if (!seg.setParameters(opt.params))
    throw Failure("the segmenter refused the parameters");
  seg.setInputCloud(toPclCloud(view));
  std::vector<pcl::PointIndices> segments;
  const auto start = Clock::now();
  seg.extract(segments);
  *seconds = secondsSince(start);
  return segmentsToLabels(segments, view.face.size());
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

/** LCCP or CPC on the valid points, normals towards the sensor: a label per pixel. */
std::vector<int> peerOnView(const DepthView& view, bool cpc, const std::string& model,
                            double* seconds) {
  std::vector<float> xyz;
  const std::vector<std::size_t> pixels = validPixels(view, xyz);
  PeerParams params;
  const auto& o = view.pose.origin;
  params.viewpoint = std::array<float, 3>{
      {static_cast<float>(o[0]), static_cast<float>(o[1]), static_cast<float>(o[2])}};
  std::vector<int> labels;
  std::string error;
  const auto start = Clock::now();
  // CPC reports every failed RANSAC draw as an error; they are part of how it works.
  pcl::console::setVerbosityLevel(pcl::console::L_ALWAYS);
  const bool ok = segmentWithPclPeer(xyz, cpc, params, labels, &error);
  pcl::console::setVerbosityLevel(pcl::console::L_WARN);
  *seconds = secondsSince(start);
  if (!ok)
    throw Failure(std::string(cpc ? "cpc" : "lccp") + " on a view of model " + model + ": " +
                  error);
  return toPixels(labels, pixels, view.face.size());
}

/** A method's pixel labels scored on the view's seen faces. */
void addPixelMethod(const std::string& method, const ScoredView& s,
                    const std::vector<int>& pixel_labels, double seconds, ModelSums& sums) {
  std::vector<float> xyz;
  const std::vector<int> faces = faceLabelsFromPixels(s.view.face, pixel_labels, s.seen);
  const double segments =
      static_cast<double>(countSegments(onValid(pixel_labels, validPixels(s.view, xyz))));
  sums.add(method, againstHumans(faces, s.humans, s.area), segments, seconds);
}

/** Every method of the options on one view. */
void scoreView(const Model& m, const Options& opt, const ScoredView& s,
               const std::vector<int>& whole, double whole_seconds, ModelSums& sums) {
  double secs = 0;
  if (opt.has("ours")) {
    const std::vector<int> labels = oursOnView(s.view, opt, &secs);
    addPixelMethod("ours", s, labels, secs, sums);
    const std::vector<int> seen = restrictToFaces(whole, s.seen);
    sums.add("ours whole", againstHumans(seen, s.humans, s.area),
             static_cast<double>(countSegments(seen)), whole_seconds);
  }
  for (const char* peer : {"lccp", "cpc"})
    if (opt.has(peer)) {
      const std::vector<int> labels = peerOnView(s.view, std::string(peer) == "cpc", m.name, &secs);
      addPixelMethod(peer, s, labels, secs, sums);
    }
  if (opt.has("one"))
    addPixelMethod("one", s, std::vector<int>(s.view.face.size(), 0), 0, sums);
  if (opt.has("octants")) {
    std::vector<float> xyz;
    const std::vector<std::size_t> pixels = validPixels(s.view, xyz);
    const auto start = Clock::now();
    const std::vector<int> labels = segmentOctants(xyz);
    secs = secondsSince(start);
    addPixelMethod("octants", s, toPixels(labels, pixels, s.view.face.size()), secs, sums);
  }
  if (opt.has("human") && s.humans.size() >= 2) {
    double segments = 0;
    const SegmentationScores h = humansAgainstEachOther(s.humans, s.area, &segments);
    sums.add("human", h, segments, 0);
  }
  sums.faces += static_cast<double>(s.seen.size());
  sums.points += static_cast<double>(s.view.validPixels());
}

} // namespace

double scoreViews(const Model& m, const Options& opt, Report& report) {
  double whole_seconds = 0;
  std::vector<int> whole;
  if (opt.has("ours"))
    whole = oursOnWhole(m, opt, &whole_seconds);
  ModelSums sums;
  for (int v = 0; v < opt.views; ++v)
    scoreView(m, opt, makeView(m, opt, v), whole, whole_seconds, sums);
  for (const std::string& method : sums.order) {
    const Sums& s = sums.by_method.at(method);
    Row r;
    r.id = m.id;
    r.category = m.category;
    r.faces = static_cast<std::size_t>(sums.faces / opt.views + 0.5);
    r.humans = m.humans.size();
    r.method = method;
    r.mode = "view";
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
