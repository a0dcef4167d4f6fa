// Segments two spheres far apart with the installed library, through the PCL class and through
// segmentPoints(): expects two segments, one per sphere, the same from both; reads the tree of
// bisections and the supernode graph (getHierarchy(), getSupernodeGraph()) and the status of a
// good and a bad extract(). Exits non-zero otherwise. Only the installed headers are reachable
// (the core's are not installed).
#include <pcl_ncut_seg/segment_points.h>
#include <pcl_ncut_seg/segment_tree.h>
#include <pcl_ncut_seg/status.h>
#include <pcl_ncut_seg/supernode_ncut_segmentation.h>

#include <pcl/point_cloud.h>
#include <pcl/point_types.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <limits>
#include <set>
#include <string>
#include <vector>

namespace {

using Seg = pcl::SupernodeNCutSegmentation<pcl::PointXYZ>;

bool fail(const std::string& why) {
  std::fprintf(stderr, "%s\n", why.c_str());
  return false;
}

/** The tree of bisections: the root covers every supernode, each split node's children
 * partition it, NCut values finite and in [0, 2]; the graph has 2 l vertices and its edges
 * lie among them. */
bool checkHierarchy(const Seg& seg, std::size_t segments) {
  const pcl_ncut_seg::SegmentTree tree = seg.getHierarchy();
  const pcl_ncut_seg::SupernodeGraph graph = seg.getSupernodeGraph();
  const std::size_t l = seg.getNumberOfSupernodes(true);
  if (l < 2 || tree.nodes.empty() || tree.num_supernodes != l || graph.num_vertices != 2 * l)
    return fail("no hierarchy over the " + std::to_string(l) + " supernodes");
  for (const auto& e : graph.edges)
    if (e.source >= graph.num_vertices || e.target >= graph.num_vertices || !(e.weight >= 0.0))
      return fail("an edge of G_s outside its vertices, or of a negative weight");
  const auto& root = tree.nodes[0];
  if (root.parent != -1 || root.supernodes.size() != l || root.vertices.size() != 2 * l)
    return fail("the root does not cover every supernode");
  std::size_t splits = 0;
  for (std::size_t i = 0; i < tree.nodes.size(); ++i) {
    const auto& node = tree.nodes[i];
    if (node.isLeaf())
      continue;
    ++splits;
    if (!std::isfinite(node.ncut) || node.ncut < 0.0 || node.ncut > 2.0)
      return fail("NCut " + std::to_string(node.ncut) + " of node " + std::to_string(i));
    std::vector<std::uint32_t> both = tree.nodes[node.left].supernodes;
    const auto& right = tree.nodes[node.right].supernodes;
    both.insert(both.end(), right.begin(), right.end());
    std::sort(both.begin(), both.end());
    if (both != node.supernodes || tree.nodes[node.left].parent != static_cast<int>(i))
      return fail("the children of node " + std::to_string(i) + " do not partition it");
  }
  const std::size_t leaves = tree.leaves().size();
  if (splits + 1 != leaves || leaves < segments)
    return fail(std::to_string(splits) + " splits, " + std::to_string(leaves) + " leaves for " +
                std::to_string(segments) + " segments");
  return true;
}

/** The status: ok after the good extract(); the reason after one on a cloud with no finite
 * point. */
bool checkStatus(const Seg& good) {
  if (!good.getStatus().ok() || !good.getStatus().warnings.empty())
    return fail("a good extract() has a status of " + good.getStatus().message);
  Seg bad;
  bad.setConsoleMessages(false);
  pcl::PointCloud<pcl::PointXYZ>::Ptr nan(new pcl::PointCloud<pcl::PointXYZ>);
  const float q = std::numeric_limits<float>::quiet_NaN();
  nan->push_back(pcl::PointXYZ(q, q, q));
  bad.setInputCloud(nan);
  std::vector<pcl::PointIndices> none;
  bad.extract(none);
  const pcl_ncut_seg::Status& status = bad.getStatus();
  if (status.ok() || status.code != pcl_ncut_seg::StatusCode::NoFinitePoint ||
      status.message != "the input has no finite point.")
    return fail("an all-NaN cloud's status: '" + status.message + "'");
  return true;
}

} // namespace

int main() {
  pcl::PointCloud<pcl::PointXYZ>::Ptr cloud(new pcl::PointCloud<pcl::PointXYZ>);
  const int n = 500; // points per sphere, on a Fibonacci spiral
  for (int s = 0; s < 2; ++s)
    for (int i = 0; i < n; ++i) {
      const float z = 1.0f - 2.0f * (static_cast<float>(i) + 0.5f) / n;
      const float rho = std::sqrt(1.0f - z * z), phi = 2.39996323f * static_cast<float>(i);
      cloud->push_back(pcl::PointXYZ(rho * std::cos(phi) + 10.0f * static_cast<float>(s),
                                     rho * std::sin(phi), z));
    }

  Seg seg;
  seg.setInputCloud(cloud);
  seg.setNumberOfNeighbours(10);
  seg.setNumberOfSegments(2);
  std::vector<pcl::PointIndices> segments;
  seg.extract(segments);

  if (segments.size() != 2) {
    std::fprintf(stderr, "expected 2 segments, got %zu\n", segments.size());
    return 1;
  }
  for (const pcl::PointIndices& segment : segments) {
    std::set<int> spheres;
    for (int index : segment.indices)
      spheres.insert(index / n);
    if (segment.indices.size() != static_cast<std::size_t>(n) || spheres.size() != 1) {
      std::fprintf(stderr, "a segment is not exactly one sphere (%zu points)\n",
                   segment.indices.size());
      return 1;
    }
  }
  const auto colored = seg.getColoredCloud();
  if (!colored || colored->size() != cloud->size()) {
    std::fprintf(stderr, "no coloured cloud\n");
    return 1;
  }
  std::vector<float> xyz;
  for (const pcl::PointXYZ& p : *cloud)
    xyz.insert(xyz.end(), {p.x, p.y, p.z});
  const std::vector<std::uint32_t> labels =
      pcl_ncut_seg::segmentPoints(xyz.data(), cloud->size(), seg.getParameters());
  for (std::size_t s = 0; s < segments.size(); ++s)
    for (int index : segments[s].indices)
      if (labels.size() != cloud->size() || labels[index] != s) {
        std::fprintf(stderr, "segmentPoints() disagrees with the PCL class\n");
        return 1;
      }
  if (!checkHierarchy(seg, segments.size()) || !checkStatus(seg))
    return 1;
  std::printf("pcl_ncut_seg consumer: 2 segments of %d points, their tree of bisections and "
              "the status, as expected\n",
              n);
  return 0;
}
