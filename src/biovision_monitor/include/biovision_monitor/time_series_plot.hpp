#pragma once

#include <string>
#include <vector>

#include <opencv2/core.hpp>

namespace biovision_monitor
{
/// A line plot of one or more quantities of one unit over time with labelled events (e.g. the head's pan
/// and tilt over a run with its fixations marked), for run reports.
class TimeSeriesPlot
{
public:
  /// An event at time t [s]: a vertical dashed line and its label (in one of 4 rows of a band above the
  /// plot, clear of the curves; left of the line near the right edge, left out where the rows are full:
  /// labelRows()).
  struct Mark
  {
    double t;
    std::string label;
  };
  /// Where values land in a rendered image.
  struct Axes
  {
    cv::Rect area;
    cv::Rect label_band;  ///< the marks' labels, above `area` (empty without marks)
    double t0 = 0, t1 = 1, y0 = -1, y1 = 1;
    int column(double t) const;
    int row(double y) const;
  };

  /// One curve: its samples (x = time [s], y = value), its colour and its name in the legend.
  struct Series
  {
    std::string label;
    cv::Scalar colour;
    std::vector<cv::Point2d> points;
  };

  /// Renders every series on shared axes (the ranges of all their finite samples) into a CV_8UC3 image of
  /// `size` (at least 160 x 120), with a legend of the labelled series at the top right; otherwise as below.
  cv::Mat render(const std::vector<Series>& series, const std::vector<Mark>& marks, const std::string& title,
                 cv::Size size, Axes* axes = nullptr) const;

  /// The row (0 .. rows - 1) of each mark's label, given the labels' horizontal spans [start, end) in px in
  /// time order: the first row whose last label ends at least `gap` px before this one starts; -1 when no
  /// row has room (the label is left out, its mark's line stays). Dense fixations had put labels on top of
  /// each other.
  static std::vector<int> labelRows(const std::vector<cv::Range>& spans, int rows, int gap = 3);

  /// Renders `points` (x = time [s], y = value; non-finite ones skipped) into a CV_8UC3 image of `size`
  /// (at least 160 x 120): axes with the time and value ranges labelled, `title` at the top, the marks.
  /// Empty `points` gives the frame and "no samples".
  cv::Mat render(const std::vector<cv::Point2d>& points, const std::vector<Mark>& marks, const std::string& title,
                 cv::Size size, Axes* axes = nullptr) const;
};
}  // namespace biovision_monitor
