#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include <opencv2/core.hpp>

#include "biovision_stereo/cost_volume.hpp"

namespace biovision_stereo
{
/// Semi-global path aggregation (Hirschmueller 2008, the step of OpenCV's SGBM) over a BioBin cost
/// volume: beyond the thesis, a switchable replacement of its iterative spatial filter (§4.4.5).
/// For each of 4 or 8 image directions r, along every straight path
///   L_r(p, d) = C(p, d) + min(L_r(p-r, d), L_r(p-r, d+-1) + P1, min_k L_r(p-r, k) + P2) - min_k L_r(p-r, k)
/// with L_r(p, d) = C(p, d) at a path's first pixel; S(p, d) = sum over r of L_r(p, d).
/// P2 is lowered to `p2_barrier` at pixels flagged in an optional barrier mask (biovision_v1's line/edge
/// events: depth edges sit on image edges), clamped to >= P1.
///
/// Volumes are pixel-major: element (x, y, d) at index (y * width + x) * stride + d with stride =
/// stride(disparities) (a multiple of 16 > disparities, so that the 16-bit SIMD lanes never straddle
/// pixels). Costs are unsigned 16-bit in [0, kMaxCost]; lanes >= disparities are ignored.
/// The forward (left, upper-left, up, upper-right) and backward sweeps run in parallel on two threads.
class SemiGlobalAggregation
{
public:
  /// Which instruction set the path recursion runs on. kGeneric is plain C++ (the compiler's baseline
  /// vectorisation), kAvx2 is 16 lanes of 16 bits with AVX2 intrinsics.
  enum class Simd
  {
    kGeneric,
    kAvx2
  };
  static constexpr std::uint16_t kMaxCost = 2047;  ///< 8 paths * (kMaxCost + P2) stays below 2^16

  /// p1, p2, p2_barrier in cost units, p1 <= p2 <= kMaxCost; paths 4 or 8. Throws std::invalid_argument.
  SemiGlobalAggregation(int p1, int p2, int p2_barrier, int paths);

  static int stride(int disparities) { return (disparities + 1 + 15) / 16 * 16; }
  /// The paths this CPU runs, slowest first (kGeneric always). No AVX-512 path: a 32-lane step measured
  /// 5-8% slower than AVX2 on an AVX-512 EPYC (stage_floor sgm_ms, 2026-12-05); on an Intel Xeon a
  /// 32-lane version of the fused per-pixel step (the pixel's last vector masked) took the aggregation
  /// alone from 6.9 / 6.8 to 6.0 / 5.6 ms but left BioBin's whole pair unchanged (71.4 / 71.3 / 71.8 ->
  /// 71.3 / 71.4 / 72.2 ms, 2026-12-06): the two sweeps run side by side, bound by memory, not by lanes.
  static std::vector<Simd> availableSimds();
  /// The fastest path this CPU runs (AVX2 when present).
  static Simd bestSimd();
  static std::string name(Simd simd);

  /// costs: width * height * stride(disparities) values as above. barriers: empty or CV_8U of
  /// width x height (non-zero = P2 lowered). forward, backward: resized and filled with the sums of
  /// the forward and backward paths (S = forward + backward, each <= 4 (kMaxCost + P2)).
  /// Throws std::invalid_argument on sizes that do not fit or when kAvx2 is asked for on a CPU without it.
  void aggregate(const std::vector<std::uint16_t>& costs, int width, int height, int disparities,
                 const cv::Mat& barriers, std::vector<std::uint16_t>& forward, std::vector<std::uint16_t>& backward,
                 Simd simd) const;

  /// The pixel-major input of aggregate() from a BioBin volume: (M(x, y, d) - lowest) * scale + 0.5,
  /// truncated, saturated at kMaxCost, for every pixel and d < disparities (lanes above are left as they
  /// were); `out` is resized to width * height * stride. lowest: at most every cost (the volume's
  /// minimum), scale > 0 [cost units per volume unit]. Rows in parallel; 8x8 SSE2 transposes on x86-64.
  static void toPixelMajor(const CostVolume& costs, float lowest, float scale, std::vector<std::uint16_t>& out);
  /// Winner-take-all on S = forward + backward (aggregate()'s sums). left: CV_32F width x height, at each
  /// pixel the d <= min(disparities - 1, x) of least S (the smallest such d on ties), moved by the parabola
  /// through S(d-1), S(d), S(d+1) (at most +-0.5 px) when `subpixel` and d is not at either end.
  /// right_k: CV_32S width x height, at right pixel xr the disparity d of least S over the left pixels
  /// xr + d that see it (the smallest d on ties), -1 where none does. Throws std::invalid_argument when the
  /// sums do not match the sizes, disparities is outside [1, 32767] or kAvx2 is asked for on a CPU without it.
  static void winners(const std::vector<std::uint16_t>& forward, const std::vector<std::uint16_t>& backward, int width,
                      int height, int disparities, bool subpixel, cv::Mat& left, cv::Mat& right_k, Simd simd);
  int p1() const { return p1_; }
  int p2() const { return p2_; }
  int p2Barrier() const { return p2_barrier_; }
  int paths() const { return paths_; }

private:
  int p1_, p2_, p2_barrier_, paths_;
};
}  // namespace biovision_stereo
