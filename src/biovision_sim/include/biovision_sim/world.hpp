#pragma once

#include <memory>
#include <string>
#include <vector>

#include <Eigen/Geometry>
#include <opencv2/core.hpp>

#include "biovision_sim/texture.hpp"

namespace YAML
{
class Node;
}

namespace biovision_sim
{
/// A textured world: a floor, walls and objects (boxes, cylinders), each with a label. Frame: x forward
/// from the robot's start, y left, z up (REP-103); metres and radians.
class World
{
public:
  struct Object
  {
    std::string label;
    std::string shape;                  ///< "box" or "cylinder"
    Eigen::Vector3d position{0, 0, 0};  ///< centre [m]
    double yaw = 0.0;                   ///< about z [rad]
    Eigen::Vector3d size{1, 1, 1};      ///< box: x, y, z extents; cylinder: 2r, 2r, height [m]
    int texture = 0;                    ///< index into textures()
    bool obstacle = true;               ///< the base collides with it (its footprint)
  };

  /// Parses a YAML world file. Throws std::runtime_error naming the file and line of the problem.
  static World load(const std::string& path);
  /// The same from YAML text (`origin` names it in errors).
  static World parse(const std::string& yaml_text, const std::string& origin = "<string>");

  const std::string& name() const { return name_; }
  const std::vector<Object>& objects() const { return objects_; }
  const std::vector<std::shared_ptr<Texture>>& textures() const { return textures_; }
  int floorTexture() const { return floor_texture_; }
  double floorSize() const { return floor_size_; }
  const Eigen::Vector3d& lightDirection() const { return light_direction_; }  ///< unit, pointing from the light
  double ambient() const { return ambient_; }
  cv::Vec3b background() const { return background_; }

  /// Adds an object programmatically (tests, tools); returns its index.
  int addObject(const Object& object);
  int addTexture(const Texture::Spec& spec);
  /// Adds one object given as a world-file `objects` entry in YAML (e.g. `{label: crate, shape: box,
  /// position: [1, 0, 0.2], size: [0.4, 0.4, 0.4]}`), or replaces the object with the same label (moves
  /// it, reshapes it, retextures it). Returns its index. Throws std::runtime_error naming `origin` for
  /// bad YAML or a bad field; the world is unchanged then. Used by the simulator's sim/place_object.
  int placeObject(const std::string& yaml_text, const std::string& origin = "<object>");

private:
  /// One `objects` entry; adds its texture to textures_ last, so a throw leaves the world unchanged.
  Object parseObject(const std::string& origin, const YAML::Node& node);

  std::string name_ = "world";
  std::vector<Object> objects_;
  std::vector<std::shared_ptr<Texture>> textures_;
  int floor_texture_ = -1;
  double floor_size_ = 40.0;
  Eigen::Vector3d light_direction_{0.3, 0.2, -1.0};
  double ambient_ = 0.45;
  cv::Vec3b background_{220, 210, 200};
};
}  // namespace biovision_sim
