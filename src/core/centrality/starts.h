/*
 * pcl_ncut_seg: several starts of the farthest-point sampling of eq. (1), and the segmentation
 * that agrees best with the others (an extension of Sec. 4.1, step 4). Step 4 starts the
 * sampling at an arbitrary point. Each start gives other samples, hence another f, other
 * supernodes and at times other segments; which start is lucky depends on how the surface was
 * sampled. The segmentation closest to all the others (the medoid under the Rand distance) is
 * the one that least depends on that choice.
 */
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

namespace pcl_ncut_seg {

/** \brief Per vertex, its rank by distance from the origin (put the points' centroid there),
 * ties by index. Ties in the centrality go by it, and the farthest-point sampling begins at
 * the point farthest from the rank-0 vertex (Sec. 4.1, step 4: "an arbitrary point"). Both
 * then depend on the surface and its centroid, not on the order in which its points came (the
 * vertices' own order, core/common/morton.h, does not either), and a rotation changes them only
 * through rounding.
 *
 * With component given, by distance from the centroid of the vertex's own connected component
 * (a component with one vertex: 0): the sampling runs per component (Sec. 4.1), so each
 * begins from its own centre, and a far outlier, a component of its own, moves no other
 * component's start. Components of more than one vertex are centred in double, in vertex
 * order; a cloud of one component keeps the origin (the points' centroid, where the pipeline
 * put it).
 * \param[in] xyz  3 floats per vertex
 * \param[in] n    vertices
 * \param[in] component  per vertex its component (connectedComponents()); empty: one
 * \return per vertex its rank, 0 .. n - 1 */
std::vector<std::uint32_t> centralRanks(const float* xyz, std::size_t n,
                                        const std::vector<std::uint32_t>& component = {});

/** \brief The number of pairs of points that one partition puts together and the other apart
 * (the Rand distance times n(n-1)/2).
 * \param[in] a, b  per point, its segment; equal sizes */
std::uint64_t pairDisagreements(const std::vector<std::uint32_t>& a,
                                const std::vector<std::uint32_t>& b);

/** \brief The medoid of partitions of the same points: the one whose summed pairDisagreements()
 * with all the others, each counted weight times, is the smallest; ties to the smallest index.
 * \param[in] partitions  at least one, each per point its segment, all of one size
 * \param[in] weights     per partition, how many times it counts (a partition that stands for
 *                        several equal ones); empty: once each
 * \return its index in partitions */
std::size_t medoidPartition(const std::vector<const std::vector<std::uint32_t>*>& partitions,
                            const std::vector<std::uint32_t>& weights = {});

} // namespace pcl_ncut_seg
