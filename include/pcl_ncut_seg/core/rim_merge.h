/*
 * pcl_ncut_seg: open views (an extension). A single view of an object ends at a rim, where the
 * surface leaves the camera's sight or hides behind itself. The centrality (eq. 1) is largest
 * there, so the rim grows features of its own (Sec. 4.2) that the hierarchy (Sec. 5.2) cuts
 * off. Where such a cut crosses no concave crease, it is the rim's and not the shape's (the
 * minima rule: parts meet at concave creases), and the two segments are one part.
 */
#pragma once

#include <pcl_ncut_seg/core/csr_graph.h>

#include <cstdint>
#include <vector>

namespace pcl_ncut_seg {

/** \brief Per vertex of an organized cloud (a width x height grid of pixels), whether it lies
 * on the view's rim: a 4-neighbour pixel is off the grid, has no vertex, or lies farther along
 * its ray than 2% of the depth from it (a depth discontinuity, as PCL's organized edge
 * detection measures it).
 * \param[in] vertex_pixel  per vertex, its pixel (row * width + column)
 * \param[in] range         per pixel, the distance of its point from the sensor; NaN: no point
 * \param[in] pixel_vertex  per pixel, its vertex or kNone (no finite point, or not analysed)
 * \return per vertex, 1 on the rim, 0 inside */
std::vector<std::uint8_t> organizedRim(const std::vector<std::uint32_t>& vertex_pixel,
                                       const std::vector<float>& range,
                                       const std::vector<std::uint32_t>& pixel_vertex,
                                       std::size_t width, std::size_t height);

/** \brief Each vertex's normal averaged with its neighbours' (1-ring), unit length, so many
 * times. The stages before the rim merge chose boundaries where the 1-ring normals bend
 * concavely (crease splits, the concavity of eq. 9, boundary refinement), so on a noisy flat
 * surface they bend concavely along every boundary; bends between normals averaged over a
 * few more rings follow the surface, not the noise those stages picked.
 * \param[in] normals  3 floats per vertex, oriented (orientedNormals() in core/concavity.h)
 * \param[in] times    how many times (0: the normals as given)
 * \param[in] num_threads  0 = all cores; the result does not depend on it
 * \return 3 floats per vertex */
std::vector<float> ringAveragedNormals(const CsrGraph& graph, const std::vector<float>& normals,
                                       int times, unsigned num_threads = 0);

/** \brief Per directed edge, its concave bend -(n_p - n_q) . (p - q) / |p - q| (negative:
 * convex) over meanAbsBend(), as round(16 c) clamped to +-127. Summed along a boundary, the
 * bends of noise cancel and those of a crease add up.
 * \param[in] normals  3 floats per vertex, oriented
 * \param[in] num_threads  0 = all cores; the result does not depend on it */
std::vector<std::int8_t> signedEdgeBends(const CsrGraph& graph, const float* xyz,
                                         const std::vector<float>& normals,
                                         unsigned num_threads = 0);

/** \brief Merge touching segments of an open surface whose common boundary is neither a
 * concave crease nor a limb's neck, when one of the two reaches the rim. A limb's neck is
 * narrower than sqrt(pi) (core/short_cut.h's neck of a tube as long as it is wide); a piece
 * chipped off at the rim has a wider one. Of the qualifying pairs the least concave (then the
 * smallest ids) merges first, and the boundaries are measured again, until none qualifies.
 * \param[in] graph          kNN graph
 * \param[in] rim            per vertex, 1 on the view's rim
 * \param[in] crease         per directed edge, signedEdgeBends() (16 per mean |bend|)
 * \param[in] max_concavity  a boundary whose mean signed bend (concave positive, in mean
 *                           |bend| per kNN edge) is below this is not a crease
 * \param[in,out] segment    per vertex, its segment; compact ids on output
 * \param[in,out] num_segments
 * \return per old segment, its new one (empty when nothing merged) */
std::vector<std::uint32_t> mergeAcrossRim(const CsrGraph& graph,
                                          const std::vector<std::uint8_t>& rim,
                                          const std::vector<std::int8_t>& crease,
                                          double max_concavity, std::vector<std::uint32_t>& segment,
                                          std::size_t& num_segments);

} // namespace pcl_ncut_seg
