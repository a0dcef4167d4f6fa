/*
 * pcl_ncut_seg: reading OFF meshes and Princeton benchmark .seg files, and sampling points on
 * a mesh's surface. Plain C++ (no PCL) so that the tools, the evaluator, the benchmarks and the
 * tests share one definition.
 */
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

namespace pcl_ncut_seg {

/** \brief A triangle mesh; polygons of the file are fan-triangulated, and each triangle
 * remembers the polygon (the "original face") it came from. */
struct TriangleMesh {
  std::vector<float> vertices;              ///< x, y, z per vertex
  std::vector<std::uint32_t> faces;         ///< three vertex indices per triangle
  std::vector<std::uint32_t> original_face; ///< per triangle, its face in the file
  std::size_t num_original_faces = 0;       ///< faces in the file (benchmark labels are per face)

  std::size_t numVertices() const { return vertices.size() / 3; }
  std::size_t numTriangles() const { return faces.size() / 3; }
};

/** \brief Read an OFF file: "OFF" with the counts on the same or the next line, '#' comments,
 * blank lines, CRLF line ends, per-face colours (ignored) and polygons of any size.
 * \return false with a one-line reason in *error (if given) on any malformed input. */
bool readOff(const std::string& path, TriangleMesh& mesh, std::string* error = nullptr);

/** \brief Read a Wavefront OBJ file's geometry: "v x y z [w]" and "f a b c ..." with
 * "a/t/n" references and negative (relative) indices; other statements (normals, texture
 * coordinates, groups, materials, lines) are ignored.
 * \return false with a one-line reason in *error (if given) on any malformed input. */
bool readObj(const std::string& path, TriangleMesh& mesh, std::string* error = nullptr);

/** \brief Area of each original face (the sum of its triangles). */
std::vector<double> faceAreas(const TriangleMesh& mesh);

/** \brief One point per original face, x, y, z each: its area-weighted centroid (the mean of
 * its vertices if its area is zero). */
std::vector<float> faceCentroids(const TriangleMesh& mesh);

/** \brief n points drawn uniformly by area on the surface, x, y, z each. Deterministic for a
 * given seed on every platform (std::mt19937_64 with our own mapping to [0, 1)).
 * \param[out] face_of_sample if given, the original face of each sample.
 * \return no points if the mesh has no area. */
std::vector<float> sampleSurface(const TriangleMesh& mesh, std::size_t n, std::uint64_t seed,
                                 std::vector<std::uint32_t>* face_of_sample = nullptr);

/** \brief Read a Princeton Segmentation Benchmark .seg file: one integer label per line, in
 * the face order of the OFF file. \return false if unreadable or a line is not an integer. */
bool readSeg(const std::string& path, std::vector<int>& labels);

} // namespace pcl_ncut_seg
