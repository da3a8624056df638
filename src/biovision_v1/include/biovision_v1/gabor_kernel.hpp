#pragma once

#include <opencv2/core.hpp>

#include "biovision_v1/gabor_parameters.hpp"

namespace biovision_v1
{
/// One quadrature pair of V1 simple-cell receptive fields: even (cosine, DC-free) and odd (sine)
/// Gabor kernels, both divided by the sum of the Gaussian envelope so that a grating of amplitude A at
/// the preferred frequency gives a complex-cell response of about A / 2 at every scale.
///
/// Coordinates: x right, y down; x' = x cos(theta) + y sin(theta) is the modulation direction.
/// Responses are correlations (as cv::filter2D computes them): R(p) = sum_u k(u) I(p + u).
class GaborKernel
{
public:
  GaborKernel(double wavelength, double theta, const GaborParameters& parameters);

  const cv::Mat& even() const { return even_; }
  const cv::Mat& odd() const { return odd_; }
  int radius() const { return radius_; }
  double wavelength() const { return wavelength_; }
  double theta() const { return theta_; }

private:
  double wavelength_;
  double theta_;
  int radius_;
  cv::Mat even_;  // CV_32F, (2r+1) x (2r+1)
  cv::Mat odd_;   // CV_32F, (2r+1) x (2r+1)
};
}  // namespace biovision_v1
