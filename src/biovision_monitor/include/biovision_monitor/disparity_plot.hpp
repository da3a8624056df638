#pragma once

#include <opencv2/core.hpp>

namespace biovision_monitor
{
/// A disparity map colour-mapped (OpenCV's JET: near = red, far = blue) with a scale bar, as
/// stereo_msgs/DisparityImage carries it: values below `min_disparity` (stereo_image_proc and BioBin
/// mark invalid pixels -1) are black. The bar runs down the right edge, max_disparity at the top, with
/// both ends labelled in px.
class DisparityPlot
{
public:
  static constexpr int kBarWidth = 40;  ///< [px] the scale bar and its labels

  /// Colour of `disparity` [px] for the range [min_disparity, max_disparity] (BGR; black when invalid).
  static cv::Vec3b colourOf(double disparity, double min_disparity, double max_disparity);

  /// Renders the CV_32FC1 `disparity` [px] into a CV_8UC3 image of `size` (at least 64 x 48): the map
  /// fitted into the left part, the bar in the rightmost kBarWidth px. Throws std::invalid_argument
  /// when `disparity` is not CV_32FC1 or the range is empty or not finite.
  cv::Mat render(const cv::Mat& disparity, double min_disparity, double max_disparity, cv::Size size) const;
};
}  // namespace biovision_monitor
