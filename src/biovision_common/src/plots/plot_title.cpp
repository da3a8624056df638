#include "biovision_common/plot_title.hpp"

#include <algorithm>

#include <opencv2/imgproc.hpp>

namespace biovision_common
{
void drawTitle(cv::Mat& image, const std::string& text)
{
  if (image.empty())
    return;
  const int h = std::min(kTitleHeight, image.rows);
  cv::Mat strip = image(cv::Rect(0, 0, image.cols, h));
  strip = strip * 0.35;
  cv::putText(image, text, cv::Point(4, h - 5), cv::FONT_HERSHEY_SIMPLEX, 0.45, cv::Scalar(255, 255, 255), 1,
              cv::LINE_AA);
}
}  // namespace biovision_common
