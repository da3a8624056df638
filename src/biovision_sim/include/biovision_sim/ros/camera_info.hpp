#pragma once

#include <sensor_msgs/CameraInfo.h>
#include <std_msgs/Header.h>

#include "biovision_sim/stereo_calibration.hpp"

namespace biovision_sim
{
/// The camera_info of one camera of an ideal rectified pair: plumb_bob with zero distortion, identity
/// R, K and P from `camera`, no binning or ROI, and `header` (a rectified pair's two camera_info carry
/// the left frame id: image_geometry's StereoCameraModel requires equal frame ids).
sensor_msgs::CameraInfo toCameraInfo(const StereoCalibration::Camera& camera, const std_msgs::Header& header);
}  // namespace biovision_sim
