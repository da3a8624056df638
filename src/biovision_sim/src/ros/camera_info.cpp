#include "biovision_sim/ros/camera_info.hpp"

#include <algorithm>

namespace biovision_sim
{
sensor_msgs::CameraInfo toCameraInfo(const StereoCalibration::Camera& camera, const std_msgs::Header& header)
{
  sensor_msgs::CameraInfo info;
  info.header = header;
  info.width = static_cast<uint32_t>(camera.width);
  info.height = static_cast<uint32_t>(camera.height);
  info.distortion_model = "plumb_bob";
  info.D.assign(5, 0.0);
  std::copy(camera.K.begin(), camera.K.end(), info.K.begin());
  info.R = {1, 0, 0, 0, 1, 0, 0, 0, 1};
  std::copy(camera.P.begin(), camera.P.end(), info.P.begin());
  return info;
}
}  // namespace biovision_sim
