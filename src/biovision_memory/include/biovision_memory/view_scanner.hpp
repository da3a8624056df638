#pragma once

#include <Eigen/Geometry>
#include <opencv2/core.hpp>

#include "biovision_memory/disparity_camera.hpp"
#include "biovision_memory/view_scan.hpp"
#include "biovision_memory/view_scan_parameters.hpp"

namespace biovision_memory
{
/// Projects a left-view disparity map onto the floor around the robot (thesis §5.3.1 step 1–2, with the
/// "20% of maximum disparity" threshold read as a distance): every valid pixel becomes a point in
/// base_link through the camera's pose (the head pan and tilt from tf); points between the obstacle
/// heights and within max_range are obstacles, lower points are floor. Per image strip it keeps the
/// nearest obstacle; per bearing bin the nearest obstacle and the range of floor seen free.
/// ROS-free; stateless apart from its parameters.
class ViewScanner
{
public:
  /// Throws std::invalid_argument (from ViewScanParameters::validate) on bad parameters.
  explicit ViewScanner(const ViewScanParameters& parameters = {});

  /// disparity: CV_32FC1, left view, in pixels at `camera`'s resolution; values ≤ 0, NaN or ±Inf are
  /// "no disparity" (BioBin's kInvalid = −1, stereo_msgs' min_disparity convention). base_from_camera:
  /// the left optical frame (z forward, x right, y down) in base_link, whose origin is on the floor.
  /// Throws std::invalid_argument when the disparity is empty or not CV_32FC1 or the camera is invalid.
  ViewScan scan(const cv::Mat& disparity, const DisparityCamera& camera,
                const Eigen::Isometry3d& base_from_camera) const;

  const ViewScanParameters& parameters() const { return parameters_; }

private:
  ViewScanParameters parameters_;
};
}  // namespace biovision_memory
