#include "biovision_recognition/pair_sampler.hpp"

#include <algorithm>
#include <cmath>

namespace biovision_recognition
{
template <typename MapToB>
PairSampler::Pairs PairSampler::sample(const V1FeaturePyramid& a, const V1FeaturePyramid& b, MapToB&& map_to_b)
{
  Pairs pairs;
  std::vector<biovision_v1::Keypoint> in_a = a.detectKeypoints(parameters_.levels);
  const std::vector<biovision_v1::Keypoint> in_b = b.detectKeypoints(parameters_.levels);
  if (in_b.empty())
    return pairs;
  std::shuffle(in_a.begin(), in_a.end(), rng_);
  const cv::Size size_b = b.imageSize();
  std::uniform_int_distribution<size_t> pick(0, in_b.size() - 1);
  for (const auto& kp : in_a)
  {
    if (static_cast<int>(pairs.positive_a.size()) >= parameters_.max_pairs)
      break;
    biovision_v1::Keypoint mapped = kp;
    if (!map_to_b(kp, mapped))
      continue;
    const float border = static_cast<float>(parameters_.border_wavelengths * mapped.wavelength);
    if (mapped.x < border || mapped.y < border || mapped.x > size_b.width - 1 - border ||
        mapped.y > size_b.height - 1 - border)
      continue;
    // A detected keypoint of B far from the true correspondence; give up after a few draws.
    for (int attempt = 0; attempt < 16; ++attempt)
    {
      const auto& other = in_b[pick(rng_)];
      const float sep = static_cast<float>(parameters_.min_negative_separation *
                                           std::max(kp.wavelength, other.wavelength));
      if (std::hypot(other.x - mapped.x, other.y - mapped.y) >= sep)
      {
        pairs.positive_a.push_back(kp);
        pairs.positive_b.push_back(mapped);
        pairs.negative_a.push_back(kp);
        pairs.negative_b.push_back(other);
        break;
      }
    }
  }
  return pairs;
}

PairSampler::Pairs PairSampler::fromHomography(const V1FeaturePyramid& a, const V1FeaturePyramid& b, const cv::Mat& h)
{
  cv::Mat h64;
  h.convertTo(h64, CV_64F);
  const cv::Matx33d H(h64.ptr<double>());
  return sample(a, b, [&H](const biovision_v1::Keypoint& kp, biovision_v1::Keypoint& out) {
    const double x = kp.x, y = kp.y;
    const double w = H(2, 0) * x + H(2, 1) * y + H(2, 2);
    if (std::abs(w) < 1e-12)
      return false;
    const double u = (H(0, 0) * x + H(0, 1) * y + H(0, 2)) / w;
    const double v = (H(1, 0) * x + H(1, 1) * y + H(1, 2)) / w;
    // Jacobian of the projective map: local magnification sqrt|det J|.
    const double j00 = (H(0, 0) - u * H(2, 0)) / w, j01 = (H(0, 1) - u * H(2, 1)) / w;
    const double j10 = (H(1, 0) - v * H(2, 0)) / w, j11 = (H(1, 1) - v * H(2, 1)) / w;
    const double scale = std::sqrt(std::abs(j00 * j11 - j01 * j10));
    if (!(scale > 0.25 && scale < 4.0))
      return false;
    out.x = static_cast<float>(u);
    out.y = static_cast<float>(v);
    out.wavelength = static_cast<float>(kp.wavelength * scale);
    return true;
  });
}

PairSampler::Pairs PairSampler::fromDisparity(const V1FeaturePyramid& left, const V1FeaturePyramid& right,
                                              const cv::Mat& disparity, const cv::Mat& valid)
{
  return sample(left, right, [&](const biovision_v1::Keypoint& kp, biovision_v1::Keypoint& out) {
    const int x = static_cast<int>(std::lround(kp.x)), y = static_cast<int>(std::lround(kp.y));
    if (x < 0 || y < 0 || x >= disparity.cols || y >= disparity.rows)
      return false;
    if (!valid.empty() && valid.at<uint8_t>(y, x) == 0)
      return false;
    const float d = disparity.at<float>(y, x);
    if (!(d > 0) || !std::isfinite(d))
      return false;
    out.x = kp.x - d;
    return true;
  });
}
}  // namespace biovision_recognition
