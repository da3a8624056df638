#pragma once

#include <array>
#include <cstdint>
#include <memory>
#include <vector>

#include <opencv2/core.hpp>

#include "biovision_stereo/bio_bin_parameters.hpp"
#include "biovision_stereo/cost_simd.hpp"
#include "biovision_stereo/cost_volume.hpp"
#include "biovision_stereo/disparity_map.hpp"
#include "biovision_stereo/iterative_spatial_filter.hpp"
#include "biovision_stereo/pixel_descriptor.hpp"

namespace biovision_common
{
class AreaDownsampling;
}

namespace biovision_v1
{
class SimpleCellBank;
}

namespace biovision_stereo
{
/// BioBin multi-scale binary stereo (thesis §4.4), coarse to fine over the levels of
/// BioBinParameters::wavelengths:
///  (a) left/right resized to the level and converted to CIE L*a*b*;
///  (b) colour mask phi(m,k) = 1 where the L*a*b* SAD of left m and right m-k is among the
///      N_th = log2(N_d) smallest of the pixel;
///  (c) 256-bit rolling descriptors from odd simple cells of biovision_v1 (8 orientations);
///  (d) Hamming matching cost M(m, k);  M_phi = M (1 -/+ kappa) where phi = 1/0;
///  (e) 1-D DoG along k: M' = tau M_phi * (alpha g_s1 - beta g_s2), discrete-normalised Gaussians;
///  (f) costs above L = fusion_level * max(M') averaged with the upsampled coarser level's final
///      costs; iterative over-relaxed 3x3 binomial filtering that skips line/edge pixels of
///      biovision_v1; winner-take-all, optional sub-pixel parabola and left-right check.
///  Beyond the thesis, BioBinParameters::aggregation = "semi_global" replaces the finest level's
///  iterative filter by semi-global path aggregation (SemiGlobalAggregation) and its WTA.
/// Not thread-safe (it caches V1 filter plans per level size); use one matcher per thread.
class BioBinMatcher
{
public:
  explicit BioBinMatcher(const BioBinParameters& parameters);
  ~BioBinMatcher();

  /// left, right: rectified images of the same size and type, 8-bit BGR (or grey, taken as BGR
  /// grey). Throws std::invalid_argument on mismatched or unusable input.
  DisparityMap compute(const cv::Mat& left, const cv::Mat& right);

  const BioBinParameters& parameters() const { return parameters_; }

  /// Instruction set of the cost-volume loops (costs, DoG, fusion); default bestCostSimd(). Every path
  /// gives the same disparities bit for bit. Throws std::invalid_argument when this CPU lacks it.
  void setCostSimd(CostSimd simd);
  CostSimd costSimd() const { return cost_simd_; }

  /// Wall time of the stages of the last compute() [ms], summed over levels.
  struct StageTimes
  {
    // prepare: each level's area averaging of the input and colour conversions; costs: steps (b), (d) and
    // (e), the DoG included (they run fused, one image row at a time).
    double prepare = 0, cells = 0, costs = 0, fusion = 0, spatial = 0, wta = 0, total = 0;
  };
  const StageTimes& lastTimes() const { return times_; }

  /// Level sizes the matcher uses for an input size (finest first in parameters order).
  cv::Size levelSize(cv::Size input, size_t level) const;

  /// The iterative aggregation's winner-take-all step for one slice row, public for its tests: for i < n,
  /// cost[i] (disparity k at left pixel x = k + i) replaces best_cost[i] / best[i] when lower, and
  /// best_right[i] / right_k[i] (right pixel i) when lower; strict <, so the lowest disparity wins a tie and
  /// NaN never wins. simd: kGeneric or a vector path (kAvx2 and kAvx512 run 8 lanes of AVX2); all give the
  /// same result. Throws std::invalid_argument when this CPU lacks simd.
  static void updateWinners(const float* cost, int n, int k, float* best_cost, int* best, float* best_right,
                            int* right_k, CostSimd simd);

  /// Steps (b)-(e) of one level: colour-masked Hamming costs after the DoG along disparity.
  /// left/right: 8-bit BGR at the level's size. barriers: CV_8U, non-zero on left line/edge events.
  /// max_cost: the returned volume's max() (found while the rows are written: no pass of its own).
  CostVolume levelCosts(size_t level, const cv::Mat& left, const cv::Mat& right, int disparities, cv::Mat* barriers,
                        float* max_cost = nullptr);

private:
  /// The odd simple cells of one level's left and right image ([image]: 8 orientations as 4 CV_32FC2 pairs,
  /// full resolution, wavelength base_wavelength): the one place BioBin computes V1 responses for its
  /// descriptors. Both images in one call, so that their DFTs share the threads. gray: CV_32F in [0, 1].
  std::array<std::vector<cv::Mat>, 2> oddResponses(size_t level, const cv::Mat& left_gray, const cv::Mat& right_gray);
  /// max_cost: costs.max(), which sets the fusion level L. Returns the fused costs' min() (found on the way).
  float fuseWithCoarser(CostVolume& costs, float max_cost, const CostVolume& coarser) const;
  void spatialFilter(CostVolume& costs, const cv::Mat& barriers);
  DisparityMap winnerTakeAll(const CostVolume& costs, cv::Size input, double sf) const;
  /// parameters_.aggregation == "semi_global": the level's costs aggregated along paths, then WTA.
  /// lowest: costs.min(), the offset of the 16-bit costs.
  DisparityMap aggregateAndTakeWinners(const CostVolume& costs, float lowest, const cv::Mat& barriers, cv::Size input,
                                       double sf);
  /// Left disparities [level px, kInvalid] and the left-right check -> the map at input resolution.
  DisparityMap toInputResolution(cv::Mat& left_d, const cv::Mat& right_k, cv::Size input, double sf) const;
  /// (Re)creates the per-size caches below empty: at construction, and when a frame is smaller than the
  /// last one, so a single large frame's memory is given back (one 1920x1080 pair kept 1.3 GB of a node's
  /// resident memory while it went on matching 320x240 pairs).
  void resetCaches();

  BioBinParameters parameters_;
  cv::Size last_input_;  ///< the size of the last frame matched
  StageTimes times_;
  CostSimd cost_simd_ = bestCostSimd();
  // Per level (each caches its DFT plans for the level size): odd cells at full resolution for the
  // descriptors, and the full quadrature bank on its exact decimated grid for the line/edge barriers.
  std::vector<std::unique_ptr<biovision_v1::SimpleCellBank>> odd_banks_;
  std::vector<std::unique_ptr<biovision_v1::SimpleCellBank>> barrier_banks_;
  std::vector<std::uint16_t> sgm_costs_, sgm_forward_, sgm_backward_;  // reused between frames
  IterativeSpatialFilter spatial_filter_;  // the coarse levels' filter, its scratch reused between frames
  std::vector<CostVolume> spare_;          // each level's cost volume of the last frame, memory reused
  std::vector<std::array<PixelDescriptorImage, 2>> codes_;  // each level's left and right descriptors, reused
  // Each coarser level's area averaging of the input (its weights built once per input size).
  std::vector<std::unique_ptr<biovision_common::AreaDownsampling>> downsampling_;
};
}  // namespace biovision_stereo
