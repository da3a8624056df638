#pragma once

#include <string>
#include <vector>

#include <opencv2/core.hpp>

#include "biovision_common/grid_view.hpp"

namespace biovision_common
{
/// The path a base drove, seen from above over a map (thesis Figs. 5.8-5.10: the map built on the way,
/// the path, home and the objects), for run reports and evaluation tools (biovision_monitor's run_report,
/// biovision_tasks' mission_eval, biovision_attractor's navigation_eval): map frame, metres, +x right and
/// +y up, one scale for both axes, a 1 m scale bar. OpenCV only.
class PathPlot
{
public:
  /// Colours (BGR) of the path (blue), its start (green) and its end (red).
  static const cv::Scalar kPathColour, kStartColour, kEndColour;

  struct Mark
  {
    cv::Point2d position;  ///< [m], map frame
    std::string label;     ///< drawn beside the mark
    cv::Scalar colour;     ///< BGR
    bool filled = true;    ///< a disc, else a ring (e.g. where the memory put an object vs where it is)
  };

  /// A CV_8UC3 image of `size` on white: the grid (when not empty; cell (0, 0)'s corner at `origin` [m],
  /// the shades of GridView::toImage) and the path (polyline 2 px, the end a 5 px disc, the start a 9 px ring
  /// drawn over the marks so a mark at the start, e.g. home, leaves it visible) and marks
  /// (6 px discs or rings, the first 500 labelled), fitted together with a 0.5 m margin below a 24 px title strip. An
  /// empty grid and path give the marks alone (or a blank titled tile). Points not finite or beyond 1e6 m
  /// (and a grid placed there) are left out. A 1 m scale bar bottom left and a legend (path, start, end)
  /// bottom right, left out where it would reach the bar. Throws std::invalid_argument for a
  /// grid whose data does not match its size, a non-positive resolution of a non-empty grid, or a size
  /// smaller than 64 x 64 px.
  cv::Mat render(const GridView& grid, cv::Point2d origin, const std::vector<cv::Point2d>& path,
                 const std::vector<Mark>& marks, const std::string& title, cv::Size size) const;

  /// Where a mark's label of `text` px goes (putText's origin, the text's bottom left). The first choice
  /// is right of and above the mark at `mark`, moved to its left / below it where it would leave the image
  /// or cover the `top` px title strip (a target at the map's edge kept its label cut off); the other
  /// three places beside the mark, then the four one text line further out, are tried when the first
  /// overlaps a rectangle of `taken` (marks and
  /// labels already drawn) or covers pixels set in `avoid` (CV_8UC1 of the image's size, e.g. the path;
  /// empty = none): the place overlapping least wins, the earlier on a tie (labels had been drawn over each
  /// other and over the path).
  static cv::Point labelOrigin(cv::Point mark, cv::Size text, cv::Size image, int top,
                               const std::vector<cv::Rect>& taken = {}, const cv::Mat& avoid = cv::Mat());
};
}  // namespace biovision_common
