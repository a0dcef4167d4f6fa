#include "support/knn_graph.h"

#include <pcl/search/kdtree.h>

#include <cstdint>
#include <limits>

namespace pcl_ncut_seg {
namespace test {

std::vector<float> xyzOf(const pcl::PointCloud<pcl::PointXYZ>& cloud) {
  std::vector<float> xyz;
  xyz.reserve(3 * cloud.size());
  for (const auto& p : cloud)
    xyz.insert(xyz.end(), {p.x, p.y, p.z});
  return xyz;
}

CsrGraph kdTreeKnnGraph(const std::vector<float>& xyz, std::size_t k) {
  const std::size_t n = xyz.size() / 3;
  pcl::PointCloud<pcl::PointXYZ>::Ptr cloud(new pcl::PointCloud<pcl::PointXYZ>);
  cloud->resize(n);
  for (std::size_t i = 0; i < n; ++i)
    (*cloud)[i] = pcl::PointXYZ(xyz[3 * i], xyz[3 * i + 1], xyz[3 * i + 2]);
  pcl::search::KdTree<pcl::PointXYZ> tree;
  tree.setInputCloud(cloud);
  std::vector<std::uint32_t> knn(n * k, std::numeric_limits<std::uint32_t>::max());
  pcl::Indices nn;
  std::vector<float> sqr;
  for (std::size_t i = 0; i < n; ++i) {
    tree.nearestKSearch((*cloud)[i], static_cast<int>(k + 1), nn, sqr);
    std::size_t j = 0;
    for (const auto q : nn)
      if (j < k && static_cast<std::size_t>(q) != i)
        knn[i * k + j++] = static_cast<std::uint32_t>(q);
  }
  return buildSymmetricKnnGraph(xyz.data(), n, knn.data(), k);
}

} // namespace test
} // namespace pcl_ncut_seg
