#pragma once

#include <random>
#include <string>

#include <Eigen/Geometry>
#include <image_transport/image_transport.h>
#include <opencv2/core.hpp>
#include <ros/ros.h>
#include <std_msgs/Header.h>
#include <tf2_ros/static_transform_broadcaster.h>
#include <tf2_ros/transform_broadcaster.h>
#include <urdf/model.h>

#include "biovision_sim/differential_drive.hpp"
#include "biovision_sim/kinematic_chain.hpp"
#include "biovision_sim/scene_renderer.hpp"
#include "biovision_sim/servo.hpp"
#include "biovision_sim/simulator_parameters.hpp"
#include "biovision_sim/stereo_calibration.hpp"
#include "biovision_sim/world.hpp"
#include <biovision_msgs/PlaceObject.h>
#include <memory>

namespace biovision_sim
{
/// The simulated BioVision robot (Pioneer 3DX + PhantomX pan/tilt + Bumblebee-2) in a World, speaking
/// the real drivers' topics: renders a rectified stereo pair, publishes joint states, odometry, tf and
/// ground truth, and follows head_{pan,tilt}_joint/command and cmd_vel. Sim time starts at 1 s and
/// advances one physics step per loop; topics and parameters are listed in the package README.
class Simulator
{
public:
  /// Reads the private parameters of `private_nh` (SimulatorParameters), the world file and
  /// `robot_description`, then advertises and subscribes on `nh`. Throws std::invalid_argument for a
  /// bad parameter (naming it) and std::runtime_error for a bad world file or robot_description.
  Simulator(const ros::NodeHandle& nh, const ros::NodeHandle& private_nh);
  Simulator(const Simulator&) = delete;
  Simulator& operator=(const Simulator&) = delete;

  /// Steps physics and renders until ROS shuts down, paced to real_time_factor.
  void run();

private:
  static SimulatorParameters loadParameters(const ros::NodeHandle& private_nh);
  void advertise();
  void subscribe();
  void publishObjectMarkers();
  /// sim/place_object: adds or moves an object; refuses bad YAML and objects on the base's footprint.
  bool placeObject(biovision_msgs::PlaceObject::Request& request, biovision_msgs::PlaceObject::Response& response);
  /// Servos and base by one physics step; returns the new sim time.
  ros::Time stepPhysics();
  Eigen::Isometry3d odomFromBase() const;
  void publishClock(const ros::Time& stamp);
  void publishJointStatesAndTf(const Eigen::Isometry3d& odom_from_base, const ros::Time& stamp);
  void publishOdometryAndGroundTruthPose(const Eigen::Isometry3d& odom_from_base, const ros::Time& stamp);
  void renderAndPublishCameras(const Eigen::Isometry3d& odom_from_base, const ros::Time& stamp);
  /// Optical blur, then sensor noise, in place on a bgr8 image.
  void degrade(cv::Mat& image);
  /// Depth and disparity of the left view, each only while it has subscribers.
  void publishGroundTruthDepth(const cv::Mat& depth, const std_msgs::Header& header);
  void waitForWallClock() const;

  ros::NodeHandle nh_;
  const SimulatorParameters parameters_;
  World world_;                              // sim/place_object changes it
  std::unique_ptr<SceneRenderer> renderer_;  // holds a reference to world_; rebuilt when world_ changes
  const urdf::Model robot_;
  const KinematicChain left_chain_, right_chain_;  // base_link -> stereo_{left,right}_optical
  Servo pan_, tilt_;
  DifferentialDrive base_;
  const StereoCalibration calibration_;
  std::mt19937 rng_;
  std::normal_distribution<float> noise_;

  image_transport::ImageTransport it_;
  image_transport::Publisher left_pub_, right_pub_, depth_pub_;
  ros::Publisher left_info_pub_, right_info_pub_, gt_disparity_pub_, joints_pub_, odom_pub_, gt_pose_pub_,
      collision_pub_, objects_pub_, clock_pub_;
  tf2_ros::TransformBroadcaster tf_;
  tf2_ros::StaticTransformBroadcaster static_tf_;
  ros::Subscriber pan_sub_, tilt_sub_, cmd_sub_;
  ros::ServiceServer place_srv_;

  ros::Time epoch_;           // sim time of step 0 (ROS time 0 means "unset")
  ros::WallTime wall_start_;  // wall time of step 0, for pacing
  double t_ = 0.0;            // sim time since epoch_ [s]
  long step_ = 0;             // physics steps since epoch_
};
}  // namespace biovision_sim
