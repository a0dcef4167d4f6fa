// Morton (Z-order) codes: a cache-friendly order for kNN queries and graph searches.
#include <pcl_ncut_seg/core/morton.h>

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

std::vector<std::uint32_t> mortonCodes(const float* xyz, std::size_t n) {
  float lo[3] = {0, 0, 0}, hi[3] = {0, 0, 0};
  for (std::size_t i = 0; i < n; ++i)
    for (int c = 0; c < 3; ++c) {
      const float v = xyz[3 * i + c];
      lo[c] = i == 0 ? v : std::min(lo[c], v);
      hi[c] = i == 0 ? v : std::max(hi[c], v);
    }
  // One cube over the box, so that cells are cubes.
  const float extent = std::max({hi[0] - lo[0], hi[1] - lo[1], hi[2] - lo[2]});
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
  const std::vector<std::uint32_t> code = mortonCodes(xyz, n);
  std::vector<std::uint64_t> key(n);
  for (std::size_t i = 0; i < n; ++i)
    key[i] = (static_cast<std::uint64_t>(code[i]) << 32) | i;
  std::sort(key.begin(), key.end());
  std::vector<std::uint32_t> order(n);
  for (std::size_t i = 0; i < n; ++i)
    order[i] = static_cast<std::uint32_t>(key[i]);
  return order;
}

} // namespace pcl_ncut_seg
