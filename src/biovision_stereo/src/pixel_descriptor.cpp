#include "biovision_stereo/pixel_descriptor.hpp"

#include <algorithm>
#include <stdexcept>

#include <opencv2/core/utility.hpp>

#if defined(__SSE2__)
#include <immintrin.h>

#include <array>
#include <cstring>

#include "biovision_common/cpu_features.hpp"
#endif

namespace biovision_stereo
{
namespace
{
constexpr int kOrientations = 8;

#if !defined(__SSE2__)
// Comparison bits of one response row: bits[x] = R(x) > R(x + 1), replicated border.
void comparisonRow(const float* r, int step, int width, std::vector<std::uint8_t>& bits)
{
  bits.resize(width);
  for (int x = 0; x + 1 < width; ++x)
    bits[x] = r[x * step] > r[(x + 1) * step];
  bits[width - 1] = 0;  // R(w-1) > R(w-1) is false
}

inline std::uint8_t bitAt(const std::vector<std::uint8_t>& bits, int x)
{
  // Left of the image the replicated response is constant, so the comparison is false as well.
  return x < 0 || x >= static_cast<int>(bits.size()) ? 0 : bits[x];
}
#endif

void checkInput(const std::vector<cv::Mat>& odd)
{
  const bool singles = odd.size() == kOrientations, pairs = odd.size() == kOrientations / 2;
  if (!singles && !pairs)
    throw std::invalid_argument("PixelDescriptor: needs 8 orientation maps or 4 orientation pairs");
  for (const cv::Mat& m : odd)
    if (m.type() != (singles ? CV_32FC1 : CV_32FC2) || m.size() != odd.front().size() || m.empty())
      throw std::invalid_argument("PixelDescriptor: orientation maps must be CV_32FC1 (pairs CV_32FC2) of one size");
}

// Row y of orientation o's responses: element x at r[x * step].
struct ResponseRow
{
  const float* r;
  int step;
};

ResponseRow responseRow(const std::vector<cv::Mat>& odd, int o, int y)
{
  if (odd.size() == kOrientations)
    return {odd[o].ptr<float>(y), 1};
  return {odd[o / 2].ptr<float>(y) + o % 2, 2};
}

// Comparison bytes of one row of one orientation pair (CV_32FC2: orientations a, b interleaved), stored
// right to left: out_a[w - 1 - x] = R_a(x) > R_a(x + 1) ? 0xFF : 0, x < w - 1 (likewise b).
void comparePairRowGeneric(const float* r, int w, std::uint8_t* out_a, std::uint8_t* out_b)
{
  for (int x = 0; x + 1 < w; ++x)
  {
    out_a[w - 1 - x] = r[2 * x] > r[2 * x + 2] ? 0xFF : 0;
    out_b[w - 1 - x] = r[2 * x + 1] > r[2 * x + 3] ? 0xFF : 0;
  }
}

#if defined(__SSE2__)
// 8 comparison bits (bit k: pixel x + k) -> 8 bytes right to left (byte j: pixel x + 7 - j).
const std::array<std::uint64_t, 256> kReversedBytes = [] {
  std::array<std::uint64_t, 256> t{};
  for (int bits = 0; bits < 256; ++bits)
    for (int k = 0; k < 8; ++k)
      if (bits >> k & 1)
        t[bits] |= std::uint64_t(0xFF) << (8 * (7 - k));
  return t;
}();

// The same, 8 pixels per step: the pair's lanes sorted into a0..a3 b0..b3, compared with the next pixel's,
// one movemask per 4 pixels of both orientations; the scalar loop did a strided load per comparison
// (4.5% of the fast mode's time). NaN compares false in both (ordered >).
__attribute__((target("avx2"))) void comparePairRowAvx2(const float* r, int w, std::uint8_t* out_a, std::uint8_t* out_b)
{
  const __m256i by_orientation = _mm256_setr_epi32(0, 2, 4, 6, 1, 3, 5, 7);
  int x = 0;
  for (; x + 8 < w; x += 8)  // pixel x + 8 is the last one read
  {
    const float* p = r + 2 * x;  // (a lambda would not inherit this function's target)
    const __m256 v0 = _mm256_permutevar8x32_ps(_mm256_loadu_ps(p), by_orientation);
    const __m256 n0 = _mm256_permutevar8x32_ps(_mm256_loadu_ps(p + 2), by_orientation);
    const __m256 v1 = _mm256_permutevar8x32_ps(_mm256_loadu_ps(p + 8), by_orientation);
    const __m256 n1 = _mm256_permutevar8x32_ps(_mm256_loadu_ps(p + 10), by_orientation);
    const unsigned lo = static_cast<unsigned>(_mm256_movemask_ps(_mm256_cmp_ps(v0, n0, _CMP_GT_OQ)));
    const unsigned hi = static_cast<unsigned>(_mm256_movemask_ps(_mm256_cmp_ps(v1, n1, _CMP_GT_OQ)));
    const std::uint64_t a = kReversedBytes[(lo & 0xFu) | (hi & 0xFu) << 4];
    const std::uint64_t b = kReversedBytes[(lo >> 4) | (hi & 0xF0u)];
    std::memcpy(out_a + w - 8 - x, &a, 8);
    std::memcpy(out_b + w - 8 - x, &b, 8);
  }
  for (; x + 1 < w; ++x)
  {
    out_a[w - 1 - x] = r[2 * x] > r[2 * x + 2] ? 0xFF : 0;
    out_b[w - 1 - x] = r[2 * x + 1] > r[2 * x + 3] ? 0xFF : 0;
  }
}
#endif
}  // namespace

PixelDescriptorImage PixelDescriptorImage::compute(const std::vector<cv::Mat>& odd)
{
  PixelDescriptorImage image;
  compute(odd, image);
  image.comparisons_ = {};  // the scratch only pays off in a reused image; a returned one travels light
  return image;
}

void PixelDescriptorImage::compute(const std::vector<cv::Mat>& odd, PixelDescriptorImage& image)
{
  checkInput(odd);
  const int w = odd.front().cols, h = odd.front().rows;
  image.width_ = w;
  image.height_ = h;
  image.data_.resize(size_t(w) * h);  // every descriptor is written below
#if defined(__SSE2__)
  // Comparison bytes (0 or 0xFF) of every row and orientation, stored right to left with 8 zero bytes
  // of margin each side: then the 16 comparisons x-8..x+7 of pixel x are the 16 bytes from w - x, and one
  // movemask packs them with x-8 in bit 15, as the descriptor orders them (8-bit segments likewise). The
  // zero margin is bitAt()'s false outside the image. A third less time than shifting in one bit at a
  // time (perf on Middlebury); rows in parallel.
  const int row_bytes = w + 16;
  std::vector<std::uint8_t>& reversed = image.comparisons_;
  reversed.resize(size_t(kOrientations) * h * row_bytes);  // margins and out[0] are zeroed per row below
  const auto reversedRow = [&](int o, int y) { return reversed.data() + (size_t(o) * h + y) * row_bytes; };
  const bool pairs = odd.size() == kOrientations / 2, avx2 = biovision_common::CpuFeatures::host().avx2;
  const int per_job = pairs ? 2 : 1;  // orientations a job compares: a pair's two from one interleaved row
  cv::parallel_for_(cv::Range(0, kOrientations / per_job * h), [&](const cv::Range& jobs) {
    for (int job = jobs.start; job < jobs.end; ++job)
    {
      const int o = job / h * per_job, y = job % h;
      std::uint8_t* out[2] = {reversedRow(o, y) + 8, reversedRow(o + per_job - 1, y) + 8};
      for (std::uint8_t* row : out)
      {
        std::fill(row - 8, row + 1, 0);      // left margin; row[0] (x = w-1): R(w-1) > R(w-1) is false
        std::fill(row + w, row + w + 8, 0);  // right margin
      }
      if (pairs)
      {
        const float* r = odd[o / 2].ptr<float>(y);
        comparePairRow(r, w, out[0], out[1], avx2);
        continue;
      }
      const ResponseRow in = responseRow(odd, o, y);
      for (int x = 0; x + 1 < w; ++x)
        out[0][w - 1 - x] = in.r[x * in.step] > in.r[(x + 1) * in.step] ? 0xFF : 0;
    }
  });
  cv::parallel_for_(cv::Range(0, h), [&](const cv::Range& rows) {
    for (int y = rows.start; y < rows.end; ++y)
    {
      const int above = std::max(y - 1, 0), below = std::min(y + 1, h - 1);
      PixelDescriptor* row = &image.at(0, y);
      for (int x = 0; x < w; ++x)
      {
        std::uint64_t words[4] = {0, 0, 0, 0};
        for (int o = 0; o < kOrientations; ++o)
        {
          const auto load16 = [&](int yy) {
            return static_cast<std::uint32_t>(
                _mm_movemask_epi8(_mm_loadu_si128(reinterpret_cast<const __m128i*>(reversedRow(o, yy) + w - x))));
          };
          const auto load8 = [&](int yy) {
            return static_cast<std::uint32_t>(_mm_movemask_epi8(
                       _mm_loadl_epi64(reinterpret_cast<const __m128i*>(reversedRow(o, yy) + w - x + 4)))) &
                   0xFFu;
          };
          const std::uint64_t code = (std::uint64_t(load16(y)) << 16) | (load8(above) << 8) | load8(below);
          words[o / 2] |= code << (32 * (o % 2));
        }
        row[x].words = {words[0], words[1], words[2], words[3]};
      }
    }
  });
#else
  std::fill(image.data_.begin(), image.data_.end(), PixelDescriptor{});  // the words are OR-ed below
  std::vector<std::vector<std::uint8_t> > bits(h);  // comparisons of every row, once per orientation
  for (int o = 0; o < kOrientations; ++o)
  {
    const int word = o / 2, shift = 32 * (o % 2);
    for (int y = 0; y < h; ++y)
    {
      const ResponseRow in = responseRow(odd, o, y);
      comparisonRow(in.r, in.step, w, bits[y]);
    }
    for (int y = 0; y < h; ++y)
    {
      const std::vector<std::uint8_t>& above = bits[std::max(y - 1, 0)];
      const std::vector<std::uint8_t>& centre = bits[y];
      const std::vector<std::uint8_t>& below = bits[std::min(y + 1, h - 1)];
      // Segments hold the comparisons at x-8..x+7 (centre) and x-4..x+3 (above, below); before x = 0
      // they hold those up to x+6 / x+2, so that shifting in x+7 / x+3 completes them.
      std::uint32_t c = 0, a = 0, b = 0;
      for (int p = -8; p <= 6; ++p)
        c = (c << 1) | bitAt(centre, p);
      for (int p = -4; p <= 2; ++p)
      {
        a = (a << 1) | bitAt(above, p);
        b = (b << 1) | bitAt(below, p);
      }
      PixelDescriptor* row = &image.at(0, y);
      for (int x = 0; x < w; ++x)
      {
        // Shift in the one new comparison per segment: the code of x from the code of x - 1.
        c = ((c << 1) | bitAt(centre, x + 7)) & 0xFFFFu;
        a = ((a << 1) | bitAt(above, x + 3)) & 0xFFu;
        b = ((b << 1) | bitAt(below, x + 3)) & 0xFFu;
        const std::uint64_t code = (std::uint64_t(c) << 16) | (std::uint64_t(a) << 8) | b;
        row[x].words[word] |= code << shift;
      }
    }
  }
#endif
}

void PixelDescriptorImage::comparePairRow(const float* pair_row, int width, std::uint8_t* out_a, std::uint8_t* out_b,
                                          bool avx2)
{
#if defined(__SSE2__)
  if (avx2)
  {
    if (!biovision_common::CpuFeatures::host().avx2)
      throw std::invalid_argument("PixelDescriptorImage::comparePairRow: this CPU has no AVX2");
    comparePairRowAvx2(pair_row, width, out_a, out_b);
    return;
  }
#else
  if (avx2)
    throw std::invalid_argument("PixelDescriptorImage::comparePairRow: built without x86 SIMD");
#endif
  comparePairRowGeneric(pair_row, width, out_a, out_b);
}

PixelDescriptor PixelDescriptorImage::fromScratch(const std::vector<cv::Mat>& odd, int x, int y)
{
  checkInput(odd);
  const int w = odd.front().cols, h = odd.front().rows;
  auto response = [&](int o, int xx, int yy) {
    const ResponseRow in = responseRow(odd, o, std::clamp(yy, 0, h - 1));
    return in.r[std::clamp(xx, 0, w - 1) * in.step];
  };
  auto bit = [&](int o, int xx, int yy) -> std::uint64_t { return response(o, xx, yy) > response(o, xx + 1, yy); };
  PixelDescriptor d;
  for (int o = 0; o < kOrientations; ++o)
  {
    std::uint64_t code = 0;
    for (int i = -8; i <= 7; ++i)
      code = (code << 1) | bit(o, x + i, y);
    std::uint64_t a = 0, b = 0;
    for (int i = -4; i <= 3; ++i)
    {
      a = (a << 1) | bit(o, x + i, y - 1);
      b = (b << 1) | bit(o, x + i, y + 1);
    }
    code = (code << 16) | (a << 8) | b;
    d.words[o / 2] |= code << (32 * (o % 2));
  }
  return d;
}
}  // namespace biovision_stereo
