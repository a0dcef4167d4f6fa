/*
 * pcl_ncut_seg: scoring a segmentation of a depth view (depth_view.h) on the mesh's faces that
 * the view sees. Plain C++ (no PCL).
 */
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

namespace pcl_ncut_seg {

/** \brief The faces that at least one pixel hit, in increasing order (pixel_face: the face of
 * each pixel, -1 for none). */
std::vector<std::size_t> seenFaces(const std::vector<std::int64_t>& pixel_face);

/** \brief The label of each seen face from the labels of the pixels that hit it: the label most
 * of its pixels carry (of equal counts, the smallest label). Pixels in no segment (label < 0)
 * vote only when no pixel of the face has a label; then the face is in no segment (-1).
 * \param[in] pixel_face the face of each pixel (-1 for none)
 * \param[in] pixel_label the label of each pixel (any value where pixel_face is -1)
 * \param[in] seen seenFaces(pixel_face)
 * \return one label per seen face, in the order of seen. */
std::vector<int> faceLabelsFromPixels(const std::vector<std::int64_t>& pixel_face,
                                      const std::vector<int>& pixel_label,
                                      const std::vector<std::size_t>& seen);

/** \brief The values of the seen faces, in the order of seen. */
template <typename T>
std::vector<T> restrictToFaces(const std::vector<T>& per_face,
                               const std::vector<std::size_t>& seen) {
  std::vector<T> out;
  out.reserve(seen.size());
  for (const std::size_t f : seen)
    out.push_back(per_face[f]);
  return out;
}

} // namespace pcl_ncut_seg
