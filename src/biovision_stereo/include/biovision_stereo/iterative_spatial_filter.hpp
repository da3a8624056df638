#pragma once

#include <vector>

#include <opencv2/core.hpp>

#include "biovision_stereo/cost_simd.hpp"
#include "biovision_stereo/cost_volume.hpp"

namespace biovision_stereo
{
/// The thesis's spatial filtering of a cost volume (§4.4.6, BioBin's step 6): each slice is over-relaxed
/// towards its 3x3 binomial mean, M_F = M_f + r (w_s − M_f), with line/edge pixels left out of the mean;
/// a cost below Th_D before and after an iteration is frozen from then on; the filter iterates until fewer
/// than `changing_fraction` of the costs move by more than 1e-3, at most `max_iterations` times. Binomial
/// weights give the averaging operator a spectrum in [0, 1], so r in (0, 2) is stable (a box mean would
/// diverge at r = 1.6). Pixels with no open neighbour (inside a thick barrier) keep their costs.
///
/// apply() runs the per-pixel update on whole rows with 32-bit masks, compiled for the baseline
/// instruction set and for AVX2 without FMA (CostSimd): the same bits on both, and the same as
/// applyReference(), the scalar formulation (gtest). Why: the update was BioBin's fast mode's largest
/// stage, ~50 instructions per cost scalar (callgrind, stereo_eval biobin_fast_thesis on Cones).
class IterativeSpatialFilter
{
public:
  /// relaxation r in (0, 2), stable_cost Th_D, changing_fraction w in [0, 1], max_iterations >= 0
  /// (BioBinParameters validates them).
  IterativeSpatialFilter(double relaxation, double stable_cost, double changing_fraction, int max_iterations);

  /// Filters `costs` in place. `barriers`: CV_8U of the volume's size, non-zero = a line/edge pixel left
  /// out of the means; empty = no barriers. Throws std::invalid_argument on a barrier map of another size
  /// or type. Reuses the instance's scratch (the frozen flags, one per cost: a fresh zeroed volume per
  /// call was 6% of BioBin's time in page faults and memset), so one instance serves one thread at a time.
  void apply(CostVolume& costs, const cv::Mat& barriers) const;
  /// The same filter, scalar and unvectorised (the reference for tests).
  void applyReference(CostVolume& costs, const cv::Mat& barriers) const;

  /// Instruction set of apply() (default bestCostSimd()). Throws std::invalid_argument when this CPU lacks it.
  void setSimd(CostSimd simd);
  CostSimd simd() const { return simd_; }

private:
  /// Weight (0 on barriers, else 1) and the inverse of its 3x3 binomial mean (0 = no open neighbour).
  void weights(const CostVolume& costs, const cv::Mat& barriers, cv::Mat& weight, cv::Mat& inv_norm) const;

  float relaxation_, stable_cost_;
  double changing_fraction_;
  int max_iterations_;
  CostSimd simd_ = bestCostSimd();
  mutable std::vector<float> frozen_;  // apply()'s flags, slice after slice; capacity kept between calls
};
}  // namespace biovision_stereo
