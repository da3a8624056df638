#pragma once

#include <atomic>
#include <memory>
#include <mutex>
#include <string>

#include <biovision_saliency/SaliencyConfig.h>
#include <boost/thread/recursive_mutex.hpp>
#include <diagnostic_updater/diagnostic_updater.h>
#include <diagnostic_updater/publisher.h>
#include <dynamic_reconfigure/server.h>
#include <image_transport/image_transport.h>
#include <nodelet/nodelet.h>
#include <ros/ros.h>
#include <sensor_msgs/CameraInfo.h>
#include <sensor_msgs/Image.h>
#include <sensor_msgs/JointState.h>
#include <std_srvs/Trigger.h>
#include <stereo_msgs/DisparityImage.h>

#include "biovision_saliency/saliency_pipeline.hpp"
#include "biovision_ros_common/lazy_nodelet.hpp"
#include "biovision_ros_common/nodelet_diagnostics.hpp"

namespace biovision_saliency
{
/// ROS wrapper of SaliencyPipeline. Processes every `image` (the left camera) with the latest
/// `disparity`, `joint_states` and `camera_info` when they are recent; each of those is optional and
/// the map degrades to the channels it has. Publishes `saliency/map` (32FC1, working resolution),
/// `saliency/thresholded` (mono8) and `saliency/regions` (FoA order); subscribes only while one of them
/// has a subscriber. Service `saliency/reset_inhibition` clears the IoR memory.
/// Bad input (issue #23): an image larger than ~max_input_pixels, a camera_info that InputCheck::cameraInfo
/// refuses (fx 0/NaN/Inf/tiny, NaN in P, zero size) or joint_states with a NaN/Inf/huge head joint or
/// mismatched name/position lengths is refused with a throttled error and an ERROR diagnostic; the refused
/// value is not used (the previous good one stays). A region whose pan/tilt is not finite and within ±pi is
/// never published.
class SaliencyNodelet : public biovision_ros_common::LazyNodelet
{
private:
  void onInitNodelet() override;
  void subscribe() override;
  void unsubscribe() override;
  void imageCallback(const sensor_msgs::ImageConstPtr& msg);
  void disparityCallback(const stereo_msgs::DisparityImageConstPtr& msg);
  void jointCallback(const sensor_msgs::JointStateConstPtr& msg);
  void infoCallback(const sensor_msgs::CameraInfoConstPtr& msg);
  bool resetInhibition(std_srvs::Trigger::Request& req, std_srvs::Trigger::Response& res);
  void reconfigure(SaliencyConfig& config, uint32_t level);
  void details(diagnostic_updater::DiagnosticStatusWrapper& status);

  std::unique_ptr<image_transport::ImageTransport> it_;
  image_transport::Subscriber image_sub_;
  ros::Subscriber disparity_sub_, joint_sub_, info_sub_;
  image_transport::Publisher map_pub_, thresholded_pub_;
  ros::Publisher regions_pub_;
  ros::ServiceServer reset_srv_;

  std::mutex state_mutex_;  // pipeline and the latest optional inputs
  std::unique_ptr<SaliencyPipeline> pipeline_;
  stereo_msgs::DisparityImageConstPtr disparity_;
  sensor_msgs::CameraInfoConstPtr info_;
  double pan_ = 0.0, tilt_ = 0.0;
  ros::Time joints_stamp_;
  std::string pan_joint_ = "head_pan_joint", tilt_joint_ = "head_tilt_joint";
  double max_input_age_ = 0.5;
  size_t max_input_pixels_ = 0;                            // ~max_input_pixels
  biovision_ros_common::ClockJumpGuard image_clock_{0.0};  // image stamps going back: motion and IoR restart

  boost::recursive_mutex reconfigure_mutex_;  // dynamic_reconfigure::Server takes a boost mutex; outlives it
  std::unique_ptr<dynamic_reconfigure::Server<SaliencyConfig>> reconfigure_server_;
  biovision_ros_common::NodeletDiagnostics diagnostics_;
  double last_ms_ = 0.0;
  size_t last_regions_ = 0;
  std::string last_channels_;
};
}  // namespace biovision_saliency
