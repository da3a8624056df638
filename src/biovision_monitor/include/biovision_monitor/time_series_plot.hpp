#pragma once

#include <string>
#include <vector>

#include <opencv2/core.hpp>

namespace biovision_monitor
{
/// A line plot of one quantity over time with labelled events (e.g. the head's pan over a run with its
/// fixations marked), for run reports.
class TimeSeriesPlot
{
public:
  /// An event at time t [s]: a vertical dashed line and its label.
  struct Mark
  {
    double t;
    std::string label;
  };
  /// Where values land in a rendered image.
  struct Axes
  {
    cv::Rect area;
    double t0 = 0, t1 = 1, y0 = -1, y1 = 1;
    int column(double t) const;
    int row(double y) const;
  };

  /// Renders `points` (x = time [s], y = value; non-finite ones skipped) into a CV_8UC3 image of `size`
  /// (at least 160 x 120): axes with the time and value ranges labelled, `title` at the top, the marks.
  /// Empty `points` gives the frame and "no samples".
  cv::Mat render(const std::vector<cv::Point2d>& points, const std::vector<Mark>& marks, const std::string& title,
                 cv::Size size, Axes* axes = nullptr) const;
};
}  // namespace biovision_monitor
