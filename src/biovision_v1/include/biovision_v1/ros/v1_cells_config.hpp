#pragma once

#include <biovision_v1/V1CellsConfig.h>

#include "biovision_v1/v1_pipeline.hpp"
#include "biovision_v1/wavelength_list.hpp"

namespace biovision_v1
{
/// The one mapping of the nodelet's reconfigurable parameters (cfg/V1Cells.cfg) onto the core's
/// V1Pipeline::Parameters (min_contrast serves keypoints and line/edges alike). Does not validate: the
/// V1Pipeline constructor does. Throws std::invalid_argument on an unreadable wavelength list.
inline V1Pipeline::Parameters toV1Parameters(const V1CellsConfig& config)
{
  V1Pipeline::Parameters p;
  p.gabor.wavelengths = parseWavelengthList(config.wavelengths);
  p.gabor.orientations = config.orientations;
  p.gabor.sigma_per_wavelength = config.sigma_per_wavelength;
  p.gabor.aspect_ratio = config.aspect_ratio;
  p.gabor.min_grid_wavelength = config.min_grid_wavelength;
  p.keypoints.threshold = config.keypoint_threshold;
  p.keypoints.min_contrast = config.min_contrast;
  p.keypoints.inhibition_gain = config.inhibition_gain;
  p.keypoints.radial_factor = config.radial_factor;
  p.keypoints.junction_weight = config.junction_weight;
  p.keypoints.junction_balance = config.junction_balance;
  p.keypoints.max_keypoints = config.max_keypoints;
  p.line_edges.relative_threshold = config.line_edge_threshold;
  p.line_edges.min_contrast = config.min_contrast;
  p.line_edges.lateral_inhibition = config.lateral_inhibition;
  p.end_stop_offset = config.end_stop_offset;
  return p;
}
}  // namespace biovision_v1
