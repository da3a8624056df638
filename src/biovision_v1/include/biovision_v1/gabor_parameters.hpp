#pragma once

#include <vector>

namespace biovision_v1
{
/// Shape and sampling of the Gabor quadrature bank that models V1 simple cells.
struct GaborParameters
{
  /// Wavelengths lambda [px] of the scales, ascending.
  std::vector<double> wavelengths{4.0, 8.0, 16.0};
  /// Number of orientations N_theta in [0, pi); theta_i = i * pi / N_theta. 4..12.
  int orientations = 8;
  /// Envelope sigma across the bar, in wavelengths: 0.56 gives a bandwidth of about one octave.
  double sigma_per_wavelength = 0.56;
  /// Envelope aspect ratio gamma: the envelope along the bar has sigma / gamma. (0, 1].
  double aspect_ratio = 0.5;
  /// Kernel radius in units of the long-axis sigma (sigma / gamma). 2.5..5.
  double support_sigmas = 3.5;
  /// Each scale is computed on the coarsest power-of-two grid that keeps lambda / decimation >= this
  /// (decimation is exact: the full-resolution convolution sampled on that grid). A quadrature pair
  /// has a one-sided spectrum, so 2 samples per wavelength suffice (measured error ~1e-6, see
  /// README). 0 = never decimate (full-resolution responses at every scale).
  double min_grid_wavelength = 2.0;

  /// Throws std::invalid_argument naming the offending field.
  void validate() const;
  /// Envelope sigma across the bar [px] at wavelength lambda.
  double sigma(double wavelength) const { return sigma_per_wavelength * wavelength; }
  /// Kernel radius [px] at wavelength lambda.
  int radius(double wavelength) const;
  /// Grid decimation (1, 2, 4, ...) of the scale with wavelength lambda.
  int decimation(double wavelength) const;
  /// Orientation theta_i [rad] of channel i: the direction of the modulation (the bar's normal).
  double theta(int i) const;
};
}  // namespace biovision_v1
