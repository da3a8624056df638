#pragma once

#include <vector>

#include "biovision_recognition/affine_shape_adaptation.hpp"

namespace biovision_recognition
{
/// Which pooled V1 cell responses make the descriptor's input vector x (thesis 3.3.2).
///
/// The patch around a keypoint of wavelength lambda_k is patch_wavelengths * lambda_k wide (32 px at
/// lambda_k = 4, as the source's 32 x 32 patches). Descriptor scale j uses cells of wavelength
/// lambda_k * 2^(j/2), i.e. 4 * 2^(j/2) px of the 32 px patch: j = 0..6 are the source's
/// {4, 6, 8, 12, 16, 24, 32} (as half octaves). Each scale is read on pyramid level k + j where those
/// cells are lambda = 4, so its pooling fields (diameter 4, step 2, as the source's best) are in level
/// pixels: the pooling grid coarsens with the scale. Deviation, on purpose: the source pooled every
/// scale on the 32 x 32 patch grid; a response at wavelength lambda carries nothing finer than lambda / 2,
/// so that finer grid only adds correlated copies (25,200 inputs for 7 scales, whose Sigma_N^-1/2 is
/// infeasible) where this grid gives 6,416 per two phases.
/// Channels: simple cells are half-wave rectified in V1, so a cell and its opposite phase are different
/// cells; pooling the maximum of the signed response keeps only the ON half. With phases = 4 the OFF
/// halves (maxima of -even, -odd) are pooled too: measured on descriptor_eval's test part (2000 pairs per
/// image pair), fpr95 0.239 -> 0.196 (0.203 for the committed retraining), most of it on the strongest
/// viewpoint change.
/// Sampling geometry: with shape.iterations > 0 the pooling grid is laid on the keypoint's affine shape
/// (AffineShapeAdaptation, estimated from the image alone) instead of a square, so a foreshortened view
/// of a surface is sampled where the frontal view was: measured on descriptor_eval's test part, fpr95
/// 0.203 -> 0.130 (the strongest viewpoint change, HPatches 1-6 with 2-4:1 foreshortening: 0.708 -> 0.624).
/// Order in x: scale, then grid row, grid column, then channel (even 0..N-1, odd 0..N-1[, -even, -odd]).
struct DescriptorLayout
{
  /// Largest pooling grid side validate() accepts (a 32-wavelength patch pooled at step 1).
  static constexpr int kMaxGridSide = 128;

  std::vector<int> scales{0, 1, 2, 3, 4, 5, 6};  ///< j, ascending, >= 0
  int orientations = 8;
  double patch_wavelengths = 8.0;           ///< patch side / keypoint wavelength. > 0
  int pooling_diameter = 4;                 ///< [level px]
  int pooling_step = 2;                     ///< [level px]
  int phases = 4;                           ///< 2: even, odd (signed maximum); 4: also -even, -odd (OFF half-waves)
  AffineShapeAdaptation::Parameters shape;  ///< iterations = 0: square grid (the source's)

  /// Pooling fields per side of scale j.
  int gridSide(int j) const;
  /// Length of x.
  int featureCount() const;
  /// Throws std::invalid_argument naming the offending field.
  void validate() const;
  bool operator==(const DescriptorLayout& o) const
  {
    return scales == o.scales && orientations == o.orientations && patch_wavelengths == o.patch_wavelengths &&
           pooling_diameter == o.pooling_diameter && pooling_step == o.pooling_step && phases == o.phases &&
           shape.iterations == o.shape.iterations && shape.window_wavelengths == o.shape.window_wavelengths &&
           shape.level_offset == o.shape.level_offset && shape.max_anisotropy == o.shape.max_anisotropy;
  }
};
}  // namespace biovision_recognition
