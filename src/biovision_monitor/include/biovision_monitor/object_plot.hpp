#pragma once

#include <vector>

#include <opencv2/core.hpp>

#include "biovision_monitor/plot_inputs.hpp"

namespace biovision_monitor
{
/// The camera image with the recognised objects boxed (green) and labelled "<label> <score>", fitted
/// into the tile. Object boxes are in the image's px.
class ObjectPlot
{
public:
  /// `image`: CV_8UC1 or CV_8UC3 (BGR). An empty image gives a black tile with the labels only.
  cv::Mat render(const cv::Mat& image, const std::vector<ObjectView>& objects, cv::Size size) const;
};
}  // namespace biovision_monitor
