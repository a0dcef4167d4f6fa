/*
 * pcl_ncut_seg: what a depth camera sees of a mesh. Plain C++ (no PCL): the evaluator, the
 * sampler tool and a benchmark share it, and depth_view_pcl.h turns a view into a PCL cloud.
 *
 * The camera (PCL's convention, that of pcl::RangeImagePlanar and of RGB-D drivers): in the
 * camera frame the optical centre is the origin, z points forward along the optical axis, x to
 * the right of the image and y down it. Pixel (u, v) is column u (0 .. width-1, left to right)
 * and row v (0 .. height-1, top to bottom); its ray goes from the origin through
 *   ((u + 0.5 - width / 2) / f, (v + 0.5 - height / 2) / f, 1),
 * f = (width / 2) / tan(horizontal_fov / 2) pixels (square pixels, centred principal point).
 *
 * The world frame of a view is the mesh's frame scaled (uniformly) so that its bounding-box
 * diagonal is object_diagonal and moved so that the box's centre is the origin: the object
 * as it would stand on a table. The camera sits at distance from that centre and looks at it.
 * Points are given in this world frame; the pose maps camera coordinates c to world ones,
 * world = origin + rotation * c (the rotation's columns are the camera's x, y, z axes in the
 * world), which is what PCL's sensor_origin_ and sensor_orientation_ mean.
 */
#pragma once

#include "surfaces/mesh_sampling.h"

#include <array>
#include <cstddef>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

namespace pcl_ncut_seg {

/** \brief The camera and the scene: a tabletop object seen by a structured-light sensor. */
struct CameraSettings {
  int width = 640, height = 480;
  double horizontal_fov_degrees = 57.0;
  double object_diagonal = 0.3; ///< metres: the model's bounding-box diagonal once scaled
  double distance = 1.0;        ///< metres from the optical centre to the box's centre
  /// Range noise: the depth z (metres) gets a normal error of sigma = noise_at_1m * z^2
  /// (as structured-light sensors have), along the pixel's ray. 0: no noise.
  double noise_at_1m = 0.0015;

  double focalLength() const; ///< f in pixels
};

/** \brief Where the camera is: world = origin + rotation * camera. */
struct CameraPose {
  std::array<double, 3> origin{{0, 0, 0}};
  std::array<double, 9> rotation{{1, 0, 0, 0, 1, 0, 0, 0, 1}}; ///< row-major 3 x 3
  /// The same rotation as a unit quaternion w, x, y, z.
  std::array<double, 4> quaternion() const;
};

/** \brief One organized depth image: width x height points, row by row (pixel (u, v) at index
 * v * width + u), and the face each pixel's ray hit first. */
struct DepthView {
  int width = 0, height = 0;
  std::vector<float> xyz;         ///< x, y, z per pixel in the world frame; NaN where no hit
  std::vector<std::int64_t> face; ///< per pixel the mesh's original face, -1 where no hit
  CameraPose pose;                ///< the sensor pose
  double scale = 1;               ///< world = scale * (mesh - centre)
  std::array<double, 3> centre{{0, 0, 0}};

  std::size_t validPixels() const;
};

/** \brief The first triangle a ray meets: its index in the mesh and the distance t along the
 * ray (point = origin + t * direction, t > 0), or triangle -1 for none. */
struct RayHit {
  std::int64_t triangle = -1;
  double t = 0;
};

/** \brief Exact ray casting on a triangle mesh (both sides of each triangle count), with a
 * bounding-volume hierarchy. Of several triangles hit at the same t, the lowest index wins, as
 * in castBruteForce, so that both always give the same hit. */
class RayCaster {
public:
  explicit RayCaster(const TriangleMesh& mesh);
  ~RayCaster();
  RayCaster(const RayCaster&) = delete;
  RayCaster& operator=(const RayCaster&) = delete;

  RayHit cast(const std::array<double, 3>& origin, const std::array<double, 3>& direction) const;
  /** \brief The same hit by testing every triangle (the reference for the tests). */
  static RayHit castBruteForce(const TriangleMesh& mesh, const std::array<double, 3>& origin,
                               const std::array<double, 3>& direction);

private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

/** \brief An image size "WxH" (e.g. "640x480"), each side an integer in [8, 4096].
 * \return false if the text is not one. */
bool parseResolution(const std::string& text, int& width, int& height);

/** \brief A uniformly random rotation (a random direction to look from and a random roll
 * about it) for this seed; the same on every platform. */
std::array<double, 9> randomRotation(std::uint64_t seed);

/** \brief The seed of view `view` of model `model`, so that views differ per model and view. */
std::uint64_t viewSeed(std::uint64_t model, std::uint64_t view);

/** \brief Render a mesh whose vertices are already in the world frame from this pose; the
 * noise is drawn from noise_seed (cross-platform). scale and centre of the result are 1, 0. */
DepthView renderMesh(const TriangleMesh& world_mesh, const CameraSettings& camera,
                     const CameraPose& pose, std::uint64_t noise_seed);

/** \brief The view of seed `seed`: the mesh scaled to the tabletop object, the camera at
 * camera.distance from its centre looking at it along randomRotation(seed)'s z axis.
 * \return an empty view (width 0) if the mesh has no extent. */
DepthView renderView(const TriangleMesh& mesh, const CameraSettings& camera, std::uint64_t seed);

} // namespace pcl_ncut_seg
