#pragma once

#include <vector>

#include "biovision_stereo/cost_simd.hpp"
#include "biovision_stereo/cost_volume.hpp"

namespace biovision_stereo
{
/// 1-D Difference-of-Gaussians along the disparity axis of a cost volume (thesis §4.4.5):
///   out(m, k) = tau * (alpha * g_sigma1 - beta * g_sigma2) * in(m, .)   (convolution over k)
/// with discrete Gaussians normalised to unit sum and the cost curve replicated past both ends.
/// The narrow Gaussian is an exact FIR; a broad one (sigma >= 2) is the recursive Young & van Vliet
/// (1995) Gaussian, O(1) per cost instead of 6 sigma taps. Both run along k over whole image rows,
/// so the inner loops are contiguous and vectorise. applyReference() is the exact FIR of both.
class DisparityDog
{
public:
  DisparityDog(double sigma1, double sigma2, double tau, double alpha, double beta);

  void apply(const CostVolume& in, CostVolume& out) const;
  /// The same filter written back into `costs` (one image row copied at a time: no second volume).
  void applyInPlace(CostVolume& costs) const;
  void applyReference(const CostVolume& in, CostVolume& out) const;
  /// The filter on one image row of a volume: in[k] and out[k] point at the w costs of disparity k
  /// (k = 0..nd-1, nd = in.size() = out.size()); out must not alias in. scratch: the caller's buffers
  /// (reused between calls), so that rows can be filtered on several threads. Throws std::invalid_argument
  /// when nd = 0 or in and out differ in length. BioBinMatcher runs it on
  /// each row as soon as the row's costs exist, while they are still in the cache.
  void applyRow(const std::vector<const float*>& in, int w, std::vector<float*>& out,
                std::vector<std::vector<float>>& scratch) const;

  /// Instruction set of apply()/applyInPlace() (default bestCostSimd(); both give the same bits).
  /// Throws std::invalid_argument when this CPU lacks it.
  void setSimd(CostSimd simd);
  CostSimd simd() const { return simd_; }

private:
  struct Recursive
  {
    bool enabled = false;
    float b = 0.f, a1 = 0.f, a2 = 0.f, a3 = 0.f;  // w[n] = b x[n] + a1 w[n-1] + a2 w[n-2] + a3 w[n-3]
    int pad = 0;                                  // replicated values added at both ends of the curve
  };

  static std::vector<float> taps(double sigma);
  static Recursive recursive(double sigma);
  // applyRow() runs filterRowBody() compiled for simd_.
  void filterRowAvx2(const std::vector<const float*>& in, int w, std::vector<float*>& out,
                     std::vector<std::vector<float>>& scratch) const;
  void filterRowAvx512(const std::vector<const float*>& in, int w, std::vector<float*>& out,
                       std::vector<std::vector<float>>& scratch) const;
  void filterRowGeneric(const std::vector<const float*>& in, int w, std::vector<float*>& out,
                        std::vector<std::vector<float>>& scratch) const;
  void filterRowBody(const std::vector<const float*>& in, int w, std::vector<float*>& out,
                     std::vector<std::vector<float>>& scratch) const;
  /// out += gain * (taps * in) along disparity; with `assign`, out's old values are taken as 0 (not read).
  void firAdd(const std::vector<const float*>& in, int w, const std::vector<float>& taps, float gain,
              std::vector<float*>& out, bool assign = false) const;
  void recursiveAdd(const std::vector<const float*>& in, int w, float gain, std::vector<float*>& out,
                    std::vector<std::vector<float>>& scratch) const;

  double tau_, alpha_, beta_;
  std::vector<float> narrow_, broad_;
  Recursive broad_recursive_;
  CostSimd simd_ = bestCostSimd();
};
}  // namespace biovision_stereo
