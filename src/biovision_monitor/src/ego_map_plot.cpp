#include "biovision_monitor/ego_map_plot.hpp"

#include <algorithm>
#include <cmath>
#include <vector>

#include <opencv2/imgproc.hpp>

#include "biovision_monitor/drawing.hpp"

namespace biovision_monitor
{
cv::Point EgoMapPlot::Axes::point(double angle, double distance) const
{
  return cv::Point(int(std::lround(robot.x - distance * pixels_per_metre * std::sin(angle))),
                   int(std::lround(robot.y - distance * pixels_per_metre * std::cos(angle))));
}

namespace
{
// The slice of `axes` between angles a0 and a1 [rad] and distances r0 and r1 [m] as a polygon.
std::vector<cv::Point> slice(const EgoMapPlot::Axes& axes, double a0, double a1, double r0, double r1)
{
  std::vector<cv::Point> points;
  const int steps = std::max(2, int(std::ceil((a1 - a0) / (M_PI / 90))));
  for (int k = 0; k <= steps; ++k)
    points.push_back(axes.point(a0 + (a1 - a0) * k / steps, r1));
  for (int k = steps; k >= 0; --k)
    points.push_back(axes.point(a0 + (a1 - a0) * k / steps, r0));
  return points;
}

cv::Scalar faded(const cv::Scalar& colour, double confidence)
{
  const double c = std::clamp(std::isfinite(confidence) ? confidence : 0.0, 0.0, 1.0);
  const double keep = 0.25 + 0.75 * c;  // an unconfirmed sector stays visible
  return colour * keep + colours::kBackground * (1 - keep);
}
}  // namespace

cv::Mat EgoMapPlot::render(const EgoMapView& stm, cv::Size size, Axes* axes_out) const
{
  size.width = std::max(size.width, 64);
  size.height = std::max(size.height, 48);
  cv::Mat image(size, CV_8UC3, colours::kBackground);
  Axes axes;
  axes.robot = cv::Point2d((size.width - 1) / 2.0, size.height - 12.0);
  const double radius_px = std::min((size.width - 8) / 2.0, size.height - 12.0 - 20.0);
  const bool usable = stm.max_range > 0 && std::isfinite(stm.max_range) && !stm.section_angles.empty();
  const double range = usable ? stm.max_range : 1.0;
  axes.pixels_per_metre = radius_px / range;

  if (usable)
  {
    double width = stm.section_width;
    if (!(width > 0) && stm.section_angles.size() > 1)
      width = std::abs(stm.section_angles[1] - stm.section_angles[0]);
    if (!(width > 0))
      width = M_PI / 9;
    for (size_t i = 0; i < stm.section_angles.size(); ++i)
    {
      const double centre = stm.section_angles[i];
      if (!std::isfinite(centre))
        continue;
      const double d = i < stm.obstacle_distance.size() ? stm.obstacle_distance[i] : INFINITY;
      const double confidence = i < stm.confidence.size() ? stm.confidence[i] : 1.0;
      const double a0 = centre - width / 2, a1 = centre + width / 2;
      const double free_to = std::isfinite(d) ? std::clamp(d, 0.0, range) : range;
      const std::vector<std::vector<cv::Point>> free_part{slice(axes, a0, a1, 0.0, free_to)};
      cv::fillPoly(image, free_part, faded(cv::Scalar(170, 230, 170), confidence), cv::LINE_AA);
      if (std::isfinite(d) && d < range)
      {
        const std::vector<std::vector<cv::Point>> obstacle{slice(axes, a0, a1, free_to, range)};
        cv::fillPoly(image, obstacle, faded(cv::Scalar(0, 0, 0), confidence), cv::LINE_AA);
      }
      cv::polylines(image, slice(axes, a0, a1, 0.0, range), true, colours::kGrid, 1, cv::LINE_AA);
    }
  }
  for (int k = 1; k <= 4; ++k)
  {
    const int r = int(std::lround(radius_px * k / 4));
    cv::ellipse(image, cv::Point(axes.robot), cv::Size(r, r), 0, 180, 360, cv::Scalar(150, 150, 150), 1, cv::LINE_AA);
  }
  cv::putText(image, usable ? formatNumber(range, 1) + " m" : std::string("empty STM"),
              {int(axes.robot.x + radius_px) - 36, int(axes.robot.y) + 10}, cv::FONT_HERSHEY_SIMPLEX, 0.35,
              colours::kAxis, 1, cv::LINE_AA);
  cv::circle(image, cv::Point(axes.robot), 4, colours::kCurrent, cv::FILLED, cv::LINE_AA);
  cv::line(image, cv::Point(axes.robot), axes.point(0.0, range * 0.12), colours::kCurrent, 2, cv::LINE_AA);
  if (axes_out)
    *axes_out = axes;
  return image;
}
}  // namespace biovision_monitor
