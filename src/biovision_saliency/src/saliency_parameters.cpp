#include "biovision_saliency/saliency_parameters.hpp"

#include <stdexcept>
#include <string>

namespace biovision_saliency
{
void SaliencyParameters::validate() const
{
  auto fail = [](const std::string& what) { throw std::invalid_argument("SaliencyParameters: " + what); };
  if (working_width < 16 || working_width > 4096)
    fail("working_width outside [16, 4096]");
  if (!(reference_width >= 16))
    fail("reference_width must be >= 16");
  if (blob_sigmas.empty())
    fail("blob_sigmas is empty");
  for (double s : blob_sigmas)
    if (!(s > 0 && s <= 200))
      fail("blob sigma outside (0, 200]");
  if (!(blob_pyramid_sigma >= 0 && blob_pyramid_sigma <= 100))
    fail("blob_pyramid_sigma outside [0, 100]");
  if (!(colour_weight >= 0 && disparity_weight >= 0 && motion_weight >= 0) ||
      colour_weight + disparity_weight + motion_weight <= 0)
    fail("weights must be >= 0 and not all 0");
  if (!(final_blur >= 0 && final_blur <= 200))
    fail("final_blur outside [0, 200]");
  if (prior != PriorMode::none && prior != PriorMode::centre && prior != PriorMode::horizon)
    fail("prior must be none (0), centre (1) or horizon (2)");
  if (!(prior_weight >= 0 && prior_weight <= 1))
    fail("prior_weight outside [0, 1]");
  if (!(prior_sigma >= 0.02 && prior_sigma <= 10))
    fail("prior_sigma outside [0.02, 10]");
  if (!(near_fraction >= 0 && near_fraction < 1))
    fail("near_fraction outside [0, 1)");
  if (!(preferred_width > 0))
    fail("preferred_width must be > 0");
  if (speed_edges.size() != 3 ||
      !(speed_edges[0] >= 0 && speed_edges[0] < speed_edges[1] && speed_edges[1] < speed_edges[2]))
    fail("speed_edges must be 3 ascending values >= 0");
  if (!(colour_floor > 0 && disparity_floor > 0 && motion_floor > 0))
    fail("normalisation floors must be > 0");
  if (!(min_saliency > 0 && min_saliency <= 1))
    fail("min_saliency outside (0, 1]");
  if (!(threshold > 0 && threshold < 1))
    fail("threshold outside (0, 1)");
  if (!(min_area >= 0) || !(margin >= 0) || max_regions < 1)
    fail("min_area, margin must be >= 0 and max_regions >= 1");
  if (!(ior_radius > 0) || !(ior_decay_time > 0) || !(attend_period >= 0))
    fail("ior_radius, ior_decay_time must be > 0 and attend_period >= 0");
  if (!(horizontal_fov > 0.05 && horizontal_fov < 3.1))
    fail("horizontal_fov outside (0.05, 3.1) rad");
}
}  // namespace biovision_saliency
