#pragma once

#include <opencv2/core.hpp>

namespace biovision_saliency
{
/// Head pose and camera geometry for one frame: turns image pixels into head-centred directions,
/// so that Inhibition-of-Return stays on the same object when the head turns.
struct HeadDirection
{
  double pan = 0.0;       ///< head pan [rad, + = left] (joint_states)
  double tilt = 0.0;      ///< head tilt [rad, + = down]
  double focal = 0.0;     ///< focal length at full resolution [px]
  cv::Point2d principal;  ///< principal point at full resolution [px]

  /// Direction of image pixel p: pan + atan((cx - u) / f), tilt + atan((v - cy) / f).
  cv::Point2d directionOf(const cv::Point2f& p) const;
};
}  // namespace biovision_saliency
