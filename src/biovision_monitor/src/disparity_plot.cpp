#include "biovision_monitor/disparity_plot.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include <opencv2/imgproc.hpp>

#include "biovision_monitor/drawing.hpp"

namespace biovision_monitor
{
namespace
{
cv::Mat jetLut()
{
  cv::Mat ramp(1, 256, CV_8UC1);
  for (int i = 0; i < 256; ++i)
    ramp.at<uchar>(i) = uchar(i);
  cv::Mat lut;
  cv::applyColorMap(ramp, lut, cv::COLORMAP_JET);
  return lut;
}

const cv::Mat& lut()
{
  static const cv::Mat table = jetLut();
  return table;
}

// Valid disparities take levels 1..255 (0 marks invalid pixels, drawn black).
uchar levelOf(double d, double lo, double hi)
{
  return uchar(1 + std::clamp((d - lo) * 254.0 / (hi - lo) + 0.5, 0.0, 254.0));
}
}  // namespace

cv::Vec3b DisparityPlot::colourOf(double d, double lo, double hi)
{
  if (!(d >= lo) || !std::isfinite(d))
    return cv::Vec3b(0, 0, 0);
  return lut().at<cv::Vec3b>(levelOf(d, lo, hi));
}

cv::Mat DisparityPlot::render(const cv::Mat& disparity, double lo, double hi, cv::Size size) const
{
  if (disparity.type() != CV_32FC1)
    throw std::invalid_argument("DisparityPlot: the disparity map must be CV_32FC1");
  if (!(std::isfinite(lo) && std::isfinite(hi) && hi > lo))
    throw std::invalid_argument("DisparityPlot: need finite min_disparity < max_disparity, got " + formatNumber(lo, 2) +
                                " and " + formatNumber(hi, 2));
  size.width = std::max(size.width, 64 + kBarWidth);
  size.height = std::max(size.height, 48);
  cv::Mat levels(disparity.size(), CV_8UC1);
  const float flo = float(lo);
  for (int r = 0; r < disparity.rows; ++r)
  {
    const float* d = disparity.ptr<float>(r);
    uchar* out = levels.ptr<uchar>(r);
    for (int c = 0; c < disparity.cols; ++c)
      out[c] = (d[c] >= flo && std::isfinite(d[c])) ? levelOf(d[c], lo, hi) : 0;
  }
  cv::Mat colour;
  cv::applyColorMap(levels, colour, cv::COLORMAP_JET);
  colour.setTo(cv::Scalar(0, 0, 0), levels == 0);

  cv::Mat image(size, CV_8UC3, cv::Scalar(0, 0, 0));
  fitInto(colour, cv::Size(size.width - kBarWidth, size.height))
      .copyTo(image(cv::Rect(0, 0, size.width - kBarWidth, size.height)));
  // The bar: max at the top, min at the bottom.
  const int top = 22, bottom = size.height - 14, x0 = size.width - kBarWidth + 4, x1 = x0 + 12;
  for (int y = top; y <= bottom; ++y)
  {
    const double v = hi - (hi - lo) * (y - top) / std::max(1, bottom - top);
    const cv::Vec3b c = colourOf(v, lo, hi);
    cv::line(image, {x0, y}, {x1, y}, cv::Scalar(c[0], c[1], c[2]), 1);
  }
  cv::rectangle(image, {x0 - 1, top - 1}, {x1 + 1, bottom + 1}, cv::Scalar(255, 255, 255), 1);
  cv::putText(image, formatNumber(hi, 0), {x0 - 2, top - 4}, cv::FONT_HERSHEY_SIMPLEX, 0.33, cv::Scalar(255, 255, 255),
              1, cv::LINE_AA);
  cv::putText(image, formatNumber(lo, 0), {x0 - 2, bottom + 12}, cv::FONT_HERSHEY_SIMPLEX, 0.33,
              cv::Scalar(255, 255, 255), 1, cv::LINE_AA);
  cv::putText(image, "px", {x1 + 3, (top + bottom) / 2}, cv::FONT_HERSHEY_SIMPLEX, 0.33, cv::Scalar(255, 255, 255), 1,
              cv::LINE_AA);
  return image;
}
}  // namespace biovision_monitor
