#include "bumblebee2_driver/ros/bumblebee2_driver_nodelet.hpp"

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <iterator>

#include <opencv2/imgproc.hpp>
#include <pluginlib/class_list_macros.hpp>
#include <sensor_msgs/image_encodings.h>

#include "biovision_ros_common/typed_parameter.hpp"

namespace bumblebee2_driver
{
namespace
{
sensor_msgs::ImagePtr toMessage(const cv::Mat& image, const std::string& encoding, const std_msgs::Header& header)
{
  auto msg = boost::make_shared<sensor_msgs::Image>();
  msg->header = header;
  msg->height = static_cast<uint32_t>(image.rows);
  msg->width = static_cast<uint32_t>(image.cols);
  msg->encoding = encoding;
  msg->is_bigendian = 0;
  msg->step = static_cast<uint32_t>(image.cols * image.elemSize());
  msg->data.resize(static_cast<size_t>(msg->step) * image.rows);
  for (int y = 0; y < image.rows; ++y)
    std::memcpy(msg->data.data() + static_cast<size_t>(y) * msg->step, image.ptr(y), msg->step);
  return msg;
}
}  // namespace

Bumblebee2DriverNodelet::~Bumblebee2DriverNodelet()
{
  running_ = false;
  if (thread_.joinable())
    thread_.join();
  camera_.close();
}

void Bumblebee2DriverNodelet::onInit()
{
  ros::NodeHandle& nh = getNodeHandle();
  ros::NodeHandle& pnh = getPrivateNodeHandle();
  try
  {
    // A value of the wrong type is refused, not replaced by the default (a driver told `_port:=123` opened
    // /dev/ttyUSB0).
    visitParameters(parameters_, [&](const std::string& name, auto& value) {
      biovision_ros_common::readTypedParameter(pnh, name, value);
    });
    parameters_.validate();
  }
  catch (const std::invalid_argument& e)
  {
    NODELET_FATAL("%s", e.what());
    throw;
  }
  it_ = std::make_unique<image_transport::ImageTransport>(nh);
  left_pub_ = it_->advertise("stereo/left/image_raw", 1);
  right_pub_ = it_->advertise("stereo/right/image_raw", 1);
  left_info_pub_ = nh.advertise<sensor_msgs::CameraInfo>("stereo/left/camera_info", 1);
  right_info_pub_ = nh.advertise<sensor_msgs::CameraInfo>("stereo/right/camera_info", 1);
  ros::NodeHandle left_nh(nh, "stereo/left"), right_nh(nh, "stereo/right");
  left_info_ = std::make_unique<camera_info_manager::CameraInfoManager>(left_nh, "bumblebee2_left",
                                                                        parameters_.left_camera_info_url);
  right_info_ = std::make_unique<camera_info_manager::CameraInfoManager>(right_nh, "bumblebee2_right",
                                                                         parameters_.right_camera_info_url);
  for (auto* m : {left_info_.get(), right_info_.get()})
    if (!m->isCalibrated())
      NODELET_WARN(
          "a Bumblebee-2 sensor has no calibration (camera_info URL empty or unreadable): run "
          "camera_calibration, see docs/robot.md");
  biovision_ros_common::DiagnosticsOptions options;
  options.status_name = "Bumblebee-2";
  options.rate_topic = "stereo/left/image_raw";
  options.default_max_rate = 2.0 * parameters_.frame_rate;
  options.working_message = "capturing";
  options.details = [this](diagnostic_updater::DiagnosticStatusWrapper& s) {
    std::lock_guard<std::mutex> lock(status_mutex_);
    if (source_.empty())
      s.summary(diagnostic_msgs::DiagnosticStatus::ERROR, "no camera: " + last_error_);
    s.add("source", source_);
    s.add("bayer pattern", pattern_name_);
    s.add("swap_left_right", parameters_.swap_left_right);
    s.add("first-frame disparity [px] (negative = swapped?)", measured_disparity_);
    s.add("frames", frames_);
    s.add("left calibrated", left_info_->isCalibrated());
    s.add("right calibrated", right_info_->isCalibrated());
    s.add("last error", last_error_);
  };
  diagnostics_.init(nh, pnh, getName(), options);
  running_ = true;
  thread_ = std::thread([this] { run(); });
}

void Bumblebee2DriverNodelet::run()
{
  const BayerPattern override_pattern = parameters_.bayer_pattern == "auto"
                                            ? BayerPattern::kGrbg
                                            : bayerPatternFromName(parameters_.bayer_pattern);
  const bool from_file = !parameters_.frame_file.empty();
  std::vector<uint8_t> file_frame;
  // Sleeps in short slices, so that a shutdown is never kept waiting by a long retry_period or a low
  // frame_rate (a 0.01 Hz rate or a 60 s retry held SIGINT off until SIGKILL).
  auto pause = [this](double seconds) {
    const double end = ros::WallTime::now().toSec() + seconds;
    for (double left = seconds; left > 0.0 && running_ && ros::ok(); left = end - ros::WallTime::now().toSec())
      ros::WallDuration(std::min(left, 0.05)).sleep();
  };
  double next_frame = ros::WallTime::now().toSec(), next_attempt = 0.0;
  while (running_ && ros::ok())
  {
    if (from_file)
    {
      if (file_frame.empty())
      {
        const size_t expected = static_cast<size_t>(parameters_.width) * parameters_.height * 2;
        std::string error;
        std::error_code ec;
        // Checked before reading: a directory threw, /dev/zero read until memory ran out, a FIFO blocked.
        if (!std::filesystem::is_regular_file(parameters_.frame_file, ec))
          error = "frame_file " + parameters_.frame_file + ": not a regular file";
        else if (const auto size = std::filesystem::file_size(parameters_.frame_file, ec); ec || size != expected)
          error = "frame_file " + parameters_.frame_file + ": " +
                  (ec ? ec.message() : std::to_string(size) + " bytes") +
                  ", expected width x height x 2 = " + std::to_string(expected);
        else
        {
          std::ifstream in(parameters_.frame_file, std::ios::binary);
          file_frame.resize(expected);
          if (!in.read(reinterpret_cast<char*>(file_frame.data()), static_cast<std::streamsize>(expected)))
            error = "frame_file " + parameters_.frame_file + ": cannot read " + std::to_string(expected) + " bytes";
        }
        if (!error.empty())
        {
          diagnostics_.health().reportError(getName(), error);
          {
            std::lock_guard<std::mutex> lock(status_mutex_);
            last_error_ = error;
          }
          file_frame.clear();
          pause(parameters_.retry_period);
          continue;
        }
        std::lock_guard<std::mutex> lock(status_mutex_);
        source_ = "file " + parameters_.frame_file;
        pattern_name_ = bayerPatternName(override_pattern);
      }
      try
      {
        publish(file_frame, override_pattern);
      }
      catch (const std::exception& e)
      {
        diagnostics_.health().reportError(getName(), std::string("frame_file ") + parameters_.frame_file +
                                                         ": cannot publish: " + e.what());
      }
      next_frame = std::max(next_frame + 1.0 / parameters_.frame_rate, ros::WallTime::now().toSec());
      pause(next_frame - ros::WallTime::now().toSec());
      continue;
    }
    if (!camera_.isOpen())
    {
      const double now = ros::WallTime::now().toSec();
      if (now < next_attempt)
      {
        pause(0.05);
        continue;
      }
      try
      {
        camera_.open(parameters_);
        std::lock_guard<std::mutex> lock(status_mutex_);
        source_ = "camera " + camera_.guid() + " (" + camera_.model() + ")";
        const BayerPattern p = parameters_.bayer_pattern == "auto" ? camera_.bayerPattern() : override_pattern;
        pattern_name_ = bayerPatternName(p) +
                        (parameters_.bayer_pattern == "auto" ? " (register 0x1040)" : " (parameter)");
        NODELET_INFO("Bumblebee-2 %s: %dx%d RAW16 at %.1f Hz, pattern %s", source_.c_str(), parameters_.width,
                     parameters_.height, parameters_.frame_rate, pattern_name_.c_str());
      }
      catch (const std::exception& e)
      {
        diagnostics_.health().reportError(getName(), std::string(e.what()) + "; retrying every " +
                                                         std::to_string(parameters_.retry_period) + " s");
        std::lock_guard<std::mutex> lock(status_mutex_);
        last_error_ = e.what();
        source_.clear();
        next_attempt = now + parameters_.retry_period;
        continue;
      }
    }
    try
    {
      const auto raw = camera_.grab();
      publish(raw, parameters_.bayer_pattern == "auto" ? camera_.bayerPattern() : override_pattern);
    }
    catch (const std::exception& e)
    {
      camera_.close();
      diagnostics_.health().reportError(getName(), std::string("capture failed, reopening: ") + e.what());
      std::lock_guard<std::mutex> lock(status_mutex_);
      last_error_ = e.what();
      source_.clear();
    }
  }
}

void Bumblebee2DriverNodelet::publish(const std::vector<uint8_t>& raw16, BayerPattern pattern)
{
  const StereoRaw pair = deinterleave(raw16.data(), parameters_.width, parameters_.height, parameters_.swap_left_right);
  std_msgs::Header left_header, right_header;
  left_header.stamp = right_header.stamp = ros::Time::now();
  left_header.frame_id = parameters_.left_frame_id;
  right_header.frame_id = parameters_.right_frame_id;
  cv::Mat left = pair.left, right = pair.right;
  std::string encoding = rosEncoding(pattern);
  if (parameters_.debayer || !swap_checked_)
  {
    const cv::Mat left_colour = debayer(pair.left, pattern), right_colour = debayer(pair.right, pattern);
    if (!swap_checked_)
    {
      // The documented left/right check, once: a correctly ordered pair has a non-negative disparity.
      const double d = horizontalDisparity(left_colour, right_colour);
      if (d < -1.0)
        NODELET_WARN(
            "the first stereo frame has a negative disparity (%.1f px): left and right look swapped; "
            "confirm by covering the left lens, then set swap_left_right (docs/robot.md)",
            d);
      std::lock_guard<std::mutex> lock(status_mutex_);
      measured_disparity_ = d;
      swap_checked_ = true;
    }
    if (parameters_.debayer)
    {
      left = left_colour;
      right = right_colour;
      encoding = pattern == BayerPattern::kMono ? sensor_msgs::image_encodings::MONO8
                                                : sensor_msgs::image_encodings::BGR8;
    }
  }
  auto publishInfo = [&](camera_info_manager::CameraInfoManager& manager, ros::Publisher& pub,
                         const std_msgs::Header& header, const char* side) {
    sensor_msgs::CameraInfo info = manager.getCameraInfo();
    if (info.width == 0 && info.height == 0)  // uncalibrated: the size at least
    {
      info.width = static_cast<uint32_t>(parameters_.width);
      info.height = static_cast<uint32_t>(parameters_.height);
    }
    if (info.width != static_cast<uint32_t>(parameters_.width) ||
        info.height != static_cast<uint32_t>(parameters_.height))
    {
      diagnostics_.health().reportError(getName(), std::string("the ") + side + " calibration is for " +
                                                       std::to_string(info.width) + "x" + std::to_string(info.height) +
                                                       ", the images are " + std::to_string(parameters_.width) + "x" +
                                                       std::to_string(parameters_.height) + ": camera_info withheld");
      return;
    }
    info.header = header;
    pub.publish(info);
  };
  left_pub_.publish(toMessage(left, encoding, left_header));
  right_pub_.publish(toMessage(right, encoding, right_header));
  publishInfo(*left_info_, left_info_pub_, left_header, "left");
  publishInfo(*right_info_, right_info_pub_, right_header, "right");
  diagnostics_.tick();
  std::lock_guard<std::mutex> lock(status_mutex_);
  frames_++;
}
}  // namespace bumblebee2_driver

PLUGINLIB_EXPORT_CLASS(bumblebee2_driver::Bumblebee2DriverNodelet, nodelet::Nodelet)
