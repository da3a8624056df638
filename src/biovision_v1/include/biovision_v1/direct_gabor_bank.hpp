#pragma once

#include <vector>

#include <opencv2/core.hpp>

#include "biovision_v1/gabor_parameters.hpp"
#include "biovision_v1/scale_responses.hpp"

namespace biovision_v1
{
/// The reference: the same Gabor kernels applied by direct 2-D cv::filter2D at full resolution
/// (BORDER_REFLECT_101). Used to check SimpleCellBank and as the benchmark peer. Responses are on the
/// full-resolution grid (decimation 1); sampleLike() picks the samples a SimpleCellBank grid holds.
class DirectGaborBank
{
public:
  explicit DirectGaborBank(const GaborParameters& parameters);

  /// Filters all kernels; parallel over kernels with biovision_common::parallelFor (a ParallelArena when the caller runs in one).
  std::vector<ScaleResponses> compute(const cv::Mat& gray) const;

  /// The samples of a full-resolution response at the grid of `grid` (every decimation-th pixel).
  static ScaleResponses sampleLike(const ScaleResponses& full, const ScaleResponses& grid);

  /// Largest |ours - reference| over all samples, divided by the largest |reference| of the same
  /// scale and orientation; the worst over the bank.
  static double maxRelativeError(const std::vector<ScaleResponses>& ours,
                                 const std::vector<ScaleResponses>& reference_full);

private:
  GaborParameters parameters_;
};
}  // namespace biovision_v1
