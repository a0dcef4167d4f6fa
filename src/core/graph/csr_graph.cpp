#include "core/graph/csr_graph.h"
#include "core/common/geometry.h"

#include <algorithm>
#include <cmath>

namespace pcl_ncut_seg {

namespace {
/// The kNN lists and the rule that decides which of their entries become edges. Per kNN
/// entry p -> q, put says: bit 0, q goes into p's row; bit 1, p goes into q's row too.
struct KnnEntries {
  const float* xyz;
  std::size_t n;
  const std::uint32_t* knn;
  std::size_t k;
  int num_threads;
  std::vector<float> radius;     ///< per point, the distance to the farthest of its k nearest
  std::vector<std::uint8_t> put; ///< per kNN entry, see above

  /// p -> q is used unless it is over kFarEdgeRatio times q's radius: a lone far point (an
  /// outlier) would otherwise reach into a surface over a distance no surface edge has, and
  /// its centrality and area would dominate the refinement thresholds (Sec. 4.3).
  static constexpr float kFarEdgeRatio = 10.0f;

  void measureRadii();
  void markUsed(std::uint32_t* reverse_count);
  std::uint32_t ownCount(std::size_t p) const {
    std::uint32_t c = 0;
    for (std::size_t j = 0; j < k; ++j)
      c += put[p * k + j] != 0;
    return c;
  }
  void fillRows(CsrGraph& g);

private:
  /// The test on p -> q of length d (the same length both ways, bit for bit).
  bool usedAt(std::uint32_t q, float d) const {
    return radius[q] == 0.0f || d <= kFarEdgeRatio * radius[q];
  }
  // Both scans without an early exit: where the match lies is unpredictable, and a branch per
  // entry cost more than the entries after it.
  bool listsUsed(std::uint32_t q, std::size_t p, float d) const {
    bool lists = false;
    for (std::size_t j = 0; j < k; ++j)
      lists |= knn[q * k + j] == p;
    return lists && usedAt(static_cast<std::uint32_t>(p), d);
  }
  bool isDuplicateInRow(std::size_t p, std::size_t j) const {
    bool duplicate = false;
    for (std::size_t i = 0; i < j; ++i)
      duplicate |= knn[p * k + i] == knn[p * k + j];
    return duplicate;
  }
};

void KnnEntries::measureRadii() {
  const auto rows = static_cast<std::ptrdiff_t>(n);
  radius.assign(n, 0.0f);
#pragma omp parallel for num_threads(num_threads) schedule(static)
  for (std::ptrdiff_t r = 0; r < rows; ++r) {
    const auto p = static_cast<std::size_t>(r);
    for (std::size_t j = 0; j < k; ++j) {
      const std::uint32_t q = knn[p * k + j];
      if (q < n && q != p)
        radius[p] = std::max(radius[p], pointDistance(xyz, p, q));
    }
  }
}

/// Union of both directions. A used p -> q puts q in p's row, and p in q's row unless q -> p
/// is also a used kNN entry (then q's own entry adds it): rows hold no duplicate without a
/// sort-and-unique pass over 2nk entries, so memory stays at the size of the result. The
/// reverse entries are counted per row (atomically).
void KnnEntries::markUsed(std::uint32_t* reverse_count) {
  const auto rows = static_cast<std::ptrdiff_t>(n);
  put.assign(n * k, 0);
#pragma omp parallel for num_threads(num_threads) schedule(static)
  for (std::ptrdiff_t r = 0; r < rows; ++r) {
    const auto p = static_cast<std::size_t>(r);
    for (std::size_t j = 0; j < k; ++j) {
      const std::uint32_t q = knn[p * k + j];
      if (q >= n || q == p)
        continue;
      const float d = pointDistance(xyz, p, q);
      if (!usedAt(q, d) || isDuplicateInRow(p, j))
        continue;
      const bool reverse = !listsUsed(q, p, d);
      put[p * k + j] = reverse ? 3 : 1;
      if (reverse) {
#pragma omp atomic
        ++reverse_count[q];
      }
    }
  }
}

/// A row starts with its own kNN entries (written by the thread that owns it), then holds the
/// reverse ones (placed atomically, in any order).
void KnnEntries::fillRows(CsrGraph& g) {
  const auto rows = static_cast<std::ptrdiff_t>(n);
  g.targets.resize(g.offsets[n]);
  // fill[v]: where v's next reverse entry goes.
  std::vector<std::uint32_t> fill(n);
#pragma omp parallel for num_threads(num_threads) schedule(static)
  for (std::ptrdiff_t r = 0; r < rows; ++r)
    fill[r] = g.offsets[r] + ownCount(static_cast<std::size_t>(r));
#pragma omp parallel for num_threads(num_threads) schedule(static)
  for (std::ptrdiff_t r = 0; r < rows; ++r) {
    const auto p = static_cast<std::size_t>(r);
    std::uint32_t own = g.offsets[p];
    for (std::size_t j = 0; j < k; ++j) {
      if (!put[p * k + j])
        continue;
      const std::uint32_t q = knn[p * k + j];
      g.targets[own++] = q;
      if (put[p * k + j] & 2) {
        std::uint32_t at;
#pragma omp atomic capture
        at = fill[q]++;
        g.targets[at] = static_cast<std::uint32_t>(p);
      }
    }
  }
}

/// Each row sorted by target (so the graph is the same for any number of threads) and its
/// edges' lengths measured. Rows are short (k and a few more): an insertion sort in place,
/// without the library sort's block moves; long rows (a hub) go to std::sort. Targets in a row
/// are distinct.
void sortRowsAndMeasure(CsrGraph& g, const float* xyz, int num_threads) {
  const auto rows = static_cast<std::ptrdiff_t>(g.numVertices());
  g.lengths.resize(g.targets.size());
#pragma omp parallel for num_threads(num_threads) schedule(static)
  for (std::ptrdiff_t r = 0; r < rows; ++r) {
    const auto v = static_cast<std::size_t>(r);
    std::uint32_t* row = g.targets.data() + g.offsets[v];
    const std::uint32_t degree = g.offsets[v + 1] - g.offsets[v];
    if (degree > 32) {
      std::sort(row, row + degree);
    } else {
      for (std::uint32_t i = 1; i < degree; ++i) {
        const std::uint32_t t = row[i];
        std::uint32_t j = i;
        for (; j > 0 && row[j - 1] > t; --j)
          row[j] = row[j - 1];
        row[j] = t;
      }
    }
    for (std::uint32_t e = g.offsets[v]; e < g.offsets[v + 1]; ++e)
      g.lengths[e] = pointDistance(xyz, v, g.targets[e]);
  }
}
} // namespace

CsrGraph buildSymmetricKnnGraph(const float* xyz, std::size_t n, const std::uint32_t* knn,
                                std::size_t k, int num_threads) {
  KnnEntries entries{xyz, n, knn, k, num_threads, {}, {}};
  entries.measureRadii();
  CsrGraph g;
  g.offsets.assign(n + 1, 0);
  entries.markUsed(g.offsets.data() + 1); // reverse entries counted into offsets[v + 1]
  for (std::size_t v = 0; v < n; ++v)
    g.offsets[v + 1] += g.offsets[v] + entries.ownCount(v);
  entries.fillRows(g);
  entries.put = std::vector<std::uint8_t>(); // the marks are no longer needed
  sortRowsAndMeasure(g, xyz, num_threads);
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

void measureLengths(CsrGraph& graph, const float* xyz) {
  for (std::size_t v = 0; v < graph.numVertices(); ++v)
    for (std::uint32_t e = graph.offsets[v]; e < graph.offsets[v + 1]; ++e)
      graph.lengths[e] = pointDistance(xyz, v, graph.targets[e]);
}

} // namespace pcl_ncut_seg
