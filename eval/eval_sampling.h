/*
 * pcl_ncut_seg_eval's sampling conditions: instead of one point per face centroid, N points
 * drawn on the surface (uniformly by area, or with a density gradient), optionally with
 * Gaussian noise and in a random order; and each face's label taken from its nearest sample.
 * Plain C++ (no PCL); every draw is deterministic for a model id, a draw and a stream.
 */
#pragma once

#include <surfaces/mesh_sampling.h>

#include <cstddef>
#include <cstdint>
#include <vector>

namespace pcl_ncut_seg {
namespace eval {

/** \brief How each model's points are made (-samples, -draws, -density_ratio, -noise,
 * -permute, -jitter). samples == 0: the face centroids, as without a condition. */
struct SamplingOptions {
  std::size_t samples = 0;  ///< N points per draw; 0: one point per face centroid
  int draws = 1;            ///< draws per model, each seeded by (model id, draw)
  double density_ratio = 1; ///< R: density R at the low end of the longest axis, 1 at the high
  double noise = 0;         ///< Gaussian sigma per coordinate, in mean spacings sqrt(area / N)
  bool permute = false;     ///< one sample set in `draws` orders: draw 0 as drawn, others shuffled
  /// One sample set in `draws` copies: draw 0 as drawn, each other moved by Gaussian noise of
  /// sigma `jitter` mean spacings per coordinate (the segmenter's sensitivity to tiny changes)
  double jitter = 0;

  bool active() const { return samples > 0; }
};

/** \brief One draw's points, and how they map back to the samples and the faces. */
struct SampledCloud {
  std::vector<float> xyz;             ///< the points the segmenters get, x y z each, in order
  std::vector<std::uint32_t> order;   ///< point i is sample order[i]; empty: the drawn order
  std::vector<std::uint32_t> nearest; ///< per face, its nearest sample; empty: points = faces
  double spacing = 0;                 ///< sqrt(area / N) (0 for face centroids)
};

/** \brief A seed from a model id, a draw and a stream (sampling, noise, order), mixed with
 * SplitMix64 so that neighbouring ids give unrelated sequences. */
std::uint64_t drawSeed(int model_id, int draw, int stream);

/** \brief The mean spacing of n points on a surface of this area: sqrt(area / n). */
double meanSpacing(double area, std::size_t n);

/** \brief The axis (0 x, 1 y, 2 z) along which the vertices' bounding box is longest. */
int longestAxis(const std::vector<float>& vertices);

/** \brief The density of the gradient at t in [0, 1] along the axis, relative to the high end:
 * R - (R - 1) t (R at t = 0, 1 at t = 1). */
double gradientDensity(double ratio, double t);

/** \brief n points on the surface whose density per unit area falls linearly from R (the low
 * end of the bounding box's longest axis) to 1 (its high end): area-uniform candidates kept
 * with probability gradientDensity(R, t) / R. R = 1: sampleSurface(mesh, n, seed) itself.
 * \return no points if the mesh has no area. */
std::vector<float> sampleWithGradient(const TriangleMesh& mesh, std::size_t n, double ratio,
                                      std::uint64_t seed);

/** \brief Add independent Gaussian noise of this sigma to every coordinate (Box-Muller on our
 * own uniform mapping: the same on every platform). */
void addNoise(std::vector<float>& xyz, double sigma, std::uint64_t seed);

/** \brief A uniformly random permutation of 0..n-1 (Fisher-Yates). */
std::vector<std::uint32_t> randomOrder(std::size_t n, std::uint64_t seed);

/** \brief The points in this order: point i of the result is point order[i]. */
std::vector<float> reordered(const std::vector<float>& xyz,
                             const std::vector<std::uint32_t>& order);

/** \brief Labels of reordered points mapped back to the original order (labels[i] belongs to
 * point order[i]); an empty order leaves them as they are. */
std::vector<int> mappedBack(const std::vector<int>& labels,
                            const std::vector<std::uint32_t>& order);

/** \brief For each query, the index of its nearest point (exact, Euclidean; the lowest index
 * on a tie), with a uniform grid. \throws std::invalid_argument if there are no points. */
std::vector<std::uint32_t> nearestPoints(const std::vector<float>& points,
                                         const std::vector<float>& queries);

/** \brief Per original face, its unit normal (x y z each): the sum of its triangles' area
 * vectors, every one flipped when the mesh's signed volume is negative, so that a closed mesh
 * wound either way gets outward normals. A face with no area gets (0, 0, 1). */
std::vector<float> outwardFaceNormals(const TriangleMesh& mesh);

/** \brief Per point, the normal of the face whose centroid is nearest (x y z each). */
std::vector<float> nearestFaceNormals(const std::vector<float>& xyz,
                                      const std::vector<float>& centroids,
                                      const std::vector<float>& face_normals);

/** \brief Each face's label: the label of its nearest point (nearest empty: the labels). */
std::vector<int> faceLabels(const std::vector<int>& point_labels,
                            const std::vector<std::uint32_t>& nearest);

/** \brief One draw of a model's points under the options: the samples (with the gradient),
 * each face's nearest clean sample, then the noise and the order. With -permute every draw
 * has draw 0's samples and noise; draws >= 1 are in a seeded random order.
 * \throws std::runtime_error if the mesh has no area. */
SampledCloud makeCloud(const TriangleMesh& mesh, const std::vector<float>& centroids,
                       const SamplingOptions& options, int model_id, int draw);

} // namespace eval
} // namespace pcl_ncut_seg
