#pragma once

#include <vector>

namespace biovision_saliency
{
/// Where a scene's interesting content tends to be, multiplied into the fused map (see `prior`).
enum class PriorMode : int
{
  none = 0,     ///< the map as the channels give it (the thesis)
  centre = 1,   ///< a Gaussian at the image centre: photographers' framing (the MIT benchmark's centre baseline)
  horizon = 2,  ///< a Gaussian band about the horizon row, from the head's tilt: world-anchored, not camera-anchored
};

/// Parameters of the saliency model (thesis §2.2.3, §4.5). Sizes in pixels refer to the reference
/// width `reference_width` (the Bumblebee-2's 640) and are scaled to the working resolution.
struct SaliencyParameters
{
  int working_width = 160;                           ///< maps are computed at this width (height keeps the aspect)
  double reference_width = 640.0;                    ///< image width the pixel sizes below are given for
  std::vector<double> blob_sigmas{5.0, 10.0, 20.0};  ///< DoG centre sigmas sigma+ [reference px]; sigma- = 2 sigma+
  /// Blurs wider than this [working px] run on a Gaussian pyramid (BlobFilterBank): at 160 px the surrounds
  /// of sigma 5 and 10 px on the half and quarter level; 0 = every blur at the working resolution. Measured
  /// (saliency_eval, MIT1003 dev cross-validation): no accuracy lost (no prior CC 0.261 -> 0.267, NSS 1.056
  /// -> 1.117; centre prior 0.547 -> 0.550), one image at 160x120 2.0 -> 0.9 ms (1 thread).
  double blob_pyramid_sigma = 2.5;

  double colour_weight = 1.0;  ///< fusion weights; equal by default (thesis)
  double disparity_weight = 1.0;
  double motion_weight = 1.0;
  /// Gaussian smoothing of the fused map, sigma [reference px]; 0 = none. Chosen by 5-fold
  /// cross-validation on the dev half of MIT1003 (saliency_eval; the test half never took part).
  double final_blur = 16.0;

  /// Spatial prior multiplied into the smoothed map: map * ((1 - prior_weight) + prior_weight * prior).
  /// Default horizon for the active head: a centre prior rewards whatever the head already looks at
  /// (the FoA would keep the fixated object and suppress the periphery that saccades should explore);
  /// the horizon band follows the head's tilt, so it favours eye-level directions in the world and is
  /// the same for every pan. Weight and width: the cross-validated choice on MIT1003's dev half among
  /// horizon priors an active head can live with (weight <= 0.5: a direction loses at most half its
  /// saliency; sigma >= 0.2: objects off eye level stay reachable); saliency_eval reports it on the test half.
  PriorMode prior = PriorMode::horizon;
  double prior_weight = 0.5;  ///< [0, 1]: 0 = no prior, 1 = pure product with the prior
  /// Prior's Gaussian sigma as a fraction of the image's width (centre, horizontally) and height
  /// (centre vertically; horizon band).
  double prior_sigma = 0.2;

  // Disparity channel.
  bool preferred_disparity_mode = false;  ///< false: nearest regions; true: a preferred-disparity layer
  double near_fraction = 0.15;            ///< nearest mode: keep disparities >= this * max disparity
  double preferred_disparity = 0.0;       ///< preferred mode: disparity getting the maximum [input px]
  double preferred_width = 10.0;          ///< preferred mode: value falls to 0 at this |d - preferred| [input px]

  // Motion channel.
  bool use_dis_flow = false;  ///< Farneback (thesis) or DIS (faster)
  /// 3 speed maps: [e0,e1), [e1,e2), [e2,inf) [working px/frame]. Below e0 is flow noise: Farneback's
  /// residual on low-texture areas reaches ~1 px at 160x120 (measured).
  std::vector<double> speed_edges{1.0, 2.0, 5.0};
  bool compensate_ego_motion = true;  ///< subtract predicted head rotation and the robust global flow

  // Normalisation floors: a channel is divided by max(its maximum, floor), so that a channel holding
  // only noise is not blown up to full saliency.
  double colour_floor = 0.25;  ///< faint texture gives ~0.27, a vivid object ~0.85, real scenes 0.4-0.6
  double disparity_floor = 0.02;
  double motion_floor = 2.0;  ///< residual flow noise gives < 1, a patch at 3 px/frame ~3.4

  // Regions.
  double threshold = 2.0 / 3.0;  ///< of the fused map's maximum
  double min_saliency = 0.1;     ///< fused maps weaker than this are not stretched to 1: a blank
                                 ///< or featureless frame gives no region
  double min_area = 64.0;        ///< [reference px^2]
  double margin = 15.0;          ///< box growth on every side [full-resolution px]
  int max_regions = 8;

  // Focus-of-Attention and Inhibition-of-Return.
  double ior_radius = 0.17;        ///< an attended direction inhibits regions within this angle [rad] (~10 deg)
  double ior_decay_time = 3.0;     ///< inhibition falls linearly to 0 over this time [s]
  double attend_period = 1.0;      ///< the top region is attended at most this often [s]; 0 = never automatically
  double horizontal_fov = 0.7505;  ///< used when no focal length is given [rad] (43 deg)

  /// Throws std::invalid_argument naming the offending field.
  void validate() const;
};
}  // namespace biovision_saliency
