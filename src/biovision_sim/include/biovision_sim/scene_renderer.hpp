#pragma once

#include <vector>

#include <Eigen/Geometry>
#include <opencv2/core.hpp>

#include "biovision_sim/pinhole_camera.hpp"
#include "biovision_sim/world.hpp"

namespace biovision_sim
{
/// Software rasteriser of a World: z-buffered triangles with near-plane clipping, perspective-correct
/// texture coordinates, a mip level per triangle, bilinear texture filtering, Lambert shading and
/// supersampling for anti-aliasing. Produces the image and the true depth, so stereo matchers see a
/// realistic pair and tests know the exact answer. One core; thread-safe for concurrent render calls.
class SceneRenderer
{
public:
  /// supersample: 1 (none) .. 4 samples per axis.
  explicit SceneRenderer(const World& world, int supersample = 2);

  /// world_from_camera: pose of the camera's optical frame in the world. Outputs: bgr CV_8UC3 and depth
  /// CV_32F (optical z [m], +inf where only background is seen), both camera.width x camera.height.
  /// Depth is the harmonic mean over each pixel's samples, so disparity f*B/depth is the pixel's mean
  /// disparity, consistent with the anti-aliased image.
  void render(const Eigen::Isometry3d& world_from_camera, const PinholeCamera& camera, cv::Mat& bgr,
              cv::Mat& depth) const;

  size_t triangles() const { return triangles_.size(); }

private:
  struct Vertex
  {
    Eigen::Vector3f p;  // world [m]
    float u, v;         // texture [m]
  };
  struct Triangle
  {
    Vertex a, b, c;
    Eigen::Vector3f normal;  // world, outward
    int texture;
  };

  void addQuad(const Eigen::Vector3f& p0, const Eigen::Vector3f& p1, const Eigen::Vector3f& p2,
               const Eigen::Vector3f& p3, const Eigen::Vector2f& t0, const Eigen::Vector2f& t1,
               const Eigen::Vector2f& t2, const Eigen::Vector2f& t3, int texture);
  void addBox(const World::Object& o);
  void addCylinder(const World::Object& o);

  const World& world_;
  int supersample_;
  std::vector<Triangle> triangles_;
};
}  // namespace biovision_sim
