#pragma once

#include <string>

namespace biovision_sim
{
/// Parameters of the simulated robot (the `sim` node's private parameters, same names). The defaults
/// here are the node's defaults.
struct SimulatorParameters
{
  std::string world;                          ///< world YAML file (World::load); required, no default
  double camera_rate = 10.0;                  ///< stereo frames per sim second [Hz], > 0
  double physics_rate = 50.0;                 ///< physics steps per sim second [Hz], >= camera_rate; joint_states,
                                              ///< odom and tf come at this rate
  static constexpr int kMaxImageSide = 4096;  ///< [px] largest width or height
  int width = 320;                            ///< image width [px], [32, kMaxImageSide]
  int height = 240;                           ///< image height [px], [24, kMaxImageSide]
  double horizontal_fov_deg = 43.0;           ///< horizontal field of view [deg], (1, 179) (Bumblebee-2: 43)
  int supersample = 2;                        ///< anti-aliasing samples per pixel and axis, 1..4
  double noise_sigma = 0.0;                   ///< Gaussian image noise [grey levels], >= 0
  double blur_sigma = 0.0;                    ///< Gaussian optical blur [px], [0, 10]
  int seed = 1;                               ///< seed of the image noise
  double real_time_factor = 1.0;              ///< sim seconds per wall second, >= 0 (0: as fast as possible)
  bool publish_clock = true;                  ///< publish sim time on /clock (for use_sim_time)
  /// publish the identity map -> odom (the odometry is perfect); false when a localisation node, e.g.
  /// biovision_memory's landmark correction, owns that transform (two publishers would fight)
  bool publish_map_to_odom = true;
  double start_x = 0.0;      ///< initial base position in map [m], finite
  double start_y = 0.0;      ///< initial base position in map [m], finite
  double start_yaw = 0.0;    ///< initial base heading in map [rad], finite
  double servo_speed = 3.0;  ///< pan and tilt speed limit [rad/s], > 0

  /// Throws std::invalid_argument naming the offending field, its value and its range.
  void validate() const;
};
}  // namespace biovision_sim
