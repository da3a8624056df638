#include "biovision_v1/gabor_kernel.hpp"

#include <cmath>

namespace biovision_v1
{
GaborKernel::GaborKernel(double wavelength, double theta, const GaborParameters& parameters)
  : wavelength_(wavelength), theta_(theta), radius_(parameters.radius(wavelength))
{
  const int size = 2 * radius_ + 1;
  const double sigma = parameters.sigma(wavelength);
  const double gamma = parameters.aspect_ratio;
  const double c = std::cos(theta), s = std::sin(theta);
  cv::Mat envelope(size, size, CV_64F), carrier_cos(size, size, CV_64F), carrier_sin(size, size, CV_64F);
  for (int y = -radius_; y <= radius_; ++y)
    for (int x = -radius_; x <= radius_; ++x)
    {
      const double xp = x * c + y * s;   // across the bar (modulation)
      const double yp = -x * s + y * c;  // along the bar
      envelope.at<double>(y + radius_,
                          x + radius_) = std::exp(-(xp * xp + gamma * gamma * yp * yp) / (2.0 * sigma * sigma));
      carrier_cos.at<double>(y + radius_, x + radius_) = std::cos(2.0 * M_PI * xp / wavelength);
      carrier_sin.at<double>(y + radius_, x + radius_) = std::sin(2.0 * M_PI * xp / wavelength);
    }
  cv::Mat even = envelope.mul(carrier_cos);
  const cv::Mat odd = envelope.mul(carrier_sin);
  // DC-free even cell: remove the envelope-shaped mean, so uniform light gives no response.
  const double envelope_sum = cv::sum(envelope)[0];
  even -= envelope * (cv::sum(even)[0] / envelope_sum);
  even.convertTo(even_, CV_32F, 1.0 / envelope_sum);
  odd.convertTo(odd_, CV_32F, 1.0 / envelope_sum);
}
}  // namespace biovision_v1
