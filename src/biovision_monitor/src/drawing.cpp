#include "biovision_monitor/drawing.hpp"

#include <algorithm>
#include <cstdio>

#include <opencv2/imgproc.hpp>

namespace biovision_monitor
{
cv::Mat fitInto(const cv::Mat& image, cv::Size size, double* scale, cv::Point2d* offset)
{
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
  int baseline = 0;
  const cv::Size size = cv::getTextSize(text, cv::FONT_HERSHEY_SIMPLEX, scale, 1, &baseline);
  const int x = std::max(0, std::min(wanted.x, image.cols - size.width - 1));
  const int y = std::max(top + size.height + 1, std::min(wanted.y, image.rows - baseline - 1));
  return {x, y};
}

std::string formatNumber(double value, int digits)
{
  char buffer[64];
  std::snprintf(buffer, sizeof buffer, "%.*f", digits, value);
  return buffer;
}
}  // namespace biovision_monitor
