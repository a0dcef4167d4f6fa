// Morton (Z-order) codes: a cache-friendly order for kNN queries and graph searches.
#include "core/common/morton.h"
#include "core/common/radix_sort.h"

#include <algorithm>
#include <cmath>

namespace pcl_ncut_seg {
namespace {
/// Spread the low 10 bits of v to every third bit.
std::uint32_t spread(std::uint32_t v) {
  v &= 0x3ffu;
  v = (v | (v << 16)) & 0x030000ffu;
  v = (v | (v << 8)) & 0x0300f00fu;
  v = (v | (v << 4)) & 0x030c30c3u;
  v = (v | (v << 2)) & 0x09249249u;
  return v;
}
} // namespace

MortonBox mortonBox(const float* xyz, std::size_t n) {
  float lo[3] = {0, 0, 0}, hi[3] = {0, 0, 0};
  for (std::size_t i = 0; i < n; ++i)
    for (int c = 0; c < 3; ++c) {
      const float v = xyz[3 * i + c];
      lo[c] = i == 0 ? v : std::min(lo[c], v);
      hi[c] = i == 0 ? v : std::max(hi[c], v);
    }
  // One cube over the box, so that cells are cubes.
  MortonBox box;
  for (int c = 0; c < 3; ++c)
    box.lo[c] = lo[c];
  box.extent = std::max({hi[0] - lo[0], hi[1] - lo[1], hi[2] - lo[2]});
  return box;
}

std::vector<std::uint32_t> mortonCodes(const float* xyz, std::size_t n, const MortonBox* given) {
  const MortonBox box = given ? *given : mortonBox(xyz, n);
  const float* lo = box.lo;
  const float extent = box.extent;
  const double scale = extent > 0.0f ? 1023.999 / extent : 0.0;
  std::vector<std::uint32_t> code(n);
  for (std::size_t i = 0; i < n; ++i) {
    std::uint32_t cell[3];
    for (int c = 0; c < 3; ++c) {
      const double x = (static_cast<double>(xyz[3 * i + c]) - lo[c]) * scale;
      cell[c] = static_cast<std::uint32_t>(std::clamp(x, 0.0, 1023.0));
    }
    code[i] = (spread(cell[0]) << 2) | (spread(cell[1]) << 1) | spread(cell[2]);
  }
  return code;
}

std::vector<std::uint32_t> mortonOrder(const float* xyz, std::size_t n) {
  return stableOrderByKey(mortonCodes(xyz, n)); // ties in index order
}

DistinctMortonOrder distinctMortonOrder(const float* xyz, std::size_t n, const MortonBox* box) {
  const std::vector<std::uint32_t> code = mortonCodes(xyz, n, box);
  std::vector<std::uint32_t> order = stableOrderByKey(code);
  // Within a cell, the points by (x, y, z, index): the vertices' order then depends on the
  // positions alone, not on the input's order, and equal positions are adjacent.
  std::vector<std::uint32_t> first(n); // per point: the first point at its position
  std::vector<std::uint32_t> cell;
  auto less = [xyz](std::uint32_t a, std::uint32_t b) {
    const float* p = xyz + 3 * std::size_t(a);
    const float* q = xyz + 3 * std::size_t(b);
    if (p[0] != q[0])
      return p[0] < q[0];
    if (p[1] != q[1])
      return p[1] < q[1];
    if (p[2] != q[2])
      return p[2] < q[2];
    return a < b;
  };
  auto same = [xyz](std::uint32_t a, std::uint32_t b) {
    const float* p = xyz + 3 * std::size_t(a);
    const float* q = xyz + 3 * std::size_t(b);
    return p[0] == q[0] && p[1] == q[1] && p[2] == q[2];
  };
  bool any_copy = false;
  for (std::size_t i = 0; i < n;) {
    std::size_t j = i + 1;
    while (j < n && code[order[j]] == code[order[i]])
      ++j;
    first[order[i]] = order[i];
    if (j - i > 1) {
      cell.assign(order.begin() + i, order.begin() + j);
      std::sort(cell.begin(), cell.end(), less);
      std::copy(cell.begin(), cell.end(), order.begin() + std::ptrdiff_t(i));
      for (std::size_t c = 0; c < cell.size(); ++c) {
        const bool copy = c > 0 && same(cell[c], cell[c - 1]);
        first[cell[c]] = copy ? first[cell[c - 1]] : cell[c];
        any_copy = any_copy || copy;
      }
    }
    i = j;
  }
  DistinctMortonOrder out;
  if (!any_copy) {
    out.point = std::move(order);
    out.rank = out.point;
    return out;
  }
  std::vector<std::uint32_t> rank_of(n); // per point: rank among the distinct points
  for (std::uint32_t i = 0, r = 0; i < n; ++i)
    rank_of[i] = first[i] == i ? r++ : 0;
  std::vector<std::uint32_t> vertex_of(n);
  for (std::uint32_t i : order)
    if (first[i] == i) {
      vertex_of[i] = static_cast<std::uint32_t>(out.point.size());
      out.point.push_back(i);
      out.rank.push_back(rank_of[i]);
    }
  for (std::uint32_t i = 0; i < n; ++i)
    if (first[i] != i)
      out.copies.emplace_back(i, vertex_of[first[i]]);
  return out;
}

} // namespace pcl_ncut_seg
