/*
 * pcl_ncut_seg: Morton (Z-order) codes, to visit points in a spatially coherent order.
 */
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

namespace pcl_ncut_seg {

/** \brief The 30-bit Morton code of each point: its cell in a 1024^3 grid over the bounding
 * box, bits of x, y and z interleaved. Points in the same cell of any coarser power-of-two grid
 * share a prefix of the code. */
std::vector<std::uint32_t> mortonCodes(const float* xyz, std::size_t n);

/** \brief The points in ascending Morton code, ties by index: order[i] is the point at
 * position i. */
std::vector<std::uint32_t> mortonOrder(const float* xyz, std::size_t n);

} // namespace pcl_ncut_seg
