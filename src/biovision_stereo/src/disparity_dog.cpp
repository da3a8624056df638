#include "biovision_stereo/disparity_dog.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

#include <opencv2/core/utility.hpp>

#include "avx512_clone.hpp"
#include "biovision_common/parallel_arena.hpp"

namespace biovision_stereo
{
DisparityDog::DisparityDog(double sigma1, double sigma2, double tau, double alpha, double beta)
  : tau_(tau),
    alpha_(alpha),
    beta_(beta),
    narrow_(taps(sigma1)),
    broad_(taps(sigma2)),
    broad_recursive_(recursive(sigma2))
{
}

std::vector<float> DisparityDog::taps(double sigma)
{
  // Normalised to unit sum: the printed continuous normalisation 1/sqrt(2 pi sigma^2) gives a single
  // tap of 1.6 at sigma = 1/sf = 0.25, which would amplify the costs of coarse levels.
  const int r = std::max(1, static_cast<int>(std::ceil(3.0 * sigma)));
  std::vector<float> t(2 * r + 1);
  double sum = 0;
  for (int j = -r; j <= r; ++j)
    sum += t[j + r] = static_cast<float>(std::exp(-0.5 * j * j / (sigma * sigma)));
  for (float& v : t)
    v = static_cast<float>(v / sum);
  return t;
}

DisparityDog::Recursive DisparityDog::recursive(double sigma)
{
  Recursive r;
  if (sigma < 2.0)
    return r;  // too narrow for the recursive approximation: the FIR is short anyway
  const double q = sigma >= 2.5 ? 0.98711 * sigma - 0.96330 : 3.97156 - 4.14554 * std::sqrt(1.0 - 0.26891 * sigma);
  const double b0 = 1.57825 + 2.44413 * q + 1.4281 * q * q + 0.422205 * q * q * q;
  const double b1 = 2.44413 * q + 2.85619 * q * q + 1.26661 * q * q * q;
  const double b2 = -(1.4281 * q * q + 1.26661 * q * q * q);
  const double b3 = 0.422205 * q * q * q;
  r.enabled = true;
  r.pad = static_cast<int>(std::ceil(3.0 * sigma));
  r.a1 = static_cast<float>(b1 / b0);
  r.a2 = static_cast<float>(b2 / b0);
  r.a3 = static_cast<float>(b3 / b0);
  r.b = static_cast<float>(1.0 - (b1 + b2 + b3) / b0);
  return r;
}

inline void DisparityDog::firAdd(const std::vector<const float*>& in, int w, const std::vector<float>& t, float gain,
                                 std::vector<float*>& out, bool assign) const
{
  const int nd = static_cast<int>(in.size()), r = static_cast<int>(t.size() / 2);
  for (int k = 0; k < nd; ++k)
  {
    float* o = out[k];
    const float* c = in[k];
    const float t0 = gain * t[r];
    if (assign)  // 0 + product, as on a zeroed row: the same value and sign of zero
      for (int x = 0; x < w; ++x)
        o[x] = 0.f + t0 * c[x];
    else
      for (int x = 0; x < w; ++x)
        o[x] += t0 * c[x];
    for (int j = 1; j <= r; ++j)
    {
      const float tj = gain * t[r + j];
      const float* a = in[std::max(k - j, 0)];
      const float* b = in[std::min(k + j, nd - 1)];
      for (int x = 0; x < w; ++x)
        o[x] += tj * (a[x] + b[x]);
    }
  }
}

inline void DisparityDog::recursiveAdd(const std::vector<const float*>& in, int w, float gain, std::vector<float*>& out,
                                       std::vector<std::vector<float>>& s) const
{
  // The recursion runs over the cost curve extended by `pad` replicated values at both ends, so that
  // its start-up transients fall outside the range and the result matches the replicated-border FIR.
  const int nd = static_cast<int>(in.size()), pad = broad_recursive_.pad;
  const int n = nd + 2 * pad;
  const Recursive& g = broad_recursive_;
  s.resize(n);
  for (auto& row : s)
    row.resize(w);
  auto input = [&](int e) { return in[std::clamp(e - pad, 0, nd - 1)]; };
  for (int e = 0; e < n; ++e)
  {
    const float* c = input(e);
    const float* w1 = e >= 1 ? s[e - 1].data() : input(0);
    const float* w2 = e >= 2 ? s[e - 2].data() : input(0);
    const float* w3 = e >= 3 ? s[e - 3].data() : input(0);
    float* o = s[e].data();
    for (int x = 0; x < w; ++x)
      o[x] = g.b * c[x] + g.a1 * w1[x] + g.a2 * w2[x] + g.a3 * w3[x];
  }
  std::vector<float> last(s[n - 1]);
  for (int e = n - 1; e >= pad; --e)  // the left pad's anti-causal values are never read
  {
    const float* y1 = e + 1 < n ? s[e + 1].data() : last.data();
    const float* y2 = e + 2 < n ? s[e + 2].data() : last.data();
    const float* y3 = e + 3 < n ? s[e + 3].data() : last.data();
    float* o = s[e].data();
    for (int x = 0; x < w; ++x)
      o[x] = g.b * o[x] + g.a1 * y1[x] + g.a2 * y2[x] + g.a3 * y3[x];
  }
  for (int k = 0; k < nd; ++k)
  {
    float* o = out[k];
    const float* v = s[k + pad].data();
    for (int x = 0; x < w; ++x)
      o[x] += gain * v[x];
  }
}

void DisparityDog::setSimd(CostSimd simd)
{
  requireCostSimd(simd);
  simd_ = simd;
}

void DisparityDog::applyRow(const std::vector<const float*>& in, int w, std::vector<float*>& out,
                            std::vector<std::vector<float>>& scratch) const
{
  if (in.empty() || in.size() != out.size() || w < 0)
    throw std::invalid_argument("DisparityDog::applyRow: needs one input and one output row per disparity (" +
                                std::to_string(in.size()) + " and " + std::to_string(out.size()) + "), w >= 0");
  if (simd_ == CostSimd::kAvx512)
    filterRowAvx512(in, w, out, scratch);
  else if (simd_ == CostSimd::kAvx2)
    filterRowAvx2(in, w, out, scratch);
  else
    filterRowGeneric(in, w, out, scratch);
}

// The same body three times, each with every call inlined (flatten) so that its loops are compiled for the
// wrapper's instruction set (the callees are `inline`: an exported member of a -fPIC library could be
// interposed, and GCC does not inline those). No FMA (-ffp-contract=off): each product and sum rounds as in
// the generic code.
__attribute__((target("avx2"), flatten)) void DisparityDog::filterRowAvx2(
    const std::vector<const float*>& in, int w, std::vector<float*>& out,
    std::vector<std::vector<float>>& scratch) const
{
  filterRowBody(in, w, out, scratch);
}

BIOVISION_STEREO_AVX512_CLONE void DisparityDog::filterRowAvx512(const std::vector<const float*>& in, int w,
                                                                 std::vector<float*>& out,
                                                                 std::vector<std::vector<float>>& scratch) const
{
  filterRowBody(in, w, out, scratch);
}

__attribute__((flatten)) void DisparityDog::filterRowGeneric(const std::vector<const float*>& in, int w,
                                                             std::vector<float*>& out,
                                                             std::vector<std::vector<float>>& scratch) const
{
  filterRowBody(in, w, out, scratch);
}

inline void DisparityDog::filterRowBody(const std::vector<const float*>& in, int w, std::vector<float*>& out,
                                        std::vector<std::vector<float>>& scratch) const
{
  // The narrow FIR's first term assigns: no zeroing pass over the output rows first.
  firAdd(in, w, narrow_, static_cast<float>(tau_ * alpha_), out, true);
  if (broad_recursive_.enabled)
    recursiveAdd(in, w, static_cast<float>(-tau_ * beta_), out, scratch);
  else
    firAdd(in, w, broad_, static_cast<float>(-tau_ * beta_), out);
}

void DisparityDog::apply(const CostVolume& in, CostVolume& out) const
{
  out = CostVolume(in.size(), in.disparities(), 0.f);
  const int nd = in.disparities(), w = in.size().width;
  if (nd == 0)
    return;  // nothing to filter
  biovision_common::parallelFor(cv::Range(0, in.size().height), [&](const cv::Range& rows) {
    std::vector<const float*> i(nd);
    std::vector<float*> o(nd);
    std::vector<std::vector<float>> scratch;
    for (int y = rows.start; y < rows.end; ++y)
    {
      for (int k = 0; k < nd; ++k)
      {
        i[k] = in.slice(k).ptr<float>(y);
        o[k] = out.slice(k).ptr<float>(y);
      }
      applyRow(i, w, o, scratch);
    }
  });
}

void DisparityDog::applyInPlace(CostVolume& costs) const
{
  const int nd = costs.disparities(), w = costs.size().width;
  if (nd == 0)
    return;
  biovision_common::parallelFor(cv::Range(0, costs.size().height), [&](const cv::Range& rows) {
    std::vector<float> copy(size_t(nd) * w);  // one image row of the volume: the filter's input
    std::vector<const float*> i(nd);
    std::vector<float*> o(nd);
    std::vector<std::vector<float>> scratch;
    for (int k = 0; k < nd; ++k)
      i[k] = copy.data() + size_t(k) * w;
    for (int y = rows.start; y < rows.end; ++y)
    {
      for (int k = 0; k < nd; ++k)
      {
        o[k] = costs.slice(k).ptr<float>(y);
        std::copy(o[k], o[k] + w, copy.data() + size_t(k) * w);
      }
      applyRow(i, w, o, scratch);
    }
  });
}

void DisparityDog::applyReference(const CostVolume& in, CostVolume& out) const
{
  out = CostVolume(in.size(), in.disparities(), 0.f);
  const int nd = in.disparities(), w = in.size().width;
  if (nd == 0)
    return;  // nothing to filter
  std::vector<const float*> i(nd);
  std::vector<float*> o(nd);
  for (int y = 0; y < in.size().height; ++y)
  {
    for (int k = 0; k < nd; ++k)
    {
      i[k] = in.slice(k).ptr<float>(y);
      o[k] = out.slice(k).ptr<float>(y);
    }
    firAdd(i, w, narrow_, static_cast<float>(tau_ * alpha_), o);
    firAdd(i, w, broad_, static_cast<float>(-tau_ * beta_), o);
  }
}
}  // namespace biovision_stereo
