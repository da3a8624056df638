#pragma once

#include <biovision_saliency/SaliencyConfig.h>

#include "biovision_saliency/saliency_parameters.hpp"

namespace biovision_saliency
{
/// The one mapping of the nodelet's reconfigurable parameters (cfg/Saliency.cfg) onto the core's
/// SaliencyParameters; parameters the .cfg does not expose keep the struct's defaults. Does not validate.
inline SaliencyParameters toSaliencyParameters(const SaliencyConfig& c)
{
  SaliencyParameters p;
  p.working_width = c.working_width;
  p.colour_weight = c.colour_weight;
  p.disparity_weight = c.disparity_weight;
  p.motion_weight = c.motion_weight;
  p.final_blur = c.final_blur;
  p.prior = static_cast<PriorMode>(c.prior);
  p.prior_weight = c.prior_weight;
  p.prior_sigma = c.prior_sigma;
  p.preferred_disparity_mode = c.preferred_disparity_mode;
  p.near_fraction = c.near_fraction;
  p.preferred_disparity = c.preferred_disparity;
  p.preferred_width = c.preferred_width;
  p.use_dis_flow = c.use_dis_flow;
  p.compensate_ego_motion = c.compensate_ego_motion;
  p.threshold = c.threshold;
  p.min_saliency = c.min_saliency;
  p.min_area = c.min_area;
  p.margin = c.margin;
  p.max_regions = c.max_regions;
  p.ior_radius = c.ior_radius;
  p.ior_decay_time = c.ior_decay_time;
  p.attend_period = c.attend_period;
  return p;
}
}  // namespace biovision_saliency
