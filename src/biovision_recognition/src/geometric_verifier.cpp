#include "biovision_recognition/geometric_verifier.hpp"

#include <cmath>
#include <stdexcept>

#include <opencv2/calib3d.hpp>

namespace biovision_recognition
{
GeometricVerifier::Result GeometricVerifier::verify(const std::vector<cv::Point2f>& from,
                                                    const std::vector<cv::Point2f>& to) const
{
  if (from.size() != to.size())
    throw std::invalid_argument("GeometricVerifier: point lists differ in length");
  Result result;
  result.inlier_mask.assign(from.size(), 0);
  if (static_cast<int>(from.size()) < std::max(2, parameters_.min_inliers))
    return result;
  cv::Mat inliers;
  const cv::Mat t = cv::estimateAffinePartial2D(from, to, inliers, cv::RANSAC, parameters_.inlier_distance,
                                                static_cast<size_t>(parameters_.max_iterations), parameters_.confidence,
                                                10);
  if (t.empty())
    return result;
  cv::Mat t64;
  t.convertTo(t64, CV_64F);
  result.transform = cv::Matx23d(t64.ptr<double>());
  const double scale = std::hypot(result.transform(0, 0), result.transform(1, 0));
  const double rotation = std::abs(std::atan2(result.transform(1, 0), result.transform(0, 0))) * 180.0 / CV_PI;
  for (size_t i = 0; i < from.size(); ++i)
  {
    result.inlier_mask[i] = inliers.at<uint8_t>(static_cast<int>(i)) ? 1 : 0;
    result.inliers += result.inlier_mask[i];
  }
  result.accepted = result.inliers >= parameters_.min_inliers && scale >= parameters_.min_scale &&
                    scale <= parameters_.max_scale && rotation <= parameters_.max_rotation_degrees;
  return result;
}
}  // namespace biovision_recognition
