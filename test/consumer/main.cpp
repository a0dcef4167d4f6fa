// Segments two spheres far apart with the installed library, through the PCL class and through
// segmentPoints(): expects two segments, one per sphere, the same from both. Exits non-zero
// otherwise. Only the installed headers are reachable (the core's are not installed).
#include <pcl_ncut_seg/segment_points.h>
#include <pcl_ncut_seg/supernode_ncut_segmentation.h>

#include <pcl/point_cloud.h>
#include <pcl/point_types.h>

#include <cmath>
#include <cstdint>
#include <cstdio>
#include <set>
#include <vector>

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

  pcl::SupernodeNCutSegmentation<pcl::PointXYZ> seg;
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
  std::printf("pcl_ncut_seg consumer: 2 segments of %d points, as expected\n", n);
  return 0;
}
