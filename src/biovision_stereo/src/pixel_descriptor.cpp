#include "biovision_stereo/pixel_descriptor.hpp"

#include <algorithm>
#include <array>
#include <cstring>
#include <stdexcept>

#include <opencv2/core/utility.hpp>

#if defined(__x86_64__) || defined(__i386__)
#include <immintrin.h>
#define BIOVISION_STEREO_X86 1
#endif

#include "biovision_common/cpu_features.hpp"
#include "biovision_common/parallel_arena.hpp"

namespace biovision_stereo
{
namespace
{
constexpr int kOrientations = 8;

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

void comparisonRowGeneric(const std::vector<cv::Mat>& odd, int y, std::uint8_t* out)
{
  const int w = odd.front().cols;
  std::fill(out, out + w, 0);
  for (int o = 0; o < kOrientations; ++o)
  {
    const ResponseRow in = responseRow(odd, o, y);
    for (int x = 0; x + 1 < w; ++x)
      out[x] |= static_cast<std::uint8_t>((in.r[x * in.step] > in.r[(x + 1) * in.step]) << o);
  }
}

#if defined(BIOVISION_STEREO_X86)
// Bits j of m -> byte j of the result (0 or 1): 8 pixels' comparisons of one orientation, to be shifted to
// that orientation's bit.
const std::array<std::uint64_t, 256> kSpreadBits = [] {
  std::array<std::uint64_t, 256> t{};
  for (int m = 0; m < 256; ++m)
    for (int j = 0; j < 8; ++j)
      t[m] |= std::uint64_t((m >> j) & 1) << (8 * j);
  return t;
}();

// 8 pixels per step: compare with the next pixel (ordered >: NaN compares false, as in the generic loop),
// movemask, spread the 8 bits to 8 bytes, shift them to the orientation's bit. Pairs: the interleaved lanes
// are first sorted into a0..a3 b0..b3.
__attribute__((target("avx2"))) void comparisonRowAvx2(const std::vector<cv::Mat>& odd, int y, std::uint8_t* out)
{
  const int w = odd.front().cols;
  const bool pairs = odd.size() == kOrientations / 2;
  const __m256i by_orientation = _mm256_setr_epi32(0, 2, 4, 6, 1, 3, 5, 7);
  int x = 0;
  for (; x + 8 < w; x += 8)  // pixel x + 8 is the last one read
  {
    std::uint64_t bytes = 0;
    if (pairs)
      for (int pair = 0; pair < kOrientations / 2; ++pair)
      {
        const float* p = odd[pair].ptr<float>(y) + 2 * x;
        const __m256 v0 = _mm256_permutevar8x32_ps(_mm256_loadu_ps(p), by_orientation);
        const __m256 n0 = _mm256_permutevar8x32_ps(_mm256_loadu_ps(p + 2), by_orientation);
        const __m256 v1 = _mm256_permutevar8x32_ps(_mm256_loadu_ps(p + 8), by_orientation);
        const __m256 n1 = _mm256_permutevar8x32_ps(_mm256_loadu_ps(p + 10), by_orientation);
        const unsigned lo = static_cast<unsigned>(_mm256_movemask_ps(_mm256_cmp_ps(v0, n0, _CMP_GT_OQ)));
        const unsigned hi = static_cast<unsigned>(_mm256_movemask_ps(_mm256_cmp_ps(v1, n1, _CMP_GT_OQ)));
        bytes |= kSpreadBits[(lo & 0xFu) | (hi & 0xFu) << 4] << (2 * pair);
        bytes |= kSpreadBits[(lo >> 4) | (hi & 0xF0u)] << (2 * pair + 1);
      }
    else
      for (int o = 0; o < kOrientations; ++o)
      {
        const float* p = odd[o].ptr<float>(y) + x;
        const unsigned m = static_cast<unsigned>(
            _mm256_movemask_ps(_mm256_cmp_ps(_mm256_loadu_ps(p), _mm256_loadu_ps(p + 1), _CMP_GT_OQ)));
        bytes |= kSpreadBits[m] << o;
      }
    std::memcpy(out + x, &bytes, 8);
  }
  for (; x < w; ++x)
  {
    std::uint8_t byte = 0;
    for (int o = 0; o < kOrientations && x + 1 < w; ++o)
    {
      const ResponseRow in = responseRow(odd, o, y);
      byte |= static_cast<std::uint8_t>((in.r[x * in.step] > in.r[(x + 1) * in.step]) << o);
    }
    out[x] = byte;
  }
}
#endif

/// One row on the path asked for, unchecked: comparisonRow() checks the input and the CPU once per call,
/// computeComparisons() once per image.
inline void comparisonRowOn(const std::vector<cv::Mat>& odd, int y, std::uint8_t* out, [[maybe_unused]] bool avx2)
{
#if defined(BIOVISION_STEREO_X86)
  if (avx2)
  {
    comparisonRowAvx2(odd, y, out);
    return;
  }
#endif
  comparisonRowGeneric(odd, y, out);
}
}  // namespace

void PixelDescriptorImage::comparisonRow(const std::vector<cv::Mat>& odd, int y, std::uint8_t* out, bool avx2)
{
  checkInput(odd);
  if (y < 0 || y >= odd.front().rows)
    throw std::invalid_argument("PixelDescriptorImage::comparisonRow: row outside the maps");
  if (avx2 && !biovision_common::CpuFeatures::host().avx2)
    throw std::invalid_argument("PixelDescriptorImage::comparisonRow: this CPU has no AVX2");
  comparisonRowOn(odd, y, out, avx2);
}

PixelDescriptorImage PixelDescriptorImage::compute(const std::vector<cv::Mat>& odd)
{
  PixelDescriptorImage image;
  compute(odd, image);
  return image;
}

void PixelDescriptorImage::computeComparisons(const std::vector<cv::Mat>& odd, PixelDescriptorImage& image)
{
  checkInput(odd);
  const int w = odd.front().cols, h = odd.front().rows;
  image.width_ = w;
  image.height_ = h;
  image.data_.clear();
  // Zero margins: outside the image the replicated response gives no comparison, and every window of a
  // descriptor stays in bounds.
  const int row_bytes = w + kLeftMargin + kRightMargin;
  std::vector<std::uint8_t>& comparisons = image.comparisons_;
  comparisons.resize(size_t(h) * row_bytes);
  const auto comparisonsOf = [&](int y) { return comparisons.data() + size_t(y) * row_bytes + kLeftMargin; };
  const bool avx2 = biovision_common::CpuFeatures::host().avx2;
  biovision_common::parallelFor(cv::Range(0, h), [&](const cv::Range& rows) {
    for (int y = rows.start; y < rows.end; ++y)
    {
      std::uint8_t* c = comparisonsOf(y);
      std::fill(c - kLeftMargin, c, 0);
      std::fill(c + w, c + w + kRightMargin, 0);
      comparisonRowOn(odd, y, c, avx2);  // the input and the CPU were checked once above, not per row
    }
  });
}

void PixelDescriptorImage::compute(const std::vector<cv::Mat>& odd, PixelDescriptorImage& image)
{
  computeComparisons(odd, image);
  const int w = image.width_, h = image.height_;
  image.data_.resize(size_t(w) * h);  // every descriptor is written below
  const auto comparisonsOf = [&](int y) { return image.comparisons(y); };
  // Each descriptor: bytes x-8..x+7 of its row, x-4..x+3 of the rows above and below (clamped).
  biovision_common::parallelFor(cv::Range(0, h), [&](const cv::Range& rows) {
    for (int y = rows.start; y < rows.end; ++y)
    {
      const std::uint8_t* centre = comparisonsOf(y);
      const std::uint8_t* above = comparisonsOf(std::max(y - 1, 0));
      const std::uint8_t* below = comparisonsOf(std::min(y + 1, h - 1));
      auto* out = reinterpret_cast<std::uint8_t*>(&image.at(0, y));
      for (int x = 0; x < w; ++x, out += sizeof(PixelDescriptor))
      {
        std::memcpy(out, centre + x - 8, 16);
        std::memcpy(out + 16, above + x - 4, 8);
        std::memcpy(out + 24, below + x - 4, 8);
      }
    }
  });
}

PixelDescriptor PixelDescriptorImage::fromScratch(const std::vector<cv::Mat>& odd, int x, int y)
{
  checkInput(odd);
  const int w = odd.front().cols, h = odd.front().rows;
  auto response = [&](int o, int xx, int yy) {
    const ResponseRow in = responseRow(odd, o, std::clamp(yy, 0, h - 1));
    return in.r[std::clamp(xx, 0, w - 1) * in.step];
  };
  auto byteAt = [&](int xx, int yy) {
    std::uint8_t b = 0;
    for (int o = 0; o < kOrientations; ++o)
      b |= static_cast<std::uint8_t>((response(o, xx, yy) > response(o, xx + 1, yy)) << o);
    return b;
  };
  std::uint8_t bytes[32];
  for (int i = -8; i <= 7; ++i)
    bytes[i + 8] = byteAt(x + i, y);
  for (int i = -4; i <= 3; ++i)
  {
    bytes[16 + i + 4] = byteAt(x + i, y - 1);
    bytes[24 + i + 4] = byteAt(x + i, y + 1);
  }
  PixelDescriptor d;
  std::memcpy(d.words.data(), bytes, sizeof bytes);  // the bytes in order in memory, as compute() copies them
  return d;
}
}  // namespace biovision_stereo
