/*
 * pcl_ncut_seg files: PLY files (ascii, binary little- and big-endian), read without PCL's
 * reader: every element and list count is checked against what the file can hold before it
 * is allocated. PCL 1.13's PLYReader aborts on a list property among a vertex's properties and
 * allocates whatever an element count says (docs/inputs.md).
 */
#pragma once

#include "files/file_bytes.h"

#include <pcl/PCLPointCloud2.h>

#include <cstdint>
#include <string>
#include <vector>

namespace pcl_ncut_seg {
namespace files {

/** \brief What a PLY file holds: its vertices with every scalar property as a field (in the
 * file's type), and its faces (the "vertex_indices" or "vertex_index" list of the "face"
 * element), vertex indices as the file gives them. */
struct PlyContents {
  pcl::PCLPointCloud2 vertices;
  bool has_faces = false;                  ///< a face element with a vertex list
  std::vector<std::uint64_t> face_offsets; ///< face f: face_indices[offsets[f], offsets[f + 1])
  std::vector<std::int64_t> face_indices;
};

/** \brief Read a PLY file.
 * \param[in] file the open file
 * \param[out] ply its vertices and faces
 * \param[out] error on failure, one line saying what is wrong (the header line, the element,
 *             the record)
 * \return false on any file the PLY format does not allow */
bool readPly(const FileBytes& file, PlyContents& ply, std::string& error);

} // namespace files
} // namespace pcl_ncut_seg
