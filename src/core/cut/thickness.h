/*
 * pcl_ncut_seg: the surface's local thickness, from the points and their oriented normals
 * (an extension of Sec. 5.1). A part that people see but the centrality does not (a fin, a
 * wing, an ear) is thinner or thicker than the body it grows from; the medial ball inside the
 * surface at each point says how thick it is there, with no mesh.
 *
 * Inputs: points (xyz), outward unit normals (orientedNormals(), core/cut/concavity.h), the
 * refined supernodes' labels. Outputs: per point its medial radius; per supernode its
 * thickness (the median of its points').
 */
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

namespace pcl_ncut_seg {

/** \brief Per point, the radius of the largest ball inside the surface that touches it there
 * (the shrinking-ball method of Ma et al., "3D medial axis point approximation using nearest
 * neighbors and the normal field", 2012): the ball tangent at p on its inward side shrinks to
 * the nearest point inside it until none is. A ball that the noise in p's own neighbourhood
 * would shrink (the point it meets is seen from its centre at less than a small angle from p)
 * keeps its last radius. Measured at the points of an even subset of at most 8192 points
 * (evenSubset(), core/graph/subsample.h), the probes, against the probes: enough for a median
 * per supernode, at a cost that does not grow with the cloud. NaN at every other point, where
 * the normal is zero, or where the ball grows past the cloud (an open side). The result
 * depends neither on the number of threads nor on the points' order.
 * \param[in] xyz      n points, 3 floats each
 * \param[in] normals  3 floats per point, outward, unit or zero
 * \param[in] num_threads  threads for the queries (0: all cores) */
std::vector<float> medialRadii(const float* xyz, std::size_t n, const std::vector<float>& normals,
                               unsigned num_threads);

/** \brief Per supernode, the median medial radius of its points (NaN when none has one).
 * \param[in] radii  medialRadii()
 * \param[in] label  per point, its supernode (< num_supernodes) */
std::vector<float> supernodeThickness(const std::vector<float>& radii,
                                      const std::vector<std::uint32_t>& label,
                                      std::size_t num_supernodes);

} // namespace pcl_ncut_seg
