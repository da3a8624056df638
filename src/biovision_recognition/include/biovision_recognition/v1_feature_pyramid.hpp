#pragma once

#include <vector>

#include <opencv2/core.hpp>

#include "biovision_v1/keypoint.hpp"
#include "biovision_v1/keypoint_detector.hpp"
#include "biovision_v1/scale_responses.hpp"
#include "biovision_v1/simple_cell_bank.hpp"

namespace biovision_recognition
{
/// V1 simple cells at half-octave scales, computed as one lambda = 4 Gabor bank on a half-octave image
/// pyramid: level k is the image shrunk by 2^(k/2), so its cells are the image's cells at
/// lambda_k = 4 * 2^(k/2) (4, 5.7, 8, 11.3, 16, 22.6, 32, ...: the source's {4, 6, 8, 12, 16, 24, 32}
/// within 6%). Why a pyramid and not one bank per wavelength on the image: a descriptor at keypoint
/// scale lambda needs cells at lambda * 2^(j/2), up to 8 lambda; on the pyramid every one of them is a
/// small lambda = 4 convolution, computed once per image and shared by every keypoint and by the
/// keypoint detector itself.
///
/// Per level it also keeps the even and odd responses max-pooled over a disk (the descriptor's pooling
/// fields), so a descriptor samples one value per field instead of scanning the field.
class V1FeaturePyramid
{
public:
  struct Parameters
  {
    int orientations = 8;  ///< N_theta. 4..12
    double sigma_per_wavelength = 0.56;
    double aspect_ratio = 0.5;
    double support_sigmas = 3.5;
    int max_levels = 16;       ///< half-octave levels kept. >= 1
    int min_level_size = 12;   ///< stop when a level's smaller side drops below this [px]
    int pooling_diameter = 4;  ///< disk the pooled maps take the maximum over [level px]. 1..16
    int pooling_phases = 4;    ///< 2: max of the signed even/odd responses; 4: also max of their negatives
    /// Levels' DFTs on SimpleCellBank's coarse sizes, for images whose size changes every call (ObjectRecognizer's
    /// region crops: each new size rebuilt the kernel spectra, 2.5 sets per region in loop_bench). Same
    /// responses up to rounding; off for fixed sizes (training, evaluation), which only lose by it.
    bool coarse_dft_sizes = false;
    biovision_v1::KeypointDetector::Parameters keypoints;
  };

  /// Gabor wavelength every level is filtered with [level px].
  static constexpr double kWavelength = 4.0;

  V1FeaturePyramid() : V1FeaturePyramid(Parameters()) {}
  explicit V1FeaturePyramid(const Parameters& parameters);

  /// gray: CV_32FC1 in [0, 1] (biovision_v1::InputImage). Rebuilds every level's image; the cells (responses,
  /// pooled maps) of levels from first_level on only: a query that samples no finer level skips the finest
  /// ones' filtering (level 0 alone is half the work). Levels are filtered independently, so a level's cells
  /// do not depend on first_level. Throws std::invalid_argument for an empty or non-CV_32FC1 image or a
  /// negative first_level.
  void build(const cv::Mat& gray, int first_level = 0);

  int levels() const { return static_cast<int>(levels_.size()); }
  /// The finest level whose cells the last build() computed.
  int firstLevel() const { return first_level_; }
  cv::Size imageSize() const { return levels_.empty() ? cv::Size() : levels_.front().image.size(); }
  /// Image wavelength of the cells of level k [image px].
  static double wavelengthOfLevel(int k);
  /// The level whose cells are nearest to wavelength lambda (>= 0; may be >= levels()).
  static int levelOfWavelength(double wavelength);

  /// The gray image of level k (CV_32FC1, the input shrunk by 2^(k/2)).
  const cv::Mat& image(int k) const { return levels_.at(k).image; }
  /// Level k's cells; throws std::out_of_range for k outside [firstLevel(), levels()).
  const biovision_v1::ScaleResponses& responses(int k) const { return filtered(k).responses; }
  /// One CV_32FC(pooling_phases * orientations) map: per pixel the channels even 0..N-1, odd 0..N-1
  /// (then, with 4 phases, -even, -odd), each the maximum over the pooling disk whose centre is
  /// poolingCentreOffset() px up-left of the sample. Interleaved so that a descriptor reads all channels
  /// of a pooling field from one place with one set of bilinear weights.
  const cv::Mat& pooled(int k) const { return filtered(k).pooled; }
  double poolingCentreOffset() const;

  /// Image -> level k coordinates (pixel centres map to pixel centres) and back.
  cv::Point2f toLevel(const cv::Point2f& image_point, int k) const;
  cv::Point2f toImage(const cv::Point2f& level_point, int k) const;

  /// V1 keypoints of the given levels, in image coordinates with wavelength = wavelengthOfLevel(k),
  /// strongest first within each level. Levels outside [firstLevel(), levels()) are skipped.
  std::vector<biovision_v1::Keypoint> detectKeypoints(const std::vector<int>& levels) const;

  const Parameters& parameters() const { return parameters_; }

  /// The pooling element (CV_8U, pooling_diameter square, anchored at its (d/2, d/2) like cv::dilate's).
  const cv::Mat& poolingDisk() const { return pooling_disk_; }

  /// Kernel spectra sets the levels' banks have built so far (SimpleCellBank::plansBuilt() summed): a
  /// region size whose DFT sizes are cached builds none.
  long kernelSpectraBuilt() const;

private:
  struct Level
  {
    cv::Mat image;
    cv::Point2f scale;  // image px per level px, per axis
    biovision_v1::ScaleResponses responses;
    cv::Mat pooled;
  };
  struct PoolingRow
  {
    int dy;        // row offset from the anchor
    int interval;  // index into pooling_intervals_
  };
  const Level& filtered(int k) const;
  /// The level's pooled map from its responses: per channel the max over the disk (OFF channels: the
  /// negated min), equal to cv::dilate / cv::erode with pooling_disk_ and their default border.
  void poolLevel(Level& level) const;

  Parameters parameters_;
  int first_level_ = 0;
  std::vector<biovision_v1::SimpleCellBank> banks_;  // one per level: each caches its size's spectra
  std::vector<Level> levels_;
  cv::Mat pooling_disk_;                      // CV_8U d x d, anchored at (d/2, d/2) like cv::dilate's element
  std::vector<cv::Vec2i> pooling_intervals_;  // distinct column offset ranges [first, last] of its rows
  std::vector<PoolingRow> pooling_rows_;      // its rows
};
}  // namespace biovision_recognition
