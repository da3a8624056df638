#include "biovision_stereo/semi_global_aggregation.hpp"

#include <immintrin.h>

#include <algorithm>
#include <stdexcept>
#include <string>
#include <vector>

#include <opencv2/core/utility.hpp>

#include "biovision_common/cpu_features.hpp"
#include "biovision_common/parallel_arena.hpp"

namespace biovision_stereo
{
namespace
{
constexpr std::uint16_t kBlocked = 0xFFFF;  // lanes outside 0..disparities-1: never the minimum
constexpr int kGuard = 16;                  // blocked values before and after every path buffer

/// One path step at one pixel: out[d] = c[d] + min(prev[d], prev[d-1] + P1, prev[d+1] + P1, prev_min + P2)
/// - prev_min for d < nd, kBlocked above; sum[d] += out[d] (saturating), or sum[d] = out[d] for the first
/// path of a sweep at a pixel (`first`: no zero-fill of the sums). prev[-1] and prev[stride] must be
/// readable and kBlocked (or a blocked lane of a neighbour). Returns the minimum of out over 0..nd-1.
struct Step
{
  int nd, stride;
  std::uint16_t p1;
};

inline std::uint16_t stepGeneric(const Step& s, const std::uint16_t* c, const std::uint16_t* prev,
                                 std::uint16_t prev_min, std::uint16_t p2, std::uint16_t* out, std::uint16_t* sum,
                                 bool first)
{
  const std::uint32_t jump = std::uint32_t(prev_min) + p2;
  std::uint16_t m = kBlocked;
  for (int d = 0; d < s.nd; ++d)
  {
    const std::uint32_t v = std::min(std::min<std::uint32_t>(prev[d], jump),
                                     std::min<std::uint32_t>(prev[d - 1], prev[d + 1]) + s.p1);
    const auto l = static_cast<std::uint16_t>(c[d] + v - prev_min);
    out[d] = l;
    m = std::min(m, l);
    sum[d] = first ? l : static_cast<std::uint16_t>(std::min<std::uint32_t>(std::uint32_t(sum[d]) + l, kBlocked));
  }
  for (int d = s.nd; d < s.stride; ++d)
  {
    out[d] = kBlocked;
    sum[d] = kBlocked;
  }
  return m;
}

/// One pixel's steps on all paths of a sweep that reach it, with 16 lanes of AVX2: the values of
/// stepGeneric for path 0 with first = true, then the others with first = false (the same saturating sums
/// in the same order), but the sum stays in a register and is stored once per vector and the pixel's costs
/// are loaded once: per 16 lanes and 4 paths, 4 x (3 loads + 1 store) + 2 memory operations instead of
/// 4 x (5 loads + 2 stores) when each path's step loaded and stored the sum itself.
struct PathStep
{
  const std::uint16_t* prev;  // the predecessor's L_r (kBlocked guards at [-1] and [stride])
  std::uint16_t prev_min;     // its minimum over 0..nd-1
  std::uint16_t* out;         // this pixel's L_r
};

template <int kPaths>
__attribute__((target("avx2"))) inline void stepsAvx2(const Step& s, const std::uint16_t* c,
                                                      const PathStep (&paths)[kPaths], std::uint16_t p2,
                                                      std::uint16_t* sum, std::uint16_t (&mins)[kPaths])
{
  const __m256i vp1 = _mm256_set1_epi16(static_cast<short>(s.p1));
  const __m256i lane = _mm256_setr_epi16(0, 1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12, 13, 14, 15);
  __m256i vjump[kPaths], vmin[kPaths], m[kPaths];
  for (int p = 0; p < kPaths; ++p)
  {
    vjump[p] = _mm256_set1_epi16(static_cast<short>(paths[p].prev_min + p2));
    vmin[p] = _mm256_set1_epi16(static_cast<short>(paths[p].prev_min));
    m[p] = _mm256_set1_epi16(static_cast<short>(kBlocked));
  }
  for (int d = 0; d < s.stride; d += 16)
  {
    const __m256i cost = _mm256_loadu_si256(reinterpret_cast<const __m256i*>(c + d));
    const bool last = d + 16 > s.nd;  // blocked lanes d + i >= nd (only the last vector holds any)
    const __m256i blocked = last ? _mm256_cmpgt_epi16(lane, _mm256_set1_epi16(static_cast<short>(s.nd - d - 1)))
                                 : _mm256_setzero_si256();
    __m256i total = _mm256_setzero_si256();
    for (int p = 0; p < kPaths; ++p)
    {
      const std::uint16_t* prev = paths[p].prev;
      const __m256i a = _mm256_loadu_si256(reinterpret_cast<const __m256i*>(prev + d));
      const __m256i b = _mm256_adds_epu16(_mm256_loadu_si256(reinterpret_cast<const __m256i*>(prev + d - 1)), vp1);
      const __m256i e = _mm256_adds_epu16(_mm256_loadu_si256(reinterpret_cast<const __m256i*>(prev + d + 1)), vp1);
      const __m256i v = _mm256_min_epu16(_mm256_min_epu16(a, vjump[p]), _mm256_min_epu16(b, e));
      __m256i l = _mm256_add_epi16(cost, _mm256_sub_epi16(v, vmin[p]));
      if (last)
        l = _mm256_or_si256(l, blocked);
      _mm256_storeu_si256(reinterpret_cast<__m256i*>(paths[p].out + d), l);
      m[p] = _mm256_min_epu16(m[p], l);
      total = p == 0 ? l : _mm256_adds_epu16(total, l);
    }
    _mm256_storeu_si256(reinterpret_cast<__m256i*>(sum + d), total);
  }
  for (int p = 0; p < kPaths; ++p)
  {
    const __m128i m8 = _mm_min_epu16(_mm256_castsi256_si128(m[p]), _mm256_extracti128_si256(m[p], 1));
    mins[p] = static_cast<std::uint16_t>(_mm_cvtsi128_si32(_mm_minpos_epu16(m8)) & 0xFFFF);
  }
}

/// stepsAvx2's generic counterpart: the steps one after the other.
template <int kPaths>
inline void stepsGeneric(const Step& s, const std::uint16_t* c, const PathStep (&paths)[kPaths], std::uint16_t p2,
                         std::uint16_t* sum, std::uint16_t (&mins)[kPaths])
{
  for (int p = 0; p < kPaths; ++p)
    mins[p] = stepGeneric(s, c, paths[p].prev, paths[p].prev_min, p2, paths[p].out, sum, p == 0);
}

/// A path buffer of n pixels with guards of blocked values at both ends.
class PathRow
{
public:
  PathRow(int n, int stride) : stride_(stride), data_(size_t(n) * stride + 2 * kGuard, kBlocked), min_(n, 0) {}
  std::uint16_t* at(int x) { return data_.data() + kGuard + size_t(x) * stride_; }
  std::uint16_t& minAt(int x) { return min_[x]; }

private:
  int stride_;
  std::vector<std::uint16_t> data_;
  std::vector<std::uint16_t> min_;
};

// Flattened into the two entry points below, so that the AVX2 one compiles its loops (and inlines
// stepsAvx2) for AVX2 while the generic one stays on the baseline instruction set.
template <bool kAvx2, int kVertical>
void sweepPaths(const std::vector<std::uint16_t>& costs, int w, int h, int nd, const cv::Mat& barriers, int p1, int p2,
                int p2_barrier, bool backward, std::vector<std::uint16_t>& sums)
{
  constexpr int kPaths = 1 + kVertical;  // along the row, then from the previous row
  const int stride = SemiGlobalAggregation::stride(nd);
  const Step s{nd, stride, static_cast<std::uint16_t>(p1)};
  const auto p2_edge = static_cast<std::uint16_t>(std::max(p1, p2_barrier));
  sums.resize(size_t(w) * h * stride);  // every value is stored by the first path step below
  // The predecessor of a path's first pixel: zero costs, so that L = C there.
  PathRow start(1, stride);
  std::fill(start.at(0), start.at(0) + nd, 0);
  std::vector<PathRow> prev(kVertical, PathRow(w, stride)), cur(kVertical, PathRow(w, stride));
  PathRow horizontal(2, stride);
  const int dir = backward ? -1 : 1;  // forward: predecessors left and above; backward: right and below
  PathStep paths[kPaths];
  std::uint16_t mins[kPaths];
  for (int i = 0; i < h; ++i)
  {
    const int y = backward ? h - 1 - i : i;
    const uchar* barrier_row = barriers.empty() ? nullptr : barriers.ptr<uchar>(y);
    for (int j = 0; j < w; ++j)
    {
      const int x = backward ? w - 1 - j : j;
      const size_t index = (size_t(y) * w + x) * stride;
      const std::uint16_t pen2 = barrier_row && barrier_row[x] ? p2_edge : static_cast<std::uint16_t>(p2);
      // Along the row: ping-pong between two buffers (a step must not overwrite its predecessor).
      paths[0] = j == 0 ? PathStep{start.at(0), 0, horizontal.at(0)}
                        : PathStep{horizontal.at((j - 1) & 1), horizontal.minAt(0), horizontal.at(j & 1)};
      // From the previous row: predecessor columns x - dir (diagonal), x, x + dir (other diagonal).
      for (int v = 0; v < kVertical; ++v)
      {
        const int qx = x + (kVertical == 3 ? (v - 1) * dir : 0);
        const bool first = i == 0 || qx < 0 || qx >= w;
        paths[1 + v] = first ? PathStep{start.at(0), 0, cur[v].at(x)}
                             : PathStep{prev[v].at(qx), prev[v].minAt(qx), cur[v].at(x)};
      }
      if constexpr (kAvx2)
        stepsAvx2(s, costs.data() + index, paths, pen2, sums.data() + index, mins);
      else
        stepsGeneric(s, costs.data() + index, paths, pen2, sums.data() + index, mins);
      horizontal.minAt(0) = mins[0];
      for (int v = 0; v < kVertical; ++v)
        cur[v].minAt(x) = mins[1 + v];
    }
    std::swap(prev, cur);
  }
}

template <bool kAvx2>
void sweep(const std::vector<std::uint16_t>& costs, int w, int h, int nd, const cv::Mat& barriers, int p1, int p2,
           int p2_barrier, int paths, bool backward, std::vector<std::uint16_t>& sums)
{
  if (paths == 8)  // (diagonal, straight, other diagonal) from the previous row
    sweepPaths<kAvx2, 3>(costs, w, h, nd, barriers, p1, p2, p2_barrier, backward, sums);
  else
    sweepPaths<kAvx2, 1>(costs, w, h, nd, barriers, p1, p2, p2_barrier, backward, sums);
}
__attribute__((target("avx2"), flatten)) void sweepAvx2(const std::vector<std::uint16_t>& costs, int w, int h, int nd,
                                                        const cv::Mat& barriers, int p1, int p2, int p2_barrier,
                                                        int paths, bool backward, std::vector<std::uint16_t>& sums)
{
  sweep<true>(costs, w, h, nd, barriers, p1, p2, p2_barrier, paths, backward, sums);
}

__attribute__((flatten)) void sweepGeneric(const std::vector<std::uint16_t>& costs, int w, int h, int nd,
                                           const cv::Mat& barriers, int p1, int p2, int p2_barrier, int paths,
                                           bool backward, std::vector<std::uint16_t>& sums)
{
  sweep<false>(costs, w, h, nd, barriers, p1, p2, p2_barrier, paths, backward, sums);
}

/// S = forward + backward and its winners on image row y (see winners()). Written for the compiler to
/// vectorise (min reductions, a branch-free masked update); compiled twice, generic and AVX2.
struct WinnerRows
{
  const std::uint16_t* forward;
  const std::uint16_t* backward;
  int width, disparities, stride;
  bool subpixel;
  cv::Mat* left;
  cv::Mat* right_k;
};

inline void winnerRows(const WinnerRows& in, int y0, int y1)
{
  const int w = in.width, nd = in.disparities, stride = in.stride;
  std::vector<std::uint16_t> sum(stride), best_right(w);
  std::vector<std::int16_t> k_right(w);  // disparities < stride <= 2^15 (16-bit volumes)
  for (int y = y0; y < y1; ++y)
  {
    std::fill(best_right.begin(), best_right.end(), kBlocked);
    std::fill(k_right.begin(), k_right.end(), std::int16_t(-1));
    float* ld = in.left->ptr<float>(y);
    for (int x = 0; x < w; ++x)
    {
      const size_t index = (size_t(y) * w + x) * stride;
      const std::uint16_t* f = in.forward + index;
      const std::uint16_t* b = in.backward + index;
      const int kmax = std::min(nd - 1, x);  // a disparity must stay inside the right image: k <= x
      std::uint16_t least = kBlocked;
      for (int k = 0; k <= kmax; ++k)
      {
        // Each of forward, backward <= 4 (kMaxCost + P2) <= 16376: the sum fits 16 bits.
        const auto s = static_cast<std::uint16_t>(f[k] + b[k]);
        sum[k] = s;
        least = std::min(least, s);
      }
      int best = 0;
      while (sum[best] != least)
        ++best;
      // Right image pixel x - k sees left pixel x at disparity k; i runs over those pixels left to right.
      std::uint16_t* br = best_right.data() + (x - kmax);
      std::int16_t* kr = k_right.data() + (x - kmax);
      for (int i = 0; i <= kmax; ++i)
      {
        const std::uint16_t s = sum[kmax - i];
        const bool better = s < br[i];
        br[i] = better ? s : br[i];
        kr[i] = better ? static_cast<std::int16_t>(kmax - i) : kr[i];
      }
      float d = static_cast<float>(best);
      if (in.subpixel && best > 0 && best < kmax)
      {
        const float cm = float(sum[best - 1]), c0 = float(sum[best]), cp = float(sum[best + 1]);
        const float den = cm - 2 * c0 + cp;
        if (den > 0)
          d += std::clamp(0.5f * (cm - cp) / den, -0.5f, 0.5f);
      }
      ld[x] = d;
    }
    std::copy(k_right.begin(), k_right.end(), in.right_k->ptr<int>(y));
  }
}

__attribute__((flatten)) void winnerRowsGeneric(const WinnerRows& in, int y0, int y1)
{
  winnerRows(in, y0, y1);
}

__attribute__((target("avx2"), flatten)) void winnerRowsAvx2(const WinnerRows& in, int y0, int y1)
{
  winnerRows(in, y0, y1);
}

/// One image row of toPixelMajor(): c[k] points at row y of slice k.
void pixelMajorRow(const float* const* c, int w, int nd, int stride, float lowest, float scale, std::uint16_t* row)
{
  const float top = SemiGlobalAggregation::kMaxCost;
  const auto convert = [&](float v) { return static_cast<std::uint16_t>(std::min((v - lowest) * scale + 0.5f, top)); };
  int k0 = 0;
#if defined(__SSE2__)
  // 8 disparities x 8 pixels at a time: convert along x, then an 8x8 16-bit transpose to pixel-major.
  // The same float operations as convert() (min_ps differs only on NaN, which costs never are).
  const __m128 vlow = _mm_set1_ps(lowest), vscale = _mm_set1_ps(scale), vhalf = _mm_set1_ps(0.5f),
               vtop = _mm_set1_ps(top);
  const auto convert4 = [&](const float* p) {
    return _mm_cvttps_epi32(_mm_min_ps(_mm_add_ps(_mm_mul_ps(_mm_sub_ps(_mm_loadu_ps(p), vlow), vscale), vhalf), vtop));
  };
  for (; k0 + 8 <= nd; k0 += 8)
  {
    int x = 0;
    for (; x + 8 <= w; x += 8)
    {
      __m128i v[8];  // v[i]: pixels x..x+7 at disparity k0 + i (values <= kMaxCost: signed packing is exact)
      for (int i = 0; i < 8; ++i)
        v[i] = _mm_packs_epi32(convert4(c[k0 + i] + x), convert4(c[k0 + i] + x + 4));
      __m128i t[8], u[8];
      for (int i = 0; i < 4; ++i)
      {
        t[2 * i] = _mm_unpacklo_epi16(v[2 * i], v[2 * i + 1]);
        t[2 * i + 1] = _mm_unpackhi_epi16(v[2 * i], v[2 * i + 1]);
      }
      for (int i = 0; i < 2; ++i)
      {
        u[4 * i] = _mm_unpacklo_epi32(t[4 * i], t[4 * i + 2]);
        u[4 * i + 1] = _mm_unpackhi_epi32(t[4 * i], t[4 * i + 2]);
        u[4 * i + 2] = _mm_unpacklo_epi32(t[4 * i + 1], t[4 * i + 3]);
        u[4 * i + 3] = _mm_unpackhi_epi32(t[4 * i + 1], t[4 * i + 3]);
      }
      for (int i = 0; i < 4; ++i)
      {
        _mm_storeu_si128(reinterpret_cast<__m128i*>(row + size_t(x + 2 * i) * stride + k0),
                         _mm_unpacklo_epi64(u[i], u[4 + i]));
        _mm_storeu_si128(reinterpret_cast<__m128i*>(row + size_t(x + 2 * i + 1) * stride + k0),
                         _mm_unpackhi_epi64(u[i], u[4 + i]));
      }
    }
    for (; x < w; ++x)
      for (int k = k0; k < k0 + 8; ++k)
        row[size_t(x) * stride + k] = convert(c[k][x]);
  }
#endif
  for (int k = k0; k < nd; ++k)
    for (int x = 0; x < w; ++x)
      row[size_t(x) * stride + k] = convert(c[k][x]);
}
}  // namespace

SemiGlobalAggregation::SemiGlobalAggregation(int p1, int p2, int p2_barrier, int paths)
  : p1_(p1), p2_(p2), p2_barrier_(p2_barrier), paths_(paths)
{
  if (p1 < 0 || p1 > p2 || p2 > kMaxCost)
    throw std::invalid_argument("SemiGlobalAggregation: need 0 <= P1 <= P2 <= " + std::to_string(kMaxCost));
  if (p2_barrier < 0 || p2_barrier > kMaxCost)
    throw std::invalid_argument("SemiGlobalAggregation: P2 at barriers outside [0, " + std::to_string(kMaxCost) + "]");
  if (paths != 4 && paths != 8)
    throw std::invalid_argument("SemiGlobalAggregation: paths must be 4 or 8");
}

std::vector<SemiGlobalAggregation::Simd> SemiGlobalAggregation::availableSimds()
{
  std::vector<Simd> paths{Simd::kGeneric};
  if (biovision_common::CpuFeatures::host().avx2)
    paths.push_back(Simd::kAvx2);
  return paths;
}

SemiGlobalAggregation::Simd SemiGlobalAggregation::bestSimd()
{
  return availableSimds().back();
}

std::string SemiGlobalAggregation::name(Simd simd)
{
  return simd == Simd::kAvx2 ? "avx2" : "generic";
}

void SemiGlobalAggregation::aggregate(const std::vector<std::uint16_t>& costs, int width, int height, int disparities,
                                      const cv::Mat& barriers, std::vector<std::uint16_t>& forward,
                                      std::vector<std::uint16_t>& backward, Simd simd) const
{
  if (width < 1 || height < 1 || disparities < 1 || costs.size() != size_t(width) * height * stride(disparities))
    throw std::invalid_argument("SemiGlobalAggregation: cost volume size does not match width x height x stride");
  if (!barriers.empty() && (barriers.type() != CV_8UC1 || barriers.cols != width || barriers.rows != height))
    throw std::invalid_argument("SemiGlobalAggregation: barriers must be empty or CV_8U of the volume's size");
  if (simd == Simd::kAvx2 && !biovision_common::CpuFeatures::host().avx2)
    throw std::invalid_argument("SemiGlobalAggregation: the AVX2 path needs a CPU with AVX2");
  biovision_common::parallelFor(cv::Range(0, 2), [&](const cv::Range& r) {
    for (int b = r.start; b < r.end; ++b)
    {
      std::vector<std::uint16_t>& sums = b ? backward : forward;
      if (simd == Simd::kAvx2)
        sweepAvx2(costs, width, height, disparities, barriers, p1_, p2_, p2_barrier_, paths_, b == 1, sums);
      else
        sweepGeneric(costs, width, height, disparities, barriers, p1_, p2_, p2_barrier_, paths_, b == 1, sums);
    }
  });
}

void SemiGlobalAggregation::toPixelMajor(const CostVolume& costs, float lowest, float scale,
                                         std::vector<std::uint16_t>& out)
{
  const int w = costs.size().width, h = costs.size().height, nd = costs.disparities(), stride_ = stride(nd);
  out.resize(size_t(w) * h * stride_);
  biovision_common::parallelFor(cv::Range(0, h), [&](const cv::Range& rows) {
    std::vector<const float*> c(nd);
    for (int y = rows.start; y < rows.end; ++y)
    {
      for (int k = 0; k < nd; ++k)
        c[k] = costs.slice(k).ptr<float>(y);
      pixelMajorRow(c.data(), w, nd, stride_, lowest, scale, out.data() + size_t(y) * w * stride_);
    }
  });
}

void SemiGlobalAggregation::winners(const std::vector<std::uint16_t>& forward,
                                    const std::vector<std::uint16_t>& backward, int width, int height, int disparities,
                                    bool subpixel, cv::Mat& left, cv::Mat& right_k, Simd simd)
{
  const size_t n = size_t(width) * height * stride(disparities);
  // The right view's winners are kept in 16 bits (as the volumes' values are).
  if (disparities < 1 || disparities > 32767)
    throw std::invalid_argument("SemiGlobalAggregation::winners: disparities " + std::to_string(disparities) +
                                " outside [1, 32767]");
  if (width < 1 || height < 1 || forward.size() != n || backward.size() != n)
    throw std::invalid_argument("SemiGlobalAggregation::winners: sums do not match " + std::to_string(width) + "x" +
                                std::to_string(height) + "x" + std::to_string(disparities));
  if (simd == Simd::kAvx2 && !biovision_common::CpuFeatures::host().avx2)
    throw std::invalid_argument("SemiGlobalAggregation::winners: this CPU has no AVX2");
  left.create(height, width, CV_32F);
  right_k.create(height, width, CV_32S);
  const WinnerRows in{forward.data(),      backward.data(), width, disparities,
                      stride(disparities), subpixel,        &left, &right_k};
  biovision_common::parallelFor(cv::Range(0, height), [&](const cv::Range& rows) {
    if (simd == Simd::kAvx2)
      winnerRowsAvx2(in, rows.start, rows.end);
    else
      winnerRowsGeneric(in, rows.start, rows.end);
  });
}
}  // namespace biovision_stereo
