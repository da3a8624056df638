#pragma once

#include <vector>

#include <opencv2/core.hpp>

namespace biovision_v1
{
/// Simple-cell responses of one scale, on that scale's grid: sample (j, k) of the grid is image pixel
/// (decimation * k, decimation * j), and the values there equal the full-resolution convolution.
struct ScaleResponses
{
  double wavelength = 0.0;    ///< lambda [image px]
  int decimation = 1;         ///< grid step [image px]
  std::vector<cv::Mat> even;  ///< R^E_{s,i}, CV_32F, one per orientation
  std::vector<cv::Mat> odd;   ///< R^O_{s,i}, CV_32F, one per orientation

  /// lambda in grid samples: what the filters look like on this grid.
  double gridWavelength() const { return wavelength / decimation; }
  cv::Size gridSize() const { return even.empty() ? cv::Size() : even.front().size(); }
  int orientations() const { return static_cast<int>(even.size()); }
  /// Complex cell C_{s,i} = sqrt(R^E^2 + R^O^2), CV_32F on the grid.
  cv::Mat complexCell(int orientation) const;
  /// All complex cells of the scale.
  std::vector<cv::Mat> complexCells() const;
  /// Grid coordinates -> image coordinates [px].
  cv::Point2f toImage(const cv::Point2f& grid) const { return grid * static_cast<float>(decimation); }
};
}  // namespace biovision_v1
