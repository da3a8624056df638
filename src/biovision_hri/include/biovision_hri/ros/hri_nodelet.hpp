#pragma once

#include <cmath>
#include <memory>
#include <mutex>
#include <string>

#include <biovision_hri/HriConfig.h>
#include <biovision_msgs/SalientRegionArray.h>
#include <biovision_msgs/SetHeadMode.h>
#include <dynamic_reconfigure/server.h>
#include <image_transport/image_transport.h>
#include <ros/ros.h>
#include <sensor_msgs/Image.h>
#include <sensor_msgs/JointState.h>
#include <std_srvs/Trigger.h>

#include <boost/thread/recursive_mutex.hpp>

#include "biovision_hri/gesture_recognizer.hpp"
#include "biovision_hri/greet_behaviour.hpp"
#include "biovision_hri/hand_posture_classifier.hpp"
#include "biovision_hri/ros/hri_config.hpp"
#include "biovision_hri/sliding_window_detector.hpp"
#include "biovision_ros_common/async_service_client.hpp"
#include "biovision_ros_common/clock_jump_guard.hpp"
#include "biovision_ros_common/lazy_nodelet.hpp"
#include "biovision_ros_common/nodelet_diagnostics.hpp"

namespace biovision_hri
{
/// ROS wrapper of the HRI cores (thesis ch. 2). Subscribes the left `image` (and `saliency/regions` for
/// hands in salient regions, `joint_states` for the greet behaviour) only while someone listens to
/// `hri/faces`, `hri/hands` or `hri/gestures` (LazyNodelet; `~lazy: false` keeps it on). Publishes the
/// detections of every image, gestures in the hand boxes, and runs GreetBehaviour when `hri/greet` is
/// called: it puts the head controller on hold (`head/set_mode`), commands `<pan_joint>/command` and
/// `<tilt_joint>/command` inside the joint limits, publishes the gesture's action on `hri/action`, and
/// gives the head back (`explore`) when it finishes.
class HriNodelet : public biovision_ros_common::LazyNodelet
{
public:
  ~HriNodelet() override;

private:
  void onInitNodelet() override;
  void subscribe() override;
  void unsubscribe() override;
  void imageCallback(const sensor_msgs::ImageConstPtr& msg);
  void regionsCallback(const biovision_msgs::SalientRegionArrayConstPtr& msg);
  void jointCallback(const sensor_msgs::JointStateConstPtr& msg);
  bool greet(std_srvs::Trigger::Request& req, std_srvs::Trigger::Response& res);
  bool stopGreet(std_srvs::Trigger::Request& req, std_srvs::Trigger::Response& res);
  /// Keeps the images subscribed while a greeting is requested or runs (LazyNodelet::setBusy); takes mutex_.
  void updateBusy();
  void reconfigure(HriConfig& config, uint32_t level);
  void details(diagnostic_updater::DiagnosticStatusWrapper& status);
  /// Asks the head controller for `mode` (head/set_mode, off this thread); sent by sendHeadMode().
  void setHeadMode(const std::string& mode);
  /// Reports the last head/set_mode call's outcome and sends the mode asked for since, when no call is under
  /// way (from images and a 2 Hz wall timer); a mode not answered is sent again after 1 s.
  void sendHeadMode();

  std::unique_ptr<image_transport::ImageTransport> it_;
  image_transport::Subscriber image_sub_;
  ros::Subscriber regions_sub_, joint_sub_;
  std::string input_topic_;
  ros::Publisher faces_pub_, hands_pub_, gestures_pub_, action_pub_, pan_pub_, tilt_pub_;
  ros::ServiceServer greet_srv_, stop_srv_;
  std::unique_ptr<biovision_ros_common::AsyncServiceClient<biovision_msgs::SetHeadMode>> head_mode_client_;
  std::mutex head_mode_mutex_;        // guards the head mode fields below; never held while taking mutex_
  std::string head_mode_wanted_;      ///< a mode asked for and not yet sent ("" = none)
  std::string head_mode_sent_;        ///< the mode of the call under way or last made
  std::string head_mode_answer_;      ///< the last call's outcome (diagnostics)
  ros::WallTime head_mode_retry_at_;  ///< a mode not answered is sent again from then on
  ros::WallTimer head_mode_timer_;
  std::string pan_joint_, tilt_joint_;
  double max_input_age_ = 0.5;
  size_t max_input_pixels_ = 0;             // ~max_input_pixels: larger images are refused (bounded memory and time)
  std::string gestures_off_, posture_off_;  // why a configured gesture method is off ("" = on or not asked for)

  std::mutex mutex_;  // guards everything below
  std::unique_ptr<SlidingWindowDetector> face_detector_, hand_detector_;
  std::unique_ptr<GestureRecognizer> gestures_;
  std::unique_ptr<HandPostureClassifier> posture_;
  std::unique_ptr<GreetBehaviour> behaviour_;
  GreetBehaviour::Parameters greet_base_;
  HriParameters parameters_;
  biovision_msgs::SalientRegionArrayConstPtr regions_;
  double pan_ = 0.0, tilt_ = 0.0;
  bool have_joints_ = false;
  bool start_requested_ = false;
  std::string last_action_, last_reason_;
  double last_image_t_ = -HUGE_VAL;  ///< [s] the newest image stamp seen
  ros::WallTime image_time_moved_;   ///< when an image with a newer stamp (or hri/greet) last came
  double last_ms_ = 0.0;
  size_t last_faces_ = 0, last_hands_ = 0, last_gestures_ = 0;
  biovision_ros_common::ClockJumpGuard image_clock_{0.0};

  boost::recursive_mutex reconfigure_mutex_;  // dynamic_reconfigure::Server takes a boost mutex; outlives it
  std::unique_ptr<dynamic_reconfigure::Server<HriConfig>> reconfigure_server_;
  biovision_ros_common::NodeletDiagnostics diagnostics_;
};
}  // namespace biovision_hri
