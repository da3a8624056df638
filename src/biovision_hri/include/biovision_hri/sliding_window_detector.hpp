#pragma once

#include <memory>
#include <vector>

#include <opencv2/core.hpp>

#include "biovision_hri/complex_cell_features.hpp"
#include "biovision_hri/detection.hpp"
#include "biovision_hri/linear_detector_model.hpp"

namespace biovision_hri
{
/// Multi-scale sliding-window detection with a linear model on the dense complex-cell block maps
/// (thesis §2.3, L378, L390-L392).
///
/// Scales: at each pyramid level the pooling cell grows from layout.cell_size to max_cell_size px (the
/// thesis' 6..10 px, window 42..70 px), then the image shrinks by cell_size / (max_cell_size + 1) and
/// the cells start again, so window sides follow each other without a gap (42, 49, ..., 70, 77, ...).
/// The first level is scaled so that the smallest window is `min_size` image px (upsampled when below
/// 42). Per level: complex cells once, one block map per cell size, then one dot product per window
/// (the weights applied block by block to the block map). Detections above `threshold` go through NMS.
class SlidingWindowDetector
{
public:
  struct Parameters
  {
    int stride = 2;             ///< window step [level px]. [1, 8]
    int max_cell_size = 10;     ///< largest pooling cell per level (thesis: 10) [level px]. >= layout.cell_size, <= 16
    double min_size = 42.0;     ///< smallest window side searched [image px]. [16, 1000]
    double max_size = 200.0;    ///< largest window side searched [image px]. >= min_size, <= 4000
    double threshold = 0.0;     ///< keep windows with w.x + b above this. [-5, 5]
    double nms_overlap = 0.5;   ///< IoU at which the weaker of two windows is dropped (thesis: 50%). (0, 1]
    int max_detections = 20;    ///< strongest kept after NMS. [1, 1000]
    int max_image_side = 2000;  ///< larger images (or regions) are refused [px]. [64, 8000]

    /// Throws std::invalid_argument naming the field and its range.
    void validate() const;
  };

  struct Statistics
  {
    long windows = 0;         ///< windows scored
    int levels = 0;           ///< pyramid levels
    double milliseconds = 0;  ///< wall time of detect()
  };

  /// Throws std::invalid_argument for an invalid model or parameters.
  SlidingWindowDetector(LinearDetectorModel model, const Parameters& parameters);

  /// Detections in `region` of a gray image (CV_32FC1 in [0, 1]); an empty region = the whole image.
  /// The region is clipped to the image; a region smaller than the smallest window gives none. Throws
  /// std::invalid_argument for a non-float image or a region larger than max_image_side.
  std::vector<Detection> detect(const cv::Mat& gray, cv::Rect region = cv::Rect(), Statistics* statistics = nullptr);

  /// Every window score before thresholding and NMS, for evaluation (FPPW on negative images).
  std::vector<Detection> scoreAllWindows(const cv::Mat& gray, Statistics* statistics = nullptr);

  /// The window features (FeatureLayout order, featureCount() values to `out`) of a detection of the last
  /// detect() or scoreAllWindows() on the whole image, read from that scan's dense block maps: exactly the
  /// vector the score came from, image context included (for hard-negative mining; a re-cropped patch
  /// would see its borders reflected instead). Throws std::out_of_range when the detection is not from
  /// the last scan's maps.
  void lastFeatures(const Detection& detection, float* out) const;

  /// Scores of the windows of one block map on the stride grid: (rows, cols) = number of window
  /// positions; entry (j, i) is the window with top-left pixel (i * stride, j * stride). Empty when no
  /// window fits.
  cv::Mat scoreMap(const BlockMap& map, int stride) const;

  void setParameters(const Parameters& parameters);
  const Parameters& parameters() const { return parameters_; }
  const LinearDetectorModel& model() const { return model_; }
  ComplexCellFeatures& features() { return features_; }

private:
  std::vector<Detection> scan(const cv::Mat& gray, Statistics* statistics, bool keep_all);

  LinearDetectorModel model_;
  Parameters parameters_;
  ComplexCellFeatures features_;
  /// Block maps per (level, cell size), kept between frames so their memory is reused.
  std::vector<BlockMap> maps_;
};
}  // namespace biovision_hri
