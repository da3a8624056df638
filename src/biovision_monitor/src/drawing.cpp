#include "biovision_monitor/drawing.hpp"

#include <algorithm>
#include <cstdio>
#include <stdexcept>
#include <string>

#include <opencv2/imgproc.hpp>

namespace biovision_monitor
{
cv::Mat fitInto(const cv::Mat& image, cv::Size size, double* scale, cv::Point2d* offset)
{
  if (size.width < 1 || size.height < 1)
    throw std::invalid_argument("fitInto: a tile of " + std::to_string(size.width) + " x " +
                                std::to_string(size.height) + " px");
  cv::Mat tile(size, CV_8UC3, cv::Scalar(0, 0, 0));
  if (image.empty())
    return tile;
  cv::Mat colour;
  if (image.channels() == 1)
    cv::cvtColor(image, colour, cv::COLOR_GRAY2BGR);
  else
    colour = image;
  const double s = std::min(double(size.width) / colour.cols, double(size.height) / colour.rows);
  const int w = std::max(1, int(colour.cols * s)), h = std::max(1, int(colour.rows * s));
  const int x = (size.width - w) / 2, y = (size.height - h) / 2;
  cv::Mat resized;
  if (w == colour.cols && h == colour.rows)
    resized = colour;
  else
    cv::resize(colour, resized, cv::Size(w, h), 0, 0, s < 1 ? cv::INTER_AREA : cv::INTER_NEAREST);
  resized.copyTo(tile(cv::Rect(x, y, w, h)));
  if (scale)
    *scale = s;
  if (offset)
    *offset = cv::Point2d(x, y);
  return tile;
}

void putTextCentred(cv::Mat& image, const std::string& text, int y, const cv::Scalar& colour, double scale)
{
  int baseline = 0;
  cv::Size size = cv::getTextSize(text, cv::FONT_HERSHEY_SIMPLEX, scale, 1, &baseline);
  while (size.width > image.cols - 8 && scale > 0.25)
  {
    scale *= 0.9;
    size = cv::getTextSize(text, cv::FONT_HERSHEY_SIMPLEX, scale, 1, &baseline);
  }
  cv::putText(image, text, cv::Point((image.cols - size.width) / 2, y), cv::FONT_HERSHEY_SIMPLEX, scale, colour, 1,
              cv::LINE_AA);
}

cv::Mat noDataTile(const std::string& topic, cv::Size size)
{
  cv::Mat tile(size, CV_8UC3, colours::kNoData);
  putTextCentred(tile, "no data on", size.height / 2 - 4, colours::kText, 0.55);
  putTextCentred(tile, topic, size.height / 2 + 20, colours::kText, 0.55);
  return tile;
}

cv::Point textOriginInside(const cv::Mat& image, const std::string& text, double scale, cv::Point wanted, int top)
{
  if (!(scale > 0 && scale <= 100))
    throw std::invalid_argument("textOriginInside: font scale " + formatNumber(scale, 3) + " outside (0, 100]");
  int baseline = 0;
  const cv::Size size = cv::getTextSize(text, cv::FONT_HERSHEY_SIMPLEX, scale, 1, &baseline);
  top = std::clamp(top, 0, image.rows);  // 64-bit sums below: no overflow whatever the ints
  const long long x = std::max(0LL, std::min<long long>(wanted.x, 0LL + image.cols - size.width - 1));
  const long long y = std::max<long long>(0LL + top + size.height + 1,
                                          std::min<long long>(wanted.y, 0LL + image.rows - baseline - 1));
  return {static_cast<int>(x), static_cast<int>(y)};
}

cv::Rect putLabel(cv::Mat& image, const std::string& text, double scale, cv::Point wanted, const cv::Scalar& colour,
                  int top)
{
  const cv::Point at = textOriginInside(image, text, scale, wanted, top);
  int baseline = 0;
  const cv::Size size = cv::getTextSize(text, cv::FONT_HERSHEY_SIMPLEX, scale, 1, &baseline);
  const cv::Rect plate = cv::Rect(at.x - 2, at.y - size.height - 2, size.width + 4, size.height + baseline + 4) &
                         cv::Rect(0, 0, image.cols, image.rows);
  cv::rectangle(image, plate, colours::kLabelPlate, cv::FILLED);
  cv::putText(image, text, at, cv::FONT_HERSHEY_SIMPLEX, scale, colour, 1, cv::LINE_AA);
  return plate;
}

std::string formatNumber(double value, int digits)
{
  char buffer[64];
  std::snprintf(buffer, sizeof buffer, "%.*f", digits, value);
  return buffer;
}
}  // namespace biovision_monitor
