#include "biovision_monitor/saliency_plot.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

#include <opencv2/imgproc.hpp>

#include "biovision_monitor/drawing.hpp"

namespace biovision_monitor
{
namespace
{
const cv::Scalar kInhibition(255, 0, 255);  // magenta: the inhibition-of-return cross and its label
}  // namespace

SaliencyPlot::SaliencyPlot(double threshold) : threshold_(threshold)
{
  if (!(threshold >= 0 && threshold <= 1))
    throw std::invalid_argument("SaliencyPlot: threshold " + formatNumber(threshold, 3) + " outside [0, 1]");
}

cv::Mat SaliencyPlot::renderMap(const cv::Mat& map, cv::Size size) const
{
  if (map.type() != CV_32FC1)
    throw std::invalid_argument("SaliencyPlot: the saliency map must be CV_32FC1");
  double lo = 0, hi = 0;
  cv::minMaxLoc(map, &lo, &hi);
  cv::Mat grey;
  map.convertTo(grey, CV_8U, hi > 0 && std::isfinite(hi) ? 255.0 / hi : 0.0);
  return fitInto(grey, size);
}

cv::Mat SaliencyPlot::mask(const cv::Mat& map) const
{
  if (map.type() == CV_8UC1)
    return map != 0;
  if (map.type() != CV_32FC1)
    throw std::invalid_argument("SaliencyPlot: a saliency map must be CV_32FC1 or CV_8UC1");
  double lo = 0, hi = 0;
  cv::minMaxLoc(map, &lo, &hi);
  if (!(hi > 0) || !std::isfinite(hi))
    return cv::Mat::zeros(map.size(), CV_8UC1);
  return map >= threshold_ * hi;
}

cv::Mat SaliencyPlot::renderThresholded(const cv::Mat& map, const std::vector<RegionView>& regions, int image_width,
                                        int image_height, cv::Size size) const
{
  const cv::Mat salient = mask(map);
  cv::Mat grey(map.size(), CV_8UC1, cv::Scalar(40));
  grey.setTo(255, salient);
  double scale = 1.0;
  cv::Point2d offset;
  cv::Mat image = fitInto(grey, size, &scale, &offset);
  const double sx = scale * (image_width > 0 ? double(map.cols) / image_width : 1.0);
  const double sy = scale * (image_height > 0 ? double(map.rows) / image_height : 1.0);
  // Later ranks first, so the attended region is drawn on top.
  std::vector<RegionView> ordered(regions);
  std::sort(ordered.begin(), ordered.end(), [](const RegionView& a, const RegionView& b) { return a.rank > b.rank; });
  for (const RegionView& r : ordered)
  {
    // In double, clamped: a box of INT_MAX px would overflow the int sums.
    const auto px = [](double v) { return static_cast<int>(std::clamp(v, -1e6, 1e6)); };
    const cv::Rect box(cv::Point(px(offset.x + double(r.box.x) * sx), px(offset.y + double(r.box.y) * sy)),
                       cv::Point(px(offset.x + (double(r.box.x) + r.box.width) * sx),
                                 px(offset.y + (double(r.box.y) + r.box.height) * sy)));
    const bool attended = r.rank == 0;
    const cv::Scalar colour = attended ? cv::Scalar(0, 0, 255) : cv::Scalar(0, 220, 255);
    cv::rectangle(image, box, colour, attended ? 2 : 1, cv::LINE_AA);
    const bool inhibited = r.inhibition > 0.01 && std::isfinite(r.inhibition);
    if (inhibited)
    {
      const int thickness = 1 + int(std::lround(2 * std::min(1.0, r.inhibition)));
      cv::line(image, box.tl(), box.br(), kInhibition, thickness, cv::LINE_AA);
      cv::line(image, {box.x, box.br().y}, {box.br().x, box.y}, kInhibition, thickness, cv::LINE_AA);
    }
    // Labels after the cross, on dark plates (yellow and magenta were unreadable on the white blobs and under
    // the cross's lines), inside the image and below a panel's tile title wherever the box reaches.
    putLabel(image, "#" + std::to_string(r.rank), 0.4, {box.x + 2, box.y + 12}, colour, kTitleHeight);
    if (inhibited)
    {
      const std::string ior = "IoR " + formatNumber(r.inhibition, 1);
      int baseline = 0;
      const int width = cv::getTextSize(ior, cv::FONT_HERSHEY_SIMPLEX, 0.35, 1, &baseline).width;
      putLabel(image, ior, 0.35, {box.x + (box.width - width) / 2, box.br().y - 3}, kInhibition, kTitleHeight);
    }
  }
  return image;
}
}  // namespace biovision_monitor
