#pragma once

#include <opencv2/core.hpp>

#include "biovision_recognition/v1_feature_pyramid.hpp"
#include "biovision_v1/keypoint.hpp"

namespace biovision_recognition
{
/// The local affine shape of the image around a keypoint (Lindeberg and Garding 1997; Mikolajczyk and
/// Schmid 2004): the window is iteratively warped until the second-moment matrix of the gradients inside
/// it is isotropic. Returned as the symmetric positive-definite S (det 1) that maps the normalised frame
/// to the image: a viewpoint change J between two images maps S_a to about (J S_a^2 J^T)^(1/2), so a
/// descriptor sampled on the grid S * offsets sees the foreshortening undone. The symmetric choice keeps
/// the frame upright: its residual rotation between the two images stays under 10 degrees for a 3:1
/// foreshortening of texture up to 2:1 anisotropic (the descriptor is upright and tolerates that).
class AffineShapeAdaptation
{
public:
  struct Parameters
  {
    int iterations = 4;               ///< 0 = isotropic (identity). 0..16
    double window_wavelengths = 1.5;  ///< Gaussian sigma of the integration window [keypoint wavelengths]. (0, 8]
    int level_offset = 1;  ///< gradients on pyramid level base + offset (derivative step lambda 2^(offset/2) / 4). 0..4
    double max_anisotropy = 4.0;  ///< the ratio of S's eigenvalues is capped here (an edge has none). [1, 16]
  };

  /// Throws std::invalid_argument naming the offending field.
  static void validate(const Parameters& parameters);
  explicit AffineShapeAdaptation(const Parameters& parameters);

  /// S of a keypoint found on `pyramid` (identity when iterations = 0, or where the window is flat or a
  /// single straight edge).
  cv::Matx22f estimate(const V1FeaturePyramid& pyramid, const biovision_v1::Keypoint& keypoint) const;

  const Parameters& parameters() const { return parameters_; }

private:
  Parameters parameters_;
};
}  // namespace biovision_recognition
