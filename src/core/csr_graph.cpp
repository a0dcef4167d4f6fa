#include <pcl_ncut_seg/core/csr_graph.h>

#include <algorithm>
#include <cmath>

namespace pcl_ncut_seg {

CsrGraph buildSymmetricKnnGraph(const float* xyz, std::size_t n, const std::uint32_t* knn,
                                std::size_t k) {
  // Union of both directions: count each p -> q and q -> p, then sort and deduplicate rows.
  CsrGraph g;
  g.offsets.assign(n + 1, 0);
  for (std::size_t p = 0; p < n; ++p)
    for (std::size_t j = 0; j < k; ++j) {
      const std::uint32_t q = knn[p * k + j];
      if (q >= n || q == p)
        continue;
      ++g.offsets[p + 1];
      ++g.offsets[q + 1];
    }
  for (std::size_t v = 0; v < n; ++v)
    g.offsets[v + 1] += g.offsets[v];
  std::vector<std::uint32_t> fill(g.offsets.begin(), g.offsets.end() - 1);
  std::vector<std::uint32_t> targets(g.offsets[n]);
  for (std::size_t p = 0; p < n; ++p)
    for (std::size_t j = 0; j < k; ++j) {
      const std::uint32_t q = knn[p * k + j];
      if (q >= n || q == p)
        continue;
      targets[fill[p]++] = q;
      targets[fill[q]++] = static_cast<std::uint32_t>(p);
    }
  // Compact: sorted unique neighbours per row.
  std::vector<std::uint32_t> offsets(n + 1, 0);
  std::size_t out = 0;
  for (std::size_t v = 0; v < n; ++v) {
    auto b = targets.begin() + g.offsets[v], e = targets.begin() + g.offsets[v + 1];
    std::sort(b, e);
    e = std::unique(b, e);
    for (auto it = b; it != e; ++it)
      targets[out++] = *it;
    offsets[v + 1] = static_cast<std::uint32_t>(out);
  }
  targets.resize(out);
  g.offsets = std::move(offsets);
  g.targets = std::move(targets);
  g.lengths.resize(out);
  for (std::size_t v = 0; v < n; ++v)
    for (std::uint32_t e = g.offsets[v]; e < g.offsets[v + 1]; ++e) {
      const float* a = xyz + 3 * v;
      const float* b = xyz + 3 * g.targets[e];
      const float dx = a[0] - b[0], dy = a[1] - b[1], dz = a[2] - b[2];
      g.lengths[e] = std::sqrt(dx * dx + dy * dy + dz * dz);
    }
  return g;
}

std::size_t connectedComponents(const CsrGraph& graph, std::vector<std::uint32_t>& component) {
  const std::size_t n = graph.numVertices();
  component.assign(n, ~std::uint32_t(0));
  std::vector<std::uint32_t> stack;
  std::uint32_t count = 0;
  for (std::size_t s = 0; s < n; ++s) {
    if (component[s] != ~std::uint32_t(0))
      continue;
    component[s] = count;
    stack.push_back(static_cast<std::uint32_t>(s));
    while (!stack.empty()) {
      const std::uint32_t v = stack.back();
      stack.pop_back();
      for (std::uint32_t e = graph.offsets[v]; e < graph.offsets[v + 1]; ++e) {
        const std::uint32_t w = graph.targets[e];
        if (component[w] == ~std::uint32_t(0)) {
          component[w] = count;
          stack.push_back(w);
        }
      }
    }
    ++count;
  }
  return count;
}

} // namespace pcl_ncut_seg
