#pragma once

#include <vector>

#include <opencv2/core.hpp>

#include "biovision_monitor/monitor_parameters.hpp"
#include "biovision_monitor/plot_inputs.hpp"

namespace biovision_monitor
{
/// The phase plot of an attractor-dynamics controller, as the thesis draws it (Fig. 4.7 for the head,
/// Fig. 5.6 for the base): dphi/dt [rad/s] over phi [rad], -90 deg (the robot's right) at the plot's left
/// edge to +90 deg (its left) at the right edge, with
///  - each section's attractor (green, falling through zero at its angle) and repeller (red, rising
///    through zero), rebuilt from the state's strengths with the AttractorModel (biovision_attractor's
///    forcelets), and their sum (blue, thick);
///  - the sum's zero crossings: stable ones (attractors) as filled green discs, unstable ones (repellers)
///    as hollow red circles, on the zero line;
///  - the current angle as an orange dot at (angle, rate) -- the controller's own rate, not the model's;
///  - the target as a dashed vertical line, the 9 section boundaries as a grey grid.
/// The model is the controller's form with its default constants; the head's softmax weighting and
/// persistence bonus are not in the message, so the sum curve shows the shape, the dot the truth.
class AttractorPlot
{
public:
  /// Where values land in a rendered image: plot area and scales.
  struct Axes
  {
    cv::Rect area;                                     ///< the plot's inner rectangle [px]
    double angle_lo = -M_PI / 2, angle_hi = M_PI / 2;  ///< [rad] at the area's left and right edges
    double rate_max = 1.0;                             ///< [rad/s] at the area's top (and -rate_max at its bottom)
    /// Pixel column of `angle` [rad] (+ = left of the robot, drawn to the right: phi grows to the right).
    int column(double angle) const;
    /// Pixel row of `rate` [rad/s] (positive up).
    int row(double rate) const;
  };

  explicit AttractorPlot(const AttractorModel& model) : model_(model) {}

  /// Renders `state` into a CV_8UC3 image of `size` (at least 64 x 48). `axes` receives the mapping.
  cv::Mat render(const AttractorView& state, cv::Size size, Axes* axes = nullptr) const;

  /// The model's dphi/dt [rad/s] at `phi` for `state`: the sum of every section's forcelets.
  double sum(const AttractorView& state, double phi) const;
  /// One section's attractor, and its repeller, at `phi` [rad/s].
  double attractor(const AttractorView& state, size_t section, double phi) const;
  double repeller(const AttractorView& state, size_t section, double phi) const;

  struct Crossing
  {
    double angle;  ///< [rad]
    bool stable;   ///< falling through zero = an attractor
  };
  /// The sum's zero crossings over [-90, +90] deg, sampled every 0.25 deg and refined by bisection.
  std::vector<Crossing> zeroCrossings(const AttractorView& state) const;

private:
  AttractorModel model_;
};
}  // namespace biovision_monitor
