/*
 * pcl_ncut_seg: a stable order of indices by a 32-bit key, in linear time.
 */
#pragma once

#include <cstdint>
#include <vector>

namespace pcl_ncut_seg {

/// \brief The indices 0..n-1 ordered by ascending \a key, ties by ascending index (a stable
/// LSD radix sort, 11 bits a pass).
/// \param[in] key one key per index (n = key.size())
std::vector<std::uint32_t> stableOrderByKey(const std::vector<std::uint32_t>& key);

} // namespace pcl_ncut_seg
