// still_camera: publishes an image file as a camera stream (image + camera_info) at a fixed rate.
// A stand-in camera for demos and tests that need a real image but no hardware.
#include <cmath>
#include <string>

#include <cv_bridge/cv_bridge.h>
#include <image_transport/image_transport.h>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>
#include <ros/ros.h>
#include <sensor_msgs/CameraInfo.h>
#include <sensor_msgs/image_encodings.h>

int main(int argc, char** argv)
{
  ros::init(argc, argv, "still_camera");
  ros::NodeHandle nh, pnh("~");
  std::string file, frame_id;
  double rate = 10.0, hfov_deg = 43.0, baseline = 0.0;
  int width = 0, height = 0;
  pnh.param<std::string>("file", file, "");
  pnh.param<std::string>("frame_id", frame_id, "camera_optical");
  pnh.param("rate", rate, 10.0);
  pnh.param("width", width, 0);    // 0 = the file's size
  pnh.param("height", height, 0);
  pnh.param("horizontal_fov_deg", hfov_deg, 43.0);
  pnh.param("baseline", baseline, 0.0);  // > 0: this is the right camera of a rectified pair [m]
  if (!(rate > 0.0 && rate <= 1000.0))
  {
    ROS_ERROR("still_camera: ~rate %.3f outside (0, 1000] Hz; using 10", rate);
    rate = 10.0;
  }
  if (!(hfov_deg > 1.0 && hfov_deg < 179.0))
  {
    ROS_ERROR("still_camera: ~horizontal_fov_deg %.1f outside (1, 179); using 43", hfov_deg);
    hfov_deg = 43.0;
  }
  cv::Mat image = cv::imread(file, cv::IMREAD_COLOR);
  if (image.empty())
  {
    ROS_FATAL("still_camera: cannot read image file '%s' (~file)", file.c_str());
    return 1;
  }
  if (width > 0 && height > 0)
    cv::resize(image, image, cv::Size(width, height), 0, 0, cv::INTER_AREA);

  // Pinhole calibration consistent with the field of view; no distortion (the image is "rectified").
  sensor_msgs::CameraInfo info;
  info.width = image.cols;
  info.height = image.rows;
  info.distortion_model = "plumb_bob";
  info.D.assign(5, 0.0);
  const double f = 0.5 * image.cols / std::tan(0.5 * hfov_deg * M_PI / 180.0);
  const double cx = 0.5 * (image.cols - 1), cy = 0.5 * (image.rows - 1);
  info.K = {f, 0, cx, 0, f, cy, 0, 0, 1};
  info.R = {1, 0, 0, 0, 1, 0, 0, 0, 1};
  if (!(baseline >= 0.0 && baseline < 10.0))
  {
    ROS_ERROR("still_camera: ~baseline %.3f outside [0, 10) m; using 0", baseline);
    baseline = 0.0;
  }
  // Right camera of a rectified pair: P[3] = -fx * baseline (the ROS stereo convention).
  info.P = {f, 0, cx, -f * baseline, 0, f, cy, 0, 0, 0, 1, 0};

  image_transport::ImageTransport it(nh);
  image_transport::Publisher image_pub = it.advertise("image", 1);
  ros::Publisher info_pub = nh.advertise<sensor_msgs::CameraInfo>("camera_info", 1);
  cv_bridge::CvImage frame;
  frame.encoding = sensor_msgs::image_encodings::BGR8;
  frame.image = image;
  frame.header.frame_id = frame_id;
  info.header.frame_id = frame_id;
  ROS_INFO("still_camera: %s (%dx%d) at %.1f Hz as %s", file.c_str(), image.cols, image.rows, rate,
           image_pub.getTopic().c_str());
  ros::Rate loop(rate);
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
  return 0;
}
