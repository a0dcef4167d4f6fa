/*
 * pcl_ncut_seg: a stable order of indices by a 32-bit key, in linear time, and by descending
 * float value (the processing order of Sec. 4.2).
 */
#pragma once

#include <cstdint>
#include <cstring>
#include <vector>

namespace pcl_ncut_seg {

/// \brief The indices 0..n-1 ordered by ascending \a key, ties by ascending index (a stable
/// LSD radix sort, 11 bits a pass).
/// \param[in] key one key per index (n = key.size())
std::vector<std::uint32_t> stableOrderByKey(const std::vector<std::uint32_t>& key);

/// \brief A key that orders finite floats by descending value as unsigned integers (-0 counts
/// as 0): the float's bits made ascending as numbers, then complemented.
inline std::uint32_t descendingKey(float value) {
  const float v = value == 0.0f ? 0.0f : value;
  std::uint32_t bits;
  std::memcpy(&bits, &v, sizeof bits);
  bits = (bits & 0x80000000u) ? ~bits : (bits | 0x80000000u); // ascending as numbers
  return ~bits;                                               // descending
}

/// \brief The indices 0..n-1 by descending value, ties by ascending index (the order in which
/// extractSupernodes() processes the points): stableOrderByKey() of descendingKey(), linear in n.
/// \param[in] value one finite value per index (n = value.size())
std::vector<std::uint32_t> descendingOrder(const std::vector<float>& value);

} // namespace pcl_ncut_seg
