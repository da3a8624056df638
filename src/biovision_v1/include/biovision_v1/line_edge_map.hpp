#pragma once

#include <cstdint>

#include <opencv2/core.hpp>

namespace biovision_v1
{
/// Line/edge events of one scale on its grid (sample (j, k) = image pixel (d*k, d*j)).
struct LineEdgeMap
{
  enum Event : std::uint8_t
  {
    kNone = 0,
    kLinePositive = 1,  ///< bright line: R^E maximum, R^O zero crossing
    kLineNegative = 2,  ///< dark line: R^E minimum, R^O zero crossing
    kEdgePositive = 3,  ///< dark-to-bright along the normal n_i: R^O maximum, R^E zero crossing
    kEdgeNegative = 4,  ///< bright-to-dark along the normal n_i: R^O minimum, R^E zero crossing
  };

  double wavelength = 0.0;  ///< lambda [image px]
  int decimation = 1;       ///< grid step [image px]
  cv::Mat events;           ///< CV_8U, Event codes
  cv::Mat orientation;      ///< CV_8U, orientation channel i of the event (valid where events != 0)
  cv::Mat confidence;       ///< CV_32F, inhibited complex-cell response / scale contrast, [0, 1]

  /// True where there is any event: the barrier map the stereo spatial filter uses.
  cv::Mat mask() const { return events != kNone; }
};
}  // namespace biovision_v1
