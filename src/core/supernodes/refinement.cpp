// Sec. 4.3: feature height (2), area and radius (3) and width (4). The local refinement that
// merges insignificant supernodes is in local_refinement.cpp.
#include "core/supernodes/refinement.h"
#include "core/common/threads.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace pcl_ncut_seg {

std::vector<float> pointRadii(const CsrGraph& graph, const std::vector<float>& f,
                              unsigned num_threads) {
  const std::size_t n = graph.numVertices();
  std::vector<float> r(n, 0.0f);
  // Each point's mean is its own: the same for any number of threads.
#pragma omp parallel for schedule(static, 4096) num_threads(usableThreads(num_threads))
  for (std::int64_t pi = 0; pi < static_cast<std::int64_t>(n); ++pi) {
    const auto p = static_cast<std::uint32_t>(pi);
    const std::uint32_t b = graph.offsets[p], e = graph.offsets[p + 1];
    if (b == e)
      continue;
    double sum = 0.0;
    for (std::uint32_t i = b; i < e; ++i)
      sum += featureDistance(f[p] - f[graph.targets[i]], graph.lengths[i]);
    r[p] = static_cast<float>(sum / (e - b));
  }
  return r;
}

namespace {
float widthOf(double area, double height, double max_height) {
  const double floor = 1e-6 * max_height > 0 ? 1e-6 * max_height : 1e-30;
  return static_cast<float>(area / std::max(height, floor));
}
} // namespace

FeatureStats featureStats(const Supernodes& sn, const std::vector<float>& f,
                          const std::vector<float>& radii) {
  const std::size_t m = sn.size();
  std::vector<double> area(m, 0.0);
  std::vector<float> fmin(m, std::numeric_limits<float>::infinity()),
      fmax(m, -std::numeric_limits<float>::infinity());
  for (std::size_t p = 0; p < sn.label.size(); ++p) {
    const std::uint32_t s = sn.label[p];
    area[s] += pointArea(radii[p]);
    fmin[s] = std::min(fmin[s], f[p]);
    fmax[s] = std::max(fmax[s], f[p]);
  }
  FeatureStats st;
  st.height.resize(m);
  st.area.resize(m);
  st.width.resize(m);
  float max_height = 0.0f;
  for (std::size_t s = 0; s < m; ++s) {
    st.height[s] = fmax[s] >= fmin[s] ? fmax[s] - fmin[s] : 0.0f;
    max_height = std::max(max_height, st.height[s]);
  }
  for (std::size_t s = 0; s < m; ++s) {
    st.area[s] = static_cast<float>(area[s]);
    st.width[s] = widthOf(area[s], st.height[s], max_height);
  }
  return st;
}

} // namespace pcl_ncut_seg
