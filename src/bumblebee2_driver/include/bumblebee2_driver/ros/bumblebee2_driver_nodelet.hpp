#pragma once

#include <atomic>
#include <memory>
#include <mutex>
#include <thread>

#include <camera_info_manager/camera_info_manager.h>
#include <image_transport/image_transport.h>
#include <nodelet/nodelet.h>
#include <ros/ros.h>

#include "biovision_ros_common/nodelet_diagnostics.hpp"
#include "bumblebee2_driver/bumblebee2_parameters.hpp"
#include "bumblebee2_driver/dc1394_camera.hpp"
#include "bumblebee2_driver/stereo_frame.hpp"

namespace bumblebee2_driver
{
/// The Bumblebee-2 driver as a nodelet, with the simulator's topics: `stereo/{left,right}/image_raw`
/// (bayer_*8 raw mosaic, or bgr8 with ~debayer) and `stereo/{left,right}/camera_info` from
/// camera_info_manager (~left_camera_info_url, ~right_camera_info_url; `set_camera_info` services for
/// camera_calibration). Captures on its own thread; without a camera it reports an ERROR and retries every
/// ~retry_period; ~frame_file publishes a recorded RAW16 frame instead (tests, no camera). Not lazy.
class Bumblebee2DriverNodelet : public nodelet::Nodelet
{
public:
  ~Bumblebee2DriverNodelet() override;

private:
  void onInit() override;
  void run();
  void publish(const std::vector<uint8_t>& raw16, BayerPattern pattern);

  Bumblebee2Parameters parameters_;
  std::unique_ptr<image_transport::ImageTransport> it_;
  image_transport::Publisher left_pub_, right_pub_;
  ros::Publisher left_info_pub_, right_info_pub_;
  std::unique_ptr<camera_info_manager::CameraInfoManager> left_info_, right_info_;
  biovision_ros_common::NodeletDiagnostics diagnostics_;
  Dc1394Camera camera_;
  std::mutex status_mutex_;
  std::string source_, pattern_name_, last_error_;
  double measured_disparity_ = 0.0;
  bool swap_checked_ = false;
  unsigned long frames_ = 0;
  std::atomic<bool> running_{false};
  std::thread thread_;
};
}  // namespace bumblebee2_driver
