// Points prepared for analyze() (see core/model/points.h).
#include "core/model/points.h"

#include <algorithm>

namespace pcl_ncut_seg {

void centrePoints(PreparedPoints& prepared) {
  // Coordinates relative to the centroid, in double first, so that a model far from the
  // origin keeps its float precision.
  const std::size_t m = prepared.raw.size() / 3;
  double c[3] = {0, 0, 0};
  for (std::size_t i = 0; i < m; ++i)
    for (int d = 0; d < 3; ++d)
      c[d] += prepared.raw[3 * i + d];
  for (double& v : c)
    v /= static_cast<double>(std::max<std::size_t>(m, 1));
  prepared.set.xyz.resize(3 * m);
  prepared.set.xyz.shrink_to_fit();
  for (std::size_t i = 0; i < 3 * m; ++i)
    prepared.set.xyz[i] = static_cast<float>(prepared.raw[i] - c[i % 3]);
  for (int d = 0; d < 3; ++d)
    prepared.centroid[d] = c[d];
}

PreparedPoints preparePoints(std::vector<float> xyz, const MortonBox* box) {
  PreparedPoints out;
  DistinctMortonOrder order = distinctMortonOrder(xyz.data(), xyz.size() / 3, box);
  const std::size_t m = order.point.size();
  out.raw.resize(3 * m);
  for (std::size_t v = 0; v < m; ++v)
    for (std::size_t d = 0; d < 3; ++d) // (no library call per point)
      out.raw[3 * v + d] = xyz[3 * std::size_t(order.point[v]) + d];
  std::vector<float>().swap(xyz); // before the centred copy: one copy of the points less
  centrePoints(out);
  out.point = std::move(order.point);
  out.copies = std::move(order.copies);
  out.set.order = std::move(order.rank);
  return out;
}

} // namespace pcl_ncut_seg
