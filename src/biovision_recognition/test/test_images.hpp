#pragma once

// Test inputs shared by the descriptor tests.

#include <opencv2/core.hpp>
#include <opencv2/imgproc.hpp>

#include "biovision_v1/keypoint.hpp"

namespace test_images
{
/// Smooth isotropic random texture in [0.2, 0.8] (blobs at two scales): plenty of V1 keypoints at every scale.
inline cv::Mat texture(int w, int h, unsigned seed, double fine_sigma = 1.5)
{
  cv::Mat n(h, w, CV_32F);
  cv::RNG rng(seed);
  rng.fill(n, cv::RNG::NORMAL, 0.0, 1.0);
  cv::Mat fine, coarse;
  cv::GaussianBlur(n, fine, cv::Size(), fine_sigma);
  cv::GaussianBlur(n, coarse, cv::Size(), 5.0);
  cv::Mat t = fine * 2.0 + coarse * 8.0;
  cv::normalize(t, t, 0.2, 0.8, cv::NORM_MINMAX);
  return t;
}

inline biovision_v1::Keypoint at(double x, double y, double wavelength)
{
  biovision_v1::Keypoint k;
  k.x = static_cast<float>(x);
  k.y = static_cast<float>(y);
  k.wavelength = static_cast<float>(wavelength);
  return k;
}
}  // namespace test_images
