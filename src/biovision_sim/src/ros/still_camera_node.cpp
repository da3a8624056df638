// still_camera: publishes an image file as a camera stream (image + camera_info) at a fixed rate.
// A stand-in camera for demos and tests that need a real image but no hardware.
#include <cmath>
#include <sstream>
#include <stdexcept>
#include <string>

#include <cv_bridge/cv_bridge.h>
#include <image_transport/image_transport.h>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>
#include <ros/ros.h>
#include <sensor_msgs/CameraInfo.h>
#include <sensor_msgs/image_encodings.h>

#include "biovision_sim/ros/camera_info.hpp"
#include "biovision_sim/ros/read_parameter.hpp"
#include "biovision_sim/stereo_calibration.hpp"

namespace
{
/// The node's private parameters (same names); the defaults here are the node's.
struct StillCameraParameters
{
  std::string file;                         ///< image file (cv::imread); required
  std::string frame_id = "camera_optical";  ///< frame of the image and camera_info
  double rate = 10.0;                       ///< publishing rate [Hz], (0, 1000]
  int width = 0;                            ///< [px], [1, kMaxSide]: the image is resized; both 0 = the file's
  int height = 0;                           ///< [px]; see width
  static constexpr int kMaxSide = 4096;     ///< [px] largest width or height (a resize beyond crashed, issue #23)
  double horizontal_fov_deg = 43.0;         ///< horizontal field of view [deg], (1, 179)
  double baseline = 0.0;                    ///< [m], [0, 10); > 0 makes this the right camera of a rectified pair

  /// Throws std::invalid_argument naming the parameter (wrong type or out of range).
  static StillCameraParameters load(const ros::NodeHandle& private_nh)
  {
    StillCameraParameters p;
    biovision_sim::readParameter(private_nh, "file", p.file);
    biovision_sim::readParameter(private_nh, "frame_id", p.frame_id);
    biovision_sim::readParameter(private_nh, "rate", p.rate);
    biovision_sim::readParameter(private_nh, "width", p.width);
    biovision_sim::readParameter(private_nh, "height", p.height);
    biovision_sim::readParameter(private_nh, "horizontal_fov_deg", p.horizontal_fov_deg);
    biovision_sim::readParameter(private_nh, "baseline", p.baseline);
    auto require = [](bool ok, const char* name, double value, const char* range) {
      if (ok)
        return;
      std::ostringstream s;
      s << "parameter ~" << name << " = " << value << " outside " << range;
      throw std::invalid_argument(s.str());
    };
    require(p.rate > 0.0 && p.rate <= 1000.0, "rate", p.rate, "(0, 1000] Hz");
    require(p.horizontal_fov_deg > 1.0 && p.horizontal_fov_deg < 179.0, "horizontal_fov_deg", p.horizontal_fov_deg,
            "(1, 179) deg");
    require(p.baseline >= 0.0 && p.baseline < 10.0, "baseline", p.baseline, "[0, 10) m");
    require(p.width >= 0 && p.width <= kMaxSide, "width", p.width, "[0, 4096] px");
    require(p.height >= 0 && p.height <= kMaxSide, "height", p.height, "[0, 4096] px");
    if ((p.width == 0) != (p.height == 0))
      throw std::invalid_argument("parameters ~width = " + std::to_string(p.width) + " and ~height = " +
                                  std::to_string(p.height) + ": give both (resize) or neither (the file's size)");
    return p;
  }
};

void publishForever(ros::NodeHandle& nh, const StillCameraParameters& p, const cv::Mat& image,
                    sensor_msgs::CameraInfo info)
{
  image_transport::ImageTransport it(nh);
  image_transport::Publisher image_pub = it.advertise("image", 1);
  ros::Publisher info_pub = nh.advertise<sensor_msgs::CameraInfo>("camera_info", 1);
  cv_bridge::CvImage frame;
  frame.encoding = sensor_msgs::image_encodings::BGR8;
  frame.image = image;
  frame.header.frame_id = p.frame_id;
  ROS_INFO("still_camera: %s (%dx%d) at %.1f Hz as %s", p.file.c_str(), image.cols, image.rows, p.rate,
           image_pub.getTopic().c_str());
  ros::Rate loop(p.rate);
  while (ros::ok())
  {
    frame.header.stamp = ros::Time::now();
    ++frame.header.seq;
    info.header = frame.header;
    image_pub.publish(frame.toImageMsg());
    info_pub.publish(info);
    ros::spinOnce();
    loop.sleep();
  }
}
}  // namespace

int main(int argc, char** argv)
{
  ros::init(argc, argv, "still_camera");
  ros::NodeHandle nh, private_nh("~");
  try
  {
    const StillCameraParameters p = StillCameraParameters::load(private_nh);
    cv::Mat image = cv::imread(p.file, cv::IMREAD_COLOR);
    if (image.empty())
      throw std::invalid_argument("cannot read image file '" + p.file + "' (~file)");
    if (image.cols > StillCameraParameters::kMaxSide || image.rows > StillCameraParameters::kMaxSide)
      throw std::invalid_argument("image file '" + p.file + "' is " + std::to_string(image.cols) + "x" +
                                  std::to_string(image.rows) + ": larger than 4096 px a side; set ~width and ~height");
    if (p.width > 0 && p.height > 0)
      cv::resize(image, image, cv::Size(p.width, p.height), 0, 0, cv::INTER_AREA);
    // With ~baseline 0 the right camera of the pair is the left one: a single rectified camera.
    const auto calibration = biovision_sim::StereoCalibration::fromFieldOfView(
        image.cols, image.rows, p.horizontal_fov_deg * M_PI / 180.0, p.baseline);
    std_msgs::Header header;
    header.frame_id = p.frame_id;
    publishForever(nh, p, image, biovision_sim::toCameraInfo(calibration.right(), header));
  }
  catch (const std::exception& e)
  {
    ROS_FATAL("still_camera: %s", e.what());
    return 1;
  }
  return 0;
}
