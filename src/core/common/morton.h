/*
 * pcl_ncut_seg: Morton (Z-order) codes, to visit points in a spatially coherent order.
 */
#pragma once

#include <cstddef>
#include <cstdint>
#include <utility>
#include <vector>

namespace pcl_ncut_seg {

/** \brief The cube a Morton grid spans: the points' lower bounding corner and the box's longest
 * side. */
struct MortonBox {
  float lo[3] = {0, 0, 0};
  float extent = 0;
};

/** \brief The MortonBox of n points (all zero for none). */
MortonBox mortonBox(const float* xyz, std::size_t n);

/** \brief The 30-bit Morton code of each point: its cell in a 1024^3 grid over the bounding
 * box (or over `box`, so that a subset keeps the order it has among all the points), bits of x,
 * y and z interleaved. Points in the same cell of any coarser power-of-two grid share a prefix of
 * the code. */
std::vector<std::uint32_t> mortonCodes(const float* xyz, std::size_t n,
                                       const MortonBox* box = nullptr);

/** \brief The points in ascending Morton code, ties by index: order[i] is the point at
 * position i. */
std::vector<std::uint32_t> mortonOrder(const float* xyz, std::size_t n);

/** \brief The distinct positions among n points, in Morton order. */
struct DistinctMortonOrder {
  /// Per vertex (distinct position, in ascending Morton code, ties by (x, y, z)): the index of
  /// the first point at its position.
  std::vector<std::uint32_t> point;
  /// Per vertex: its rank among the vertices in index order.
  std::vector<std::uint32_t> rank;
  /// (index of a point at an earlier point's position, vertex of that position).
  std::vector<std::pair<std::uint32_t, std::uint32_t>> copies;
};

/** \brief Points at exactly the same coordinates merged into one vertex (the first point at
 * the position), the vertices in Morton order, ties by position: the same vertices in the same
 * order for any order of the points. Equal positions have equal codes, so copies are
 * found among points of one grid cell: a radix sort on the code, then a sort within cells.
 * box: as mortonCodes(). */
DistinctMortonOrder distinctMortonOrder(const float* xyz, std::size_t n,
                                        const MortonBox* box = nullptr);

} // namespace pcl_ncut_seg
