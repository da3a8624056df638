#pragma once

#include <random>
#include <vector>

#include <opencv2/core.hpp>

#include "biovision_recognition/v1_feature_pyramid.hpp"
#include "biovision_v1/keypoint.hpp"

namespace biovision_recognition
{
/// Matching and non-matching keypoint pairs cut from real images with known correspondence, for
/// training (train_descriptor) and evaluating (descriptor_eval) descriptors.
///
/// Positives: V1 keypoints of image A and the exact point the ground truth maps them to in image B, at
/// the wavelength scaled by the local magnification (HPatches homographies) or unchanged (rectified
/// stereo with Middlebury disparities). Negatives: the same keypoints of A against keypoints detected in
/// B at least `min_negative_separation` wavelengths away from the true correspondence, so a negative is
/// what a matcher would really have to reject.
class PairSampler
{
public:
  struct Parameters
  {
    std::vector<int> levels{0, 1, 2, 3, 4};  ///< pyramid levels keypoints are detected at
    int max_pairs = 3000;                    ///< per image pair, of each kind
    double border_wavelengths = 1.0;         ///< the true correspondence must lie this far inside B
    double min_negative_separation = 4.0;    ///< [wavelengths]
    unsigned seed = 7;
  };

  struct Pairs
  {
    std::vector<biovision_v1::Keypoint> positive_a, positive_b, negative_a, negative_b;
  };

  explicit PairSampler(const Parameters& parameters) : parameters_(parameters), rng_(parameters.seed) {}

  /// h: 3x3 CV_64F homography mapping A's pixels to B's.
  Pairs fromHomography(const V1FeaturePyramid& a, const V1FeaturePyramid& b, const cv::Mat& h);
  /// disparity: CV_32F left disparity [px] (<= 0 or non-finite: unknown); valid: CV_8U, 255 = usable
  /// (empty = all known pixels). A = left, B = right.
  Pairs fromDisparity(const V1FeaturePyramid& left, const V1FeaturePyramid& right, const cv::Mat& disparity,
                      const cv::Mat& valid);

private:
  template <typename MapToB>
  Pairs sample(const V1FeaturePyramid& a, const V1FeaturePyramid& b, MapToB&& map_to_b);

  Parameters parameters_;
  std::mt19937 rng_;
};
}  // namespace biovision_recognition
