#pragma once

#include <vector>

#include <opencv2/core.hpp>

#include "biovision_monitor/plot_inputs.hpp"

namespace biovision_monitor
{
/// The saliency panels of the thesis's Fig. 5.1: the fused map, and the thresholded map with the
/// Focus-of-Attention regions drawn (rank 0, attended now, in red and thick; the others yellow; each
/// labelled with its rank) and the Inhibition-of-Return marks (a magenta cross over a region, its
/// thickness growing with the inhibition, labelled "IoR x.x").
class SaliencyPlot
{
public:
  /// `threshold`: fraction of the map's maximum kept as salient (thesis L912/L1222: 0.15). Throws
  /// std::invalid_argument outside [0, 1].
  explicit SaliencyPlot(double threshold);

  /// The map (CV_32FC1, saliency >= 0) scaled by its maximum to grey, fitted into `size`. Throws
  /// std::invalid_argument for another type.
  cv::Mat renderMap(const cv::Mat& map, cv::Size size) const;

  /// The binary salient mask of `map`: CV_32FC1 -> pixels >= threshold * max (none when the max is 0);
  /// CV_8UC1 (saliency/thresholded) -> its non-zero pixels. Throws std::invalid_argument otherwise.
  cv::Mat mask(const cv::Mat& map) const;

  /// The thresholded map (salient white on dark grey) with `regions` drawn, fitted into `size`. Region
  /// boxes are in px of an image of image_width x image_height (0 = the map's size).
  cv::Mat renderThresholded(const cv::Mat& map, const std::vector<RegionView>& regions, int image_width,
                            int image_height, cv::Size size) const;

private:
  double threshold_;
};
}  // namespace biovision_monitor
