#include "biovision_stereo/bio_bin_parameters.hpp"

#include <stdexcept>
#include <string>

namespace biovision_stereo
{
void BioBinParameters::validate() const
{
  auto fail = [](const std::string& what) { throw std::invalid_argument("BioBinParameters: " + what); };
  if (wavelengths.empty())
    fail("wavelengths is empty");
  for (size_t s = 0; s < wavelengths.size(); ++s)
  {
    if (!(wavelengths[s] >= base_wavelength && wavelengths[s] <= 256.0))
      fail("wavelength " + std::to_string(wavelengths[s]) + " outside [base_wavelength, 256]");
    if (s > 0 && !(wavelengths[s] > wavelengths[s - 1]))
      fail("wavelengths must be strictly ascending");
  }
  if (!(base_wavelength >= 3.0 && base_wavelength <= 16.0))
    fail("base_wavelength outside [3, 16]");
  if (max_disparity < 1 || max_disparity > 1024)
    fail("max_disparity " + std::to_string(max_disparity) + " outside [1, 1024]");
  if (!(kappa >= 0.0 && kappa <= 1.0))
    fail("kappa outside [0, 1]");
  if (!(tau > 0.0 && tau <= 10.0))
    fail("tau outside (0, 10]");
  if (!(alpha >= 0.0 && beta >= 0.0 && alpha <= 10.0 && beta <= 10.0))
    fail("alpha/beta outside [0, 10]");
  if (!(sigma1 > 0.0 && sigma2 > 0.0 && sigma1 <= 64.0 && sigma2 <= 64.0))
    fail("sigma1/sigma2 outside (0, 64]");
  if (!(fusion_level >= 0.0 && fusion_level <= 1.0))
    fail("fusion_level outside [0, 1]");
  if (!(relaxation > 0.0 && relaxation < 2.0))
    fail("relaxation outside (0, 2): the over-relaxed filter diverges at 2");
  if (!(changing_fraction >= 0.0 && changing_fraction <= 1.0))
    fail("changing_fraction outside [0, 1]");
  if (max_iterations < 0 || max_iterations > 100)
    fail("max_iterations outside [0, 100]");
  if (!(left_right_tolerance >= 0.0))
    fail("left_right_tolerance must be >= 0");
  if (aggregation != "iterative" && aggregation != "semi_global")
    fail("aggregation '" + aggregation + "' is neither 'iterative' nor 'semi_global'");
  // P2 * kSgmCostScale must stay <= SemiGlobalAggregation::kMaxCost (2047).
  if (!(sgm_p1 >= 0.0 && sgm_p1 <= 255.0))
    fail("sgm_p1 outside [0, 255]");
  if (!(sgm_p2 >= 0.0 && sgm_p2 <= 255.0))
    fail("sgm_p2 outside [0, 255]");
  if (!(sgm_p2_barrier >= 0.0 && sgm_p2_barrier <= 255.0))
    fail("sgm_p2_barrier outside [0, 255]");
  if (sgm_paths != 4 && sgm_paths != 8)
    fail("sgm_paths must be 4 or 8");
}
}  // namespace biovision_stereo
