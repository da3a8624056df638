#pragma once

#include <opencv2/core.hpp>

#include "biovision_monitor/plot_inputs.hpp"

namespace biovision_monitor
{
/// The short-term memory as radial slices, seen from above (thesis Fig. 5.3): the robot at the bottom
/// centre facing up, +angle (left) drawn to the left. Each section is a slice of its width: light green
/// from the robot out to the nearest obstacle (free), black from the obstacle out to max_range (the
/// thesis's "black slice = obstacle"); a section with nothing in range is light green to the rim. Faded
/// towards white as the section's confidence falls. Range rings every quarter of max_range.
class EgoMapPlot
{
public:
  /// Where values land in a rendered image.
  struct Axes
  {
    cv::Point2d robot;  ///< the robot's position [px]
    double pixels_per_metre = 1.0;
    /// The pixel at `angle` [rad, + = left] and `distance` [m] from the robot.
    cv::Point point(double angle, double distance) const;
  };

  /// Renders `stm` into a CV_8UC3 image of `size` (at least 64 x 48); `axes` receives the mapping. A
  /// map without sections or with max_range <= 0 gives the rings only and "empty STM".
  cv::Mat render(const EgoMapView& stm, cv::Size size, Axes* axes = nullptr) const;
};
}  // namespace biovision_monitor
