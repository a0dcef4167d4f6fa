/*
 * pcl_ncut_seg_bench_geodesics: the exact multi-source search (multiSourceDijkstra(),
 * core/graph/shortest_paths.h) against Boost.Graph's Dijkstra over a compressed_sparse_row_graph
 * with a range of sources, on one sampled model, for the two CAD searches that Boost can
 * express: ridgeDistance() (distances alone) and the nearest region of splitAtRidges() (the
 * source's label, the lowest among equally near ones).
 *
 * The graph is the front end's (Morton order, k = 10, symmetric); the ridges are cadGraph()'s at
 * the default cad.ridge_angle, from orientedNormals(). Each round times the hand-written search
 * and Boost's (with and without building Boost's graph from the CsrGraph) in turn, alternating
 * which goes first; the medians are printed, and whether the results are bit-identical.
 */
#include "core/cad/cad.h"
#include "core/common/morton.h"
#include "core/cut/concavity.h"
#include "core/graph/csr_graph.h"
#include "core/graph/shortest_paths.h"

#include "timing.h"
#include <surfaces/mesh_sampling.h>

#include <boost/graph/compressed_sparse_row_graph.hpp>
#include <boost/graph/dijkstra_shortest_paths.hpp>

#include <pcl/kdtree/kdtree_flann.h>
#include <pcl/point_cloud.h>
#include <pcl/point_types.h>

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <functional>
#include <limits>
#include <string>
#include <vector>

namespace {
using pcl_ncut_seg::CsrGraph;
using pcl_ncut_seg_bench::now;
constexpr float kInf = std::numeric_limits<float>::infinity();
constexpr std::uint32_t kNone = std::numeric_limits<std::uint32_t>::max();

using BoostGraph =
    boost::compressed_sparse_row_graph<boost::directedS, boost::no_property, boost::no_property,
                                       boost::no_property, std::uint32_t, std::uint32_t>;

BoostGraph toBoost(const CsrGraph& graph) {
  std::vector<std::pair<std::uint32_t, std::uint32_t>> edges;
  edges.reserve(graph.numDirectedEdges());
  for (std::uint32_t v = 0; v < graph.numVertices(); ++v)
    for (std::uint32_t e = graph.offsets[v]; e < graph.offsets[v + 1]; ++e)
      edges.emplace_back(v, graph.targets[e]);
  return BoostGraph(boost::edges_are_sorted, edges.begin(), edges.end(),
                    static_cast<std::uint32_t>(graph.numVertices()),
                    static_cast<std::uint32_t>(edges.size()));
}

/// The same graph by copying the CsrGraph's rows into Boost's (public, undocumented) arrays:
/// the least a Boost graph can cost.
BoostGraph copyToBoost(const CsrGraph& graph) {
  BoostGraph g(boost::edges_are_sorted,
               static_cast<std::pair<std::uint32_t, std::uint32_t>*>(nullptr),
               static_cast<std::pair<std::uint32_t, std::uint32_t>*>(nullptr),
               static_cast<std::uint32_t>(graph.numVertices()));
  g.m_forward.m_rowstart.assign(graph.offsets.begin(), graph.offsets.end());
  g.m_forward.m_column.assign(graph.targets.begin(), graph.targets.end());
  return g;
}

/// Owners as multiSourceDijkstra() keeps them where Boost can: a relaxed edge passes its
/// source's label on, an edge that ties passes on a lower one (a vertex already finished at
/// that distance cannot be queued again: counted in ties_after_finish).
struct OwnerVisitor : boost::default_dijkstra_visitor {
  const float* dist;
  const float* length;
  std::uint32_t* owner;
  std::size_t* late;
  template <class E, class G> void edge_relaxed(E e, const G& g) const {
    owner[boost::target(e, g)] = owner[boost::source(e, g)];
  }
  template <class E, class G> void edge_not_relaxed(E e, const G& g) const {
    const auto p = boost::source(e, g), q = boost::target(e, g);
    if (dist[p] + length[boost::get(boost::edge_index, g, e)] == dist[q] && owner[p] < owner[q]) {
      owner[q] = owner[p];
      ++*late; // an upper bound of the ties that may come after q is finished
    }
  }
};

void boostSearch(const BoostGraph& g, const CsrGraph& graph,
                 const std::vector<std::uint32_t>& sources, float* dist, std::uint32_t* owner,
                 std::size_t* late) {
  const auto weight =
      boost::make_iterator_property_map(graph.lengths.data(), boost::get(boost::edge_index, g));
  const auto index = boost::get(boost::vertex_index, g);
  const auto d = boost::make_iterator_property_map(dist, index);
  if (owner) {
    OwnerVisitor vis;
    vis.dist = dist;
    vis.length = graph.lengths.data();
    vis.owner = owner;
    vis.late = late;
    boost::dijkstra_shortest_paths_no_init(g, sources.begin(), sources.end(),
                                           boost::dummy_property_map(), d, weight, index,
                                           std::less<float>(), std::plus<float>(), 0.0f, vis);
  } else {
    boost::dijkstra_shortest_paths_no_init(
        g, sources.begin(), sources.end(), boost::dummy_property_map(), d, weight, index,
        std::less<float>(), std::plus<float>(), 0.0f, boost::default_dijkstra_visitor());
  }
}

double median(std::vector<double> x) {
  std::sort(x.begin(), x.end());
  return x.empty() ? 0.0 : x[x.size() / 2];
}

CsrGraph frontEndGraph(const std::vector<float>& raw, std::vector<float>& xyz) {
  const std::size_t n = raw.size() / 3, k = 10;
  const std::vector<std::uint32_t> order = pcl_ncut_seg::mortonOrder(raw.data(), n);
  xyz.resize(3 * n);
  pcl::PointCloud<pcl::PointXYZ>::Ptr cloud(new pcl::PointCloud<pcl::PointXYZ>);
  cloud->resize(n);
  for (std::size_t i = 0; i < n; ++i) {
    for (int c = 0; c < 3; ++c)
      xyz[3 * i + c] = raw[3 * order[i] + c];
    (*cloud)[i] = pcl::PointXYZ(xyz[3 * i], xyz[3 * i + 1], xyz[3 * i + 2]);
  }
  std::vector<std::uint32_t> knn(n * k, kNone);
  pcl::KdTreeFLANN<pcl::PointXYZ> tree(false);
  tree.setInputCloud(cloud);
  pcl::Indices nn;
  std::vector<float> sqr;
  for (std::size_t i = 0; i < n; ++i) {
    tree.nearestKSearch((*cloud)[i], static_cast<int>(k + 1), nn, sqr);
    std::size_t j = 0;
    for (const auto q : nn)
      if (j < k && q >= 0 && static_cast<std::size_t>(q) != i)
        knn[i * k + j++] = static_cast<std::uint32_t>(q);
  }
  return pcl_ncut_seg::buildSymmetricKnnGraph(xyz.data(), n, knn.data(), k);
}

} // namespace

int main(int argc, char** argv) {
  std::string data = PCL_NCUT_SEG_BENCH_DATA, model = "cgal-fandisk.off";
  std::size_t n = 180926;
  int rounds = 11;
  bool centroids = false; // the CLI's default for a mesh: a point per face centroid
  for (int i = 1; i + 1 < argc; i += 2) {
    const std::string a = argv[i];
    if (a == "--model")
      model = argv[i + 1];
    else if (a == "--n")
      n = std::strtoull(argv[i + 1], nullptr, 10);
    else if (a == "--rounds")
      rounds = std::atoi(argv[i + 1]);
    else if (a == "--centroids")
      centroids = argv[i + 1] == std::string("on");
    else if (a == "--data")
      data = argv[i + 1];
  }
  if (argc % 2 == 0) {
    std::fprintf(
        stderr, "Usage: %s [--model FILE] [--n N] [--rounds R] [--centroids on|off] [--data DIR]\n",
        argv[0]);
    return 2;
  }
  pcl_ncut_seg::TriangleMesh mesh;
  std::string error;
  if (!pcl_ncut_seg::readOff(data + "/models/" + model, mesh, &error)) {
    std::fprintf(stderr, "cannot read %s: %s\n", model.c_str(), error.c_str());
    return 2;
  }
  std::vector<float> xyz;
  const CsrGraph graph = frontEndGraph(
      centroids ? pcl_ncut_seg::faceCentroids(mesh) : pcl_ncut_seg::sampleSurface(mesh, n, 1), xyz);
  n = graph.numVertices();
  const std::vector<float> normals = pcl_ncut_seg::orientedNormals(graph, xyz.data(), 1);
  const std::vector<bool> ridge = pcl_ncut_seg::cadGraph(graph, normals.data(), 5.0f).ridge;
  std::vector<std::uint32_t> ridge_points, off_ridge, label(n, kNone);
  for (std::uint32_t p = 0; p < n; ++p)
    (ridge[p] ? ridge_points : off_ridge).push_back(p);
  for (std::uint32_t p : off_ridge) // regions: blocks of the Morton curve
    label[p] = p / 4096;
  std::printf("%s at %zu points: %zu directed edges, %zu ridge points; load average %s\n",
              model.c_str(), n, graph.numDirectedEdges(), ridge_points.size(),
              pcl_ncut_seg_bench::loadAverage().c_str());

  std::vector<double> t_hand, t_boost, t_build, t_copy, t_hand_own, t_boost_own;
  bool same = true, same_owner = true;
  std::size_t late = 0;
  for (int r = 0; r < rounds; ++r) {
    for (int turn = 0; turn < 2; ++turn) {
      if ((turn == 0) == (r % 2 == 0)) { // the hand-written search
        double t = now();
        const std::vector<float> phi = pcl_ncut_seg::ridgeDistance(graph, ridge);
        t_hand.push_back(now() - t);
        same = same && phi.size() == n;
        std::vector<float> dist(n, kInf);
        std::vector<std::uint32_t> owner = label;
        for (std::uint32_t p : off_ridge)
          dist[p] = 0.0f;
        t = now();
        pcl_ncut_seg::multiSourceDijkstra(graph, off_ridge, dist.data(), pcl_ncut_seg::AnyEdge(),
                                          pcl_ncut_seg::ExpandAll(), owner.data());
        t_hand_own.push_back(now() - t);
      } else { // Boost's, on a graph built for it
        double t = now();
        const BoostGraph g = toBoost(graph);
        t_build.push_back(now() - t);
        t = now();
        const BoostGraph g2 = copyToBoost(graph);
        t_copy.push_back(now() - t);
        same = same && boost::num_edges(g2) == boost::num_edges(g);
        std::vector<float> dist(n, kInf);
        for (std::uint32_t p : ridge_points)
          dist[p] = 0.0f;
        t = now();
        boostSearch(g, graph, ridge_points, dist.data(), nullptr, nullptr);
        t_boost.push_back(now() - t);
        same = same && dist == pcl_ncut_seg::ridgeDistance(graph, ridge);
        std::vector<float> d2(n, kInf);
        std::vector<std::uint32_t> owner(n, kNone);
        for (std::uint32_t p : off_ridge)
          d2[p] = 0.0f, owner[p] = p / 4096;
        late = 0;
        t = now();
        boostSearch(g, graph, off_ridge, d2.data(), owner.data(), &late);
        t_boost_own.push_back(now() - t);
        std::vector<float> d3(n, kInf);
        std::vector<std::uint32_t> o3(n, kNone);
        for (std::uint32_t p : off_ridge)
          d3[p] = 0.0f, o3[p] = p / 4096;
        pcl_ncut_seg::multiSourceDijkstra(graph, off_ridge, d3.data(), pcl_ncut_seg::AnyEdge(),
                                          pcl_ncut_seg::ExpandAll(), o3.data());
        same_owner = same_owner && owner == o3 && d2 == d3;
      }
    }
  }
  std::printf("ridgeDistance: hand-written %.2f ms, Boost %.2f ms + %.2f ms to build its graph "
              "(%.2f ms copying its arrays); distances %s\n",
              1e3 * median(t_hand), 1e3 * median(t_boost), 1e3 * median(t_build),
              1e3 * median(t_copy), same ? "bit-identical" : "DIFFER");
  std::vector<double> diff, diff_own;
  for (std::size_t r = 0; r < t_hand.size(); ++r) {
    diff.push_back(t_boost[r] + t_build[r] - t_hand[r]);
    diff_own.push_back(t_boost_own[r] + t_build[r] - t_hand_own[r]);
  }
  std::printf("paired, per round (Boost + its graph) - hand-written: ridgeDistance %+.2f ms, "
              "nearest region %+.2f ms\n",
              1e3 * median(diff), 1e3 * median(diff_own));
  std::printf("nearest region: hand-written %.2f ms, Boost %.2f ms (+ the same build); owners "
              "%s, %zu late ties\n",
              1e3 * median(t_hand_own), 1e3 * median(t_boost_own),
              same_owner ? "identical" : "DIFFER", late);
  return same && same_owner ? 0 : 1;
}
