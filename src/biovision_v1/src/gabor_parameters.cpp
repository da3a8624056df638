#include "biovision_v1/gabor_parameters.hpp"

#include <cmath>
#include <stdexcept>
#include <string>

namespace biovision_v1
{
void GaborParameters::validate() const
{
  if (wavelengths.empty())
    throw std::invalid_argument("GaborParameters: wavelengths is empty");
  for (size_t k = 0; k < wavelengths.size(); ++k)
  {
    if (!(wavelengths[k] >= 2.0 && wavelengths[k] <= 256.0))
      throw std::invalid_argument("GaborParameters: wavelength " + std::to_string(wavelengths[k]) +
                                  " outside [2, 256] px (2 px is the sampling limit)");
    if (k > 0 && !(wavelengths[k] > wavelengths[k - 1]))
      throw std::invalid_argument("GaborParameters: wavelengths must be strictly ascending");
  }
  if (orientations < 4 || orientations > 12)
    throw std::invalid_argument("GaborParameters: orientations " + std::to_string(orientations) + " outside [4, 12]");
  if (!(sigma_per_wavelength >= 0.2 && sigma_per_wavelength <= 2.0))
    throw std::invalid_argument("GaborParameters: sigma_per_wavelength outside [0.2, 2]");
  if (!(aspect_ratio > 0.0 && aspect_ratio <= 1.0))
    throw std::invalid_argument("GaborParameters: aspect_ratio outside (0, 1]");
  if (!(support_sigmas >= 2.5 && support_sigmas <= 5.0))
    throw std::invalid_argument("GaborParameters: support_sigmas outside [2.5, 5]");
  if (!(min_grid_wavelength == 0.0 || (min_grid_wavelength >= 2.0 && min_grid_wavelength <= 64.0)))
    throw std::invalid_argument("GaborParameters: min_grid_wavelength must be 0 or in [2, 64]");
}

int GaborParameters::radius(double wavelength) const
{
  return static_cast<int>(std::ceil(support_sigmas * sigma(wavelength) / aspect_ratio));
}

int GaborParameters::decimation(double wavelength) const
{
  int d = 1;
  if (min_grid_wavelength <= 0.0)
    return d;
  while (wavelength / (2 * d) >= min_grid_wavelength)
    d *= 2;
  return d;
}

double GaborParameters::theta(int i) const
{
  return i * M_PI / orientations;
}
}  // namespace biovision_v1
