#include "biovision_stereo/bio_bin_matcher.hpp"
#include "biovision_stereo/occlusion_filling.hpp"
#include "avx512_clone.hpp"
#include "hamming_window.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

#include <immintrin.h>

#include <opencv2/core/utility.hpp>
#include <opencv2/imgproc.hpp>

#include "biovision_common/area_downsampling.hpp"
#include "biovision_stereo/disparity_dog.hpp"
#include "biovision_stereo/hamming.hpp"
#include "biovision_stereo/iterative_spatial_filter.hpp"
#include "biovision_stereo/linear_resampling.hpp"
#include "biovision_stereo/pixel_descriptor.hpp"
#include "biovision_stereo/semi_global_aggregation.hpp"
#include "biovision_v1/end_stopped_cells.hpp"
#include "biovision_v1/line_edge_detector.hpp"
#include "biovision_v1/simple_cell_bank.hpp"
#include "biovision_common/parallel_arena.hpp"

namespace biovision_stereo
{
namespace
{
using Clock = std::chrono::steady_clock;
double msSince(Clock::time_point t)
{
  return std::chrono::duration<double, std::milli>(Clock::now() - t).count();
}

constexpr float kMaxHamming = 256.f;
constexpr int kNoMatchSad = 3 * 255 + 1;  // SAD of a disparity that leaves the right image

cv::Mat toBgr8(const cv::Mat& in, const char* which)
{
  if (in.empty())
    throw std::invalid_argument(std::string("BioBin: ") + which + " image is empty");
  if (in.depth() != CV_8U)
    throw std::invalid_argument(std::string("BioBin: ") + which + " image must be 8-bit");
  cv::Mat bgr;
  switch (in.channels())
  {
    case 1:
      cv::cvtColor(in, bgr, cv::COLOR_GRAY2BGR);
      break;
    case 3:
      bgr = in;
      break;
    case 4:
      cv::cvtColor(in, bgr, cv::COLOR_BGRA2BGR);
      break;
    default:
      throw std::invalid_argument(std::string("BioBin: ") + which + " image has an unsupported channel count");
  }
  return bgr;
}

/// Steps (b), (d), the kappa modulation and (e) of levelCosts() for image rows [y0, y1): Hamming costs of
/// the codes, the planar L*a*b* SAD, its N_th smallest per pixel and the colour-masked cost of one row in
/// a row buffer, then the DoG along disparity from that buffer into `costs` while the row is in the cache
/// (one write of the volume instead of a write, a copy and a rewrite), and each row's largest cost.
struct MaskedCostRows
{
  const cv::Mat* left_planes;  // 3 planes of 8-bit L*a*b*
  const cv::Mat* right_planes;
  const PixelDescriptorImage* left_codes;
  const PixelDescriptorImage* right_codes;
  const DisparityDog* dog;
  CostVolume* costs;
  float* row_max;  // [h]: the largest filtered cost of each image row
  int w, nd, n_th;
  float damp, boost;
};

inline void maskedCostRows(const MaskedCostRows& in, int y0, int y1)
{
  const int w = in.w, nd = in.nd, n_th = in.n_th;
  const float damp = in.damp, boost = in.boost;
  const cv::Mat *left_planes = in.left_planes, *right_planes = in.right_planes;
  const PixelDescriptorImage &left_codes = *in.left_codes, &right_codes = *in.right_codes;
  CostVolume& costs = *in.costs;
  // The rows' buffers are the thread's, kept between calls: a stripe of rows per call, many calls per
  // frame (malloc and free were 4.5% of the fast mode). Every value is written before it is read.
  struct Scratch
  {
    // Signed 16 bits (SAD <= 766): SSE2 has signed 16-bit min/max/compare, so the loops below vectorise
    // on the baseline instruction set (unsigned ones did not).
    std::vector<std::int16_t> sad, carry;
    std::vector<std::vector<std::int16_t>> smallest;
    std::vector<float> masked;  // the row's colour-masked costs, disparity-major: the DoG's input
    HammingWindowScratch hamming;
    std::vector<const float*> dog_in;
    std::vector<float*> dog_out;
    std::vector<std::vector<float>> dog;
  };
  thread_local Scratch scratch;
  scratch.sad.resize(size_t(nd) * w);
  scratch.carry.resize(w);
  scratch.smallest.resize(n_th);
  for (auto& row : scratch.smallest)
    row.resize(w);
  scratch.masked.resize(size_t(nd) * w);
  scratch.dog_in.resize(nd);
  scratch.dog_out.resize(nd);
  std::vector<std::int16_t>&sad = scratch.sad, &carry = scratch.carry;
  std::vector<std::vector<std::int16_t>>& smallest = scratch.smallest;
  std::vector<float>& masked = scratch.masked;
  HammingWindowScratch& hamming_scratch = scratch.hamming;
  const int h = left_codes.height();
  std::vector<const float*>& dog_in = scratch.dog_in;
  std::vector<float*>& dog_out = scratch.dog_out;
  std::vector<std::vector<float>>& dog_scratch = scratch.dog;
  for (int k = 0; k < nd; ++k)
    dog_in[k] = &masked[size_t(k) * w];
  for (int y = y0; y < y1; ++y)
  {
    const uchar *l0 = left_planes[0].ptr(y), *l1 = left_planes[1].ptr(y), *l2 = left_planes[2].ptr(y);
    const uchar *r0 = right_planes[0].ptr(y), *r1 = right_planes[1].ptr(y), *r2 = right_planes[2].ptr(y);
    const int up = std::max(y - 1, 0), down = std::min(y + 1, h - 1);
    const std::uint8_t *la = left_codes.comparisons(up), *lc = left_codes.comparisons(y),
                       *lb = left_codes.comparisons(down);
    const std::uint8_t *ra = right_codes.comparisons(up), *rc = right_codes.comparisons(y),
                       *rb = right_codes.comparisons(down);
    for (int k = 0; k < nd; ++k)
    {
      std::int16_t* s = &sad[size_t(k) * w];
      for (int x = 0; x < std::min(k, w); ++x)
        s[x] = kNoMatchSad;
      for (int x = k; x < w; ++x)
        s[x] = static_cast<std::int16_t>(std::abs(l0[x] - r0[x - k]) + std::abs(l1[x] - r1[x - k]) +
                                         std::abs(l2[x] - r2[x - k]));
      hammingWindowRow(la, lc, lb, ra, rc, rb, w, k, kMaxHamming, &masked[size_t(k) * w], hamming_scratch);
    }
    // BT = the N_th smallest SAD of each pixel: a compare-exchange chain over x, smallest[0..n_th) kept
    // sorted per pixel, each disparity's SAD carried down the chain (exact, ties included).
    for (auto& row : smallest)
      std::fill(row.begin(), row.end(), std::numeric_limits<std::int16_t>::max());
    for (int k = 0; k < nd; ++k)
    {
      const std::int16_t* s = &sad[size_t(k) * w];
      std::copy(s, s + w, carry.begin());
      for (int i = 0; i < n_th; ++i)
      {
        std::int16_t* m = smallest[i].data();
        std::int16_t* v = carry.data();
        for (int x = 0; x < w; ++x)
        {
          const std::int16_t lo = std::min(m[x], v[x]);
          v[x] = std::max(m[x], v[x]);
          m[x] = lo;
        }
      }
    }
    // phi = 1 where SAD <= BT: M (1 - kappa); else M (1 + kappa).
    const std::int16_t* threshold = smallest[n_th - 1].data();
    for (int k = 0; k < nd; ++k)
    {
      float* c = &masked[size_t(k) * w];
      const std::int16_t* s = &sad[size_t(k) * w];
      for (int x = 0; x < w; ++x)
        c[x] *= s[x] <= threshold[x] ? damp : boost;
      dog_out[k] = costs.slice(k).ptr<float>(y);
    }
    in.dog->applyRow(dog_in, w, dog_out, dog_scratch);
    in.row_max[y] = costs.max(y, y + 1);
  }
}

// The same rows compiled three times (every call inlined into each wrapper): AVX-512 (32 lanes of int16,
// 16 of float), AVX2 (16 and 8) and the baseline instruction set, the fallback on every CPU; no FMA, so
// the same bits.
__attribute__((target("avx2"), flatten)) void maskedCostRowsAvx2(const MaskedCostRows& in, int y0, int y1)
{
  maskedCostRows(in, y0, y1);
}

BIOVISION_STEREO_AVX512_CLONE void maskedCostRowsAvx512(const MaskedCostRows& in, int y0, int y1)
{
  maskedCostRows(in, y0, y1);
}

__attribute__((flatten)) void maskedCostRowsGeneric(const MaskedCostRows& in, int y0, int y1)
{
  maskedCostRows(in, y0, y1);
}

/// Fusion of one slice row: costs above `level` averaged with the coarser level's upsampled costs.
inline void fuseRow(float* cr, const float* ur, int w, float level)
{
  for (int x = 0; x < w; ++x)
    cr[x] = cr[x] > level ? 0.5f * cr[x] + 0.5f * ur[x] : cr[x];
}

/// A fused slice and its least value (NaN ignored): the coarser level's slice `mixed` resampled to the
/// slice's size one row at a time (LinearResampling: cv::resize's bilinear values, bit for bit), each row
/// averaged in and its least value taken while it is in the cache; neither the upsampled slice nor a pass of
/// its own for the aggregation's offset.
inline float fuseSlice(cv::Mat& c, const cv::Mat& mixed, const LinearResampling& resampling,
                       std::vector<float>& scratch, float level)
{
  float lowest = HUGE_VALF;
  resampling.forEachRow(mixed, scratch, [&](int y, const float* up) {
    fuseRow(c.ptr<float>(y), up, c.cols, level);
    lowest = CostVolume::lowestOf(c.ptr<float>(y), c.cols, lowest);
  });
  return lowest;
}

__attribute__((target("avx2"), flatten)) float fuseSliceAvx2(cv::Mat& c, const cv::Mat& mixed,
                                                             const LinearResampling& resampling,
                                                             std::vector<float>& scratch, float level)
{
  return fuseSlice(c, mixed, resampling, scratch, level);
}

BIOVISION_STEREO_AVX512_CLONE float fuseSliceAvx512(cv::Mat& c, const cv::Mat& mixed,
                                                    const LinearResampling& resampling, std::vector<float>& scratch,
                                                    float level)
{
  return fuseSlice(c, mixed, resampling, scratch, level);
}

__attribute__((flatten)) float fuseSliceGeneric(cv::Mat& c, const cv::Mat& mixed, const LinearResampling& resampling,
                                                std::vector<float>& scratch, float level)
{
  return fuseSlice(c, mixed, resampling, scratch, level);
}

// Winner-take-all update of one slice row c (disparity k, valid from x = k) on both views: left pixel
// x keeps the lowest cost so far (best_cost, best), right pixel x - k likewise (best_right, right_k).
// Strict <: the lowest disparity wins a tie; a NaN cost never wins. i = x - k.
void updateWinnersGeneric(const float* c, int n, int k, float* best_cost, int* best, float* best_right, int* right_k)
{
  for (int i = 0; i < n; ++i)
  {
    if (c[i] < best_cost[i])
    {
      best_cost[i] = c[i];
      best[i] = k;
    }
    if (c[i] < best_right[i])
    {
      best_right[i] = c[i];
      right_k[i] = k;
    }
  }
}

// The same 8 pixels per step with blends (GCC keeps the scalar version's branches: 6% of the fast mode).
__attribute__((target("avx2"))) void updateWinnersAvx2(const float* c, int n, int k, float* best_cost, int* best,
                                                       float* best_right, int* right_k)
{
  const __m256i kk = _mm256_set1_epi32(k);
  int i = 0;
  for (; i + 8 <= n; i += 8)
  {
    const __m256 v = _mm256_loadu_ps(c + i), bl = _mm256_loadu_ps(best_cost + i), br = _mm256_loadu_ps(best_right + i);
    const __m256 left = _mm256_cmp_ps(v, bl, _CMP_LT_OQ), right = _mm256_cmp_ps(v, br, _CMP_LT_OQ);
    _mm256_storeu_ps(best_cost + i, _mm256_blendv_ps(bl, v, left));
    _mm256_storeu_ps(best_right + i, _mm256_blendv_ps(br, v, right));
    const __m256i kl = _mm256_loadu_si256(reinterpret_cast<const __m256i*>(best + i));
    const __m256i kr = _mm256_loadu_si256(reinterpret_cast<const __m256i*>(right_k + i));
    _mm256_storeu_si256(reinterpret_cast<__m256i*>(best + i), _mm256_blendv_epi8(kl, kk, _mm256_castps_si256(left)));
    _mm256_storeu_si256(reinterpret_cast<__m256i*>(right_k + i),
                        _mm256_blendv_epi8(kr, kk, _mm256_castps_si256(right)));
  }
  updateWinnersGeneric(c + i, n - i, k, best_cost + i, best + i, best_right + i, right_k + i);
}
}  // namespace

void BioBinMatcher::updateWinners(const float* cost, int n, int k, float* best_cost, int* best, float* best_right,
                                  int* right_k, CostSimd simd)
{
  requireCostSimd(simd);
  (simd == CostSimd::kGeneric ? updateWinnersGeneric : updateWinnersAvx2)(cost, n, k, best_cost, best, best_right,
                                                                          right_k);
}

BioBinMatcher::BioBinMatcher(const BioBinParameters& parameters)
  : parameters_(parameters),
    spatial_filter_(parameters.relaxation, parameters.stable_cost, parameters.changing_fraction,
                    parameters.max_iterations)
{
  parameters_.validate();
  resetCaches();
}

void BioBinMatcher::resetCaches()
{
  biovision_v1::GaborParameters gabor;
  gabor.wavelengths = {parameters_.base_wavelength};
  gabor.orientations = 8;
  biovision_v1::GaborParameters full = gabor;
  full.min_grid_wavelength = 0.0;  // the descriptor compares neighbouring pixels: full resolution
  const size_t levels = parameters_.wavelengths.size();
  odd_banks_.clear();
  barrier_banks_.clear();
  for (size_t s = 0; s < levels; ++s)
  {
    odd_banks_.push_back(std::make_unique<biovision_v1::SimpleCellBank>(full));
    barrier_banks_.push_back(std::make_unique<biovision_v1::SimpleCellBank>(gabor));
  }
  spare_.assign(levels, CostVolume());
  codes_.assign(levels, {});
  downsampling_.clear();
  downsampling_.resize(levels);
  std::vector<std::uint16_t>().swap(sgm_costs_);
  std::vector<std::uint16_t>().swap(sgm_forward_);
  std::vector<std::uint16_t>().swap(sgm_backward_);
  spatial_filter_ = IterativeSpatialFilter(parameters_.relaxation, parameters_.stable_cost,
                                           parameters_.changing_fraction, parameters_.max_iterations);
}

BioBinMatcher::~BioBinMatcher() = default;

void BioBinMatcher::setCostSimd(CostSimd simd)
{
  requireCostSimd(simd);
  cost_simd_ = simd;
}

cv::Size BioBinMatcher::levelSize(cv::Size input, size_t level) const
{
  const double sf = parameters_.scaleFactor(level);
  return cv::Size(std::max(1, static_cast<int>(std::lround(input.width / sf))),
                  std::max(1, static_cast<int>(std::lround(input.height / sf))));
}

std::array<std::vector<cv::Mat>, 2> BioBinMatcher::oddResponses(size_t level, const cv::Mat& left_gray,
                                                                const cv::Mat& right_gray)
{
  auto pairs = odd_banks_[level]->computeOddPairsBatch({left_gray, right_gray});
  return {std::move(pairs[0][0]), std::move(pairs[1][0])};
}

CostVolume BioBinMatcher::levelCosts(size_t level, const cv::Mat& left, const cv::Mat& right, int disparities,
                                     cv::Mat* barriers, float* max_cost)
{
  const cv::Size size = left.size();
  const int w = size.width, h = size.height, nd = disparities;
  const double sf = parameters_.scaleFactor(level);

  auto t = Clock::now();
  // (a) CIE L*a*b* (8-bit: L scaled to 0..255, a and b offset by 128).
  // One task per image: OpenCV runs a small image's conversion on one thread (Lab 0.054 ms at 113x94), so
  // the two images side by side halve the fast mode's wait; a large one's runs in parallel inside anyway.
  cv::Mat labs[2], grays_f[2];
  const cv::Mat* bgr[2] = {&left, &right};
  biovision_common::parallelFor(
      cv::Range(0, 2),
      [&](const cv::Range& images) {
        for (int i = images.start; i < images.end; ++i)
        {
          cv::cvtColor(*bgr[i], labs[i], cv::COLOR_BGR2Lab);
          cv::cvtColor(*bgr[i], grays_f[i], cv::COLOR_BGR2GRAY);
          grays_f[i].convertTo(grays_f[i], CV_32F, 1.0 / 255.0);
        }
      },
      2);
  cv::Mat &left_lab = labs[0], &right_lab = labs[1], &left_gray = grays_f[0], &right_gray = grays_f[1];

  times_.prepare += msSince(t);
  t = Clock::now();
  // (c) odd simple cells -> rolling 256-bit descriptors.
  PixelDescriptorImage& left_codes = codes_[level][0];
  PixelDescriptorImage& right_codes = codes_[level][1];
  // Comparison bytes only: the costs are taken from them directly (Hamming::windowRow), no 256-bit codes.
  const auto odd = oddResponses(level, left_gray, right_gray);
  PixelDescriptorImage::computeComparisons(odd[0], left_codes);
  PixelDescriptorImage::computeComparisons(odd[1], right_codes);
  if (barriers)
  {
    // Line/edge events of the left image, on the bank's exact decimated grid, back at level size.
    const auto cells = barrier_banks_[level]->compute(left_gray);
    const biovision_v1::EndStoppedCells end_stopped(cells[0], 0.6, false);  // single cells suffice here
    const cv::Mat events = biovision_v1::LineEdgeDetector().detect(cells[0], end_stopped).mask();
    cv::Mat up;
    cv::resize(events, up, cv::Size(events.cols * cells[0].decimation, events.rows * cells[0].decimation), 0, 0,
               cv::INTER_NEAREST);
    *barriers = up(cv::Rect(0, 0, w, h)).clone();
  }

  times_.cells += msSince(t);
  t = Clock::now();
  // (d) Hamming costs, (b) colour mask, modulation, (e) 1-D DoG along disparity; one image row at a time
  // through all four, rows in parallel. The level's volume of the last frame: same shape, so no allocation (and no page faults) per frame.
  CostVolume costs = std::move(spare_[level]);
  costs.create(size, nd);  // every value is written below
  const int n_th = std::clamp(static_cast<int>(std::lround(std::log2(std::max(2.0, parameters_.max_disparity / sf)))),
                              1, nd);
  const float boost = static_cast<float>(1.0 + parameters_.kappa), damp = static_cast<float>(1.0 - parameters_.kappa);
  // Planar L*a*b* so that the SAD below runs over contiguous bytes and vectorises.
  cv::Mat left_planes[3], right_planes[3];
  cv::split(left_lab, left_planes);
  cv::split(right_lab, right_planes);
  DisparityDog dog(parameters_.sigma1 / sf, parameters_.sigma2 / sf, parameters_.tau, parameters_.alpha,
                   parameters_.beta);
  dog.setSimd(cost_simd_);
  std::vector<float> row_max(h);
  const MaskedCostRows rows_in{left_planes, right_planes, &left_codes, &right_codes, &dog, &costs, row_max.data(),
                               w,           nd,           n_th,        damp,         boost};
  const CostSimd simd = cost_simd_;
  biovision_common::parallelFor(cv::Range(0, h), [&](const cv::Range& rows) {
    if (simd == CostSimd::kAvx512)
      maskedCostRowsAvx512(rows_in, rows.start, rows.end);
    else if (simd == CostSimd::kAvx2)
      maskedCostRowsAvx2(rows_in, rows.start, rows.end);
    else
      maskedCostRowsGeneric(rows_in, rows.start, rows.end);
  });

  if (max_cost)
  {
    *max_cost = -HUGE_VALF;  // CostVolume::max()'s value, NaN ignored
    for (const float m : row_max)
      *max_cost = std::max(*max_cost, m);
  }
  times_.costs += msSince(t);
  return costs;
}

float BioBinMatcher::fuseWithCoarser(CostVolume& costs, float max_cost, const CostVolume& coarser) const
{
  // Costs above L are averaged with the coarser level's final costs at the same disparity, resampled
  // as CostVolume::resampled does (linear in k, bilinear in x, y) but one slice at a time: the whole
  // upsampled volume is never stored (it was 17 of this stage's 18 ms on Cones).
  const float level = static_cast<float>(parameters_.fusion_level) * max_cost;
  const int nd = costs.disparities(), d_in = coarser.disparities();
  const double scale = nd > 1 ? double(d_in - 1) / double(nd - 1) : 0.0;
  std::vector<float> slice_min(nd);
  const LinearResampling resampling(coarser.size(), costs.size());
  biovision_common::parallelFor(cv::Range(0, nd), [&](const cv::Range& ks) {
    cv::Mat mixed;
    std::vector<float> scratch;
    for (int k = ks.start; k < ks.end; ++k)
    {
      const double kc = k * scale;
      const int k0 = std::min(static_cast<int>(kc), d_in - 1), k1 = std::min(k0 + 1, d_in - 1);
      cv::addWeighted(coarser.slice(k0), 1.0 - (kc - k0), coarser.slice(k1), kc - k0, 0.0, mixed);
      cv::Mat slice = costs.slice(k);
      if (cost_simd_ == CostSimd::kAvx512)
        slice_min[k] = fuseSliceAvx512(slice, mixed, resampling, scratch, level);
      else if (cost_simd_ == CostSimd::kAvx2)
        slice_min[k] = fuseSliceAvx2(slice, mixed, resampling, scratch, level);
      else
        slice_min[k] = fuseSliceGeneric(slice, mixed, resampling, scratch, level);
    }
  });
  return *std::min_element(slice_min.begin(), slice_min.end());
}

void BioBinMatcher::spatialFilter(CostVolume& costs, const cv::Mat& barriers)
{
  spatial_filter_.setSimd(cost_simd_);
  spatial_filter_.apply(costs, parameters_.line_edge_barriers ? barriers : cv::Mat());
}

DisparityMap BioBinMatcher::winnerTakeAll(const CostVolume& costs, cv::Size input, double sf) const
{
  const cv::Size size = costs.size();
  const int w = size.width, h = size.height, nd = costs.disparities();
  cv::Mat left_d(size, CV_32F), right_k(size, CV_32S);
  const CostSimd simd = cost_simd_;
  biovision_common::parallelFor(cv::Range(0, h), [&](const cv::Range& rows) {
    std::vector<float> best_cost(w), best_right(w);
    std::vector<int> best(w);
    for (int y = rows.start; y < rows.end; ++y)
    {
      std::fill(best_cost.begin(), best_cost.end(), HUGE_VALF);
      std::fill(best_right.begin(), best_right.end(), HUGE_VALF);
      std::fill(best.begin(), best.end(), 0);
      int* rk = right_k.ptr<int>(y);
      std::fill(rk, rk + w, -1);
      // Disparity outer, pixels inner: each slice row is read once, contiguously (the pixel-outer
      // order strode across all slices per pixel). Same visiting order per pixel, so the same ties win.
      // A disparity must stay inside the right image: k <= x. Right view: the right pixel x - k sees left
      // pixel x at disparity k.
      for (int k = 0; k < nd; ++k)
        (simd == CostSimd::kGeneric ? updateWinnersGeneric : updateWinnersAvx2)(
            costs.slice(k).ptr<float>(y) + k, w - k, k, best_cost.data() + k, best.data() + k, best_right.data(), rk);
      float* ld = left_d.ptr<float>(y);
      for (int x = 0; x < w; ++x)
      {
        const int kmax = std::min(nd - 1, x);
        float d = static_cast<float>(best[x]);
        if (parameters_.subpixel && best[x] > 0 && best[x] < kmax)
        {
          const float cm = costs.slice(best[x] - 1).ptr<float>(y)[x], cp = costs.slice(best[x] + 1).ptr<float>(y)[x];
          const float den = cm - 2 * best_cost[x] + cp;
          if (den > 0)
            d += std::clamp(0.5f * (cm - cp) / den, -0.5f, 0.5f);
        }
        ld[x] = d;
      }
    }
  });
  return toInputResolution(left_d, right_k, input, sf);
}

DisparityMap BioBinMatcher::toInputResolution(cv::Mat& left_d, const cv::Mat& right_k, cv::Size input, double sf) const
{
  const cv::Size size = left_d.size();
  const int w = size.width, h = size.height;
  if (parameters_.left_right_check)
  {
    const float tol = static_cast<float>(parameters_.left_right_tolerance / sf);
    for (int y = 0; y < h; ++y)
    {
      float* d = left_d.ptr<float>(y);
      const int* rk = right_k.ptr<int>(y);
      for (int x = 0; x < w; ++x)
      {
        const int xr = x - static_cast<int>(std::lround(d[x]));
        if (xr < 0 || xr >= w || rk[xr] < 0 || std::abs(rk[xr] - d[x]) > tol + 0.5f)
          d[x] = DisparityMap::kInvalid;
      }
    }
    if (parameters_.fill_occlusions)
      OcclusionFilling::fill(left_d);
  }
  if (parameters_.median_filter)
  {
    const cv::Mat invalid = left_d < 0;
    cv::medianBlur(left_d, left_d, 3);
    left_d.setTo(DisparityMap::kInvalid, invalid);
  }
  DisparityMap out;
  out.max_disparity = parameters_.max_disparity;
  const double value_scale = double(input.width) / w;  // level disparities -> input pixels
  cv::Mat scaled = left_d * value_scale;
  // A level's disparity count is rounded up (ceil(max / sf) + 1), so where max_disparity / sf is no
  // integer its last disparity lies up to sf - 1 px beyond max_disparity: the map keeps its declared range.
  scaled = cv::min(scaled, parameters_.max_disparity);
  scaled.setTo(DisparityMap::kInvalid, left_d < 0);
  if (size == input)
    out.disparity = scaled;
  else
    cv::resize(scaled, out.disparity, input, 0, 0, cv::INTER_NEAREST);
  return out;
}

DisparityMap BioBinMatcher::aggregateAndTakeWinners(const CostVolume& costs, float lowest, const cv::Mat& barriers,
                                                    cv::Size input, double sf)
{
  auto t = Clock::now();
  const cv::Size size = costs.size();
  const int w = size.width, h = size.height, nd = costs.disparities();
  // 16-bit pixel-major costs: (M - min M) * kSgmCostScale, saturated at kMaxCost. A constant offset does
  // not change the aggregation's winners, the scale fixes what P1 and P2 mean.
  const float scale = static_cast<float>(BioBinParameters::kSgmCostScale);
  SemiGlobalAggregation::toPixelMajor(costs, lowest, scale, sgm_costs_);
  const auto units = [scale](double v) { return static_cast<int>(std::lround(v * scale)); };
  const SemiGlobalAggregation sgm(units(parameters_.sgm_p1),
                                  std::max(units(parameters_.sgm_p1), units(parameters_.sgm_p2)),
                                  units(parameters_.sgm_p2_barrier), parameters_.sgm_paths);
  const cv::Mat no_barriers;
  sgm.aggregate(sgm_costs_, w, h, nd, parameters_.line_edge_barriers ? barriers : no_barriers, sgm_forward_,
                sgm_backward_, SemiGlobalAggregation::bestSimd());
  times_.spatial += msSince(t);
  t = Clock::now();
  // Winner-take-all on S = forward + backward, as winnerTakeAll() does on the filtered costs.
  cv::Mat left_d, right_k;
  SemiGlobalAggregation::winners(sgm_forward_, sgm_backward_, w, h, nd, parameters_.subpixel, left_d, right_k,
                                 SemiGlobalAggregation::bestSimd());
  DisparityMap out = toInputResolution(left_d, right_k, input, sf);
  times_.wta += msSince(t);
  return out;
}

DisparityMap BioBinMatcher::compute(const cv::Mat& left_in, const cv::Mat& right_in)
{
  const cv::Mat left = toBgr8(left_in, "left"), right = toBgr8(right_in, "right");
  if (left.size() != right.size())
    throw std::invalid_argument("BioBin: left " + std::to_string(left.cols) + "x" + std::to_string(left.rows) +
                                " and right " + std::to_string(right.cols) + "x" + std::to_string(right.rows) +
                                " differ in size");
  if (left_in.type() != right_in.type())
    throw std::invalid_argument("BioBin: left and right images differ in type");
  if (parameters_.max_disparity >= left.cols)
    throw std::invalid_argument("BioBin: max_disparity " + std::to_string(parameters_.max_disparity) +
                                " is not smaller than the image width " + std::to_string(left.cols));
  const cv::Size coarsest = levelSize(left.size(), parameters_.wavelengths.size() - 1);
  if (coarsest.width < 17 || coarsest.height < 3)
    throw std::invalid_argument("BioBin: image " + std::to_string(left.cols) + "x" + std::to_string(left.rows) +
                                " is smaller than the descriptor window at the coarsest level");

  if (left.size().area() < last_input_.area())
    resetCaches();
  last_input_ = left.size();
  times_ = StageTimes();
  const auto start = Clock::now();
  CostVolume previous;
  for (size_t s = parameters_.wavelengths.size(); s-- > 0;)
  {
    const double sf = parameters_.scaleFactor(s);
    const cv::Size size = levelSize(left.size(), s);
    auto t = Clock::now();
    cv::Mat l, r;
    if (size == left.size())
    {
      l = left;
      r = right;
    }
    else
    {
      // Area averaging as INTER_AREA, but 5x faster than OpenCV's single-threaded non-integer path.
      auto& down = downsampling_[s];
      if (!down || down->input() != left.size() || down->output() != size)
        down = std::make_unique<biovision_common::AreaDownsampling>(left.size(), size);
      // One task per image (a nested parallel_for_ runs serially): half the waits on a small level.
      const cv::Mat* in[2] = {&left, &right};
      cv::Mat* out[2] = {&l, &r};
      const biovision_common::AreaDownsampling& d = *down;
      biovision_common::parallelFor(
          cv::Range(0, 2),
          [&](const cv::Range& images) {
            for (int i = images.start; i < images.end; ++i)
              d.apply(*in[i], *out[i]);
          },
          2);
    }
    times_.prepare += msSince(t);
    const int disparities = static_cast<int>(std::ceil(parameters_.max_disparity / sf)) + 1;
    // Line/edge barriers only where a step uses them (the finest level's semi-global aggregation does
    // only when it lowers P2 there): at the finest level that saves the quadrature bank's compute.
    const bool semi_global = s == 0 && parameters_.aggregation == "semi_global";
    const bool need_barriers = parameters_.line_edge_barriers &&
                               (!semi_global || parameters_.sgm_p2_barrier != parameters_.sgm_p2);
    cv::Mat barriers;
    float max_cost = 0.f;
    CostVolume costs = levelCosts(s, l, r, disparities, need_barriers ? &barriers : nullptr, &max_cost);
    t = Clock::now();
    const bool fused = previous.disparities() > 0;
    float lowest = 0.f;  // the fused costs' min: the aggregation's 16-bit offset
    if (fused)
    {
      lowest = fuseWithCoarser(costs, max_cost, previous);
      spare_[s + 1] = std::move(previous);
    }
    times_.fusion += msSince(t);
    if (semi_global)
    {
      DisparityMap result = aggregateAndTakeWinners(costs, fused ? lowest : costs.min(), barriers, left.size(), sf);
      spare_[0] = std::move(costs);
      times_.total = msSince(start);
      return result;
    }
    t = Clock::now();
    spatialFilter(costs, barriers);
    times_.spatial += msSince(t);
    previous = std::move(costs);
    if (s == 0)
    {
      t = Clock::now();
      DisparityMap result = winnerTakeAll(previous, left.size(), sf);
      times_.wta = msSince(t);
      spare_[0] = std::move(previous);
      times_.total = msSince(start);
      return result;
    }
  }
  return DisparityMap();  // not reached: the loop ends at level 0
}
}  // namespace biovision_stereo
