#pragma once

#include <biovision_stereo/BioBinDisparityConfig.h>

#include "biovision_stereo/bio_bin_parameters.hpp"
#include "biovision_v1/wavelength_list.hpp"

namespace biovision_stereo
{
/// The one mapping of the nodelet's reconfigurable parameters (cfg/BioBinDisparity.cfg) onto the core's
/// BioBinParameters; parameters the .cfg does not expose keep the struct's defaults. Does not validate.
/// Throws std::invalid_argument on an unreadable wavelength list.
inline BioBinParameters toBioBinParameters(const BioBinDisparityConfig& config)
{
  BioBinParameters p;
  p.wavelengths = biovision_v1::parseWavelengthList(config.wavelengths);
  p.max_disparity = config.max_disparity;
  p.kappa = config.kappa;
  p.tau = config.tau;
  p.alpha = config.alpha;
  p.beta = config.beta;
  p.sigma1 = config.sigma1;
  p.sigma2 = config.sigma2;
  p.fusion_level = config.fusion_level;
  p.relaxation = config.relaxation;
  p.stable_cost = config.stable_cost;
  p.max_iterations = config.max_iterations;
  p.line_edge_barriers = config.line_edge_barriers;
  p.subpixel = config.subpixel;
  p.left_right_check = config.left_right_check;
  p.left_right_tolerance = config.left_right_tolerance;
  p.fill_occlusions = config.fill_occlusions;
  p.median_filter = config.median_filter;
  p.aggregation = config.aggregation;
  p.sgm_p1 = config.sgm_p1;
  p.sgm_p2 = config.sgm_p2;
  p.sgm_p2_barrier = config.sgm_p2_barrier;
  p.sgm_paths = config.sgm_paths;
  return p;
}
}  // namespace biovision_stereo
