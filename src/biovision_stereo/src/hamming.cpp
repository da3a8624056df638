#include "biovision_stereo/hamming.hpp"

#include <algorithm>
#include <stdexcept>

#include "avx512_clone.hpp"
#include "biovision_stereo/cost_simd.hpp"
#include "hamming_window.hpp"

namespace biovision_stereo
{
void Hamming::row(const PixelDescriptor* a, const PixelDescriptor* b, int width, int shift, float missing, float* out,
                  biovision_common::HammingPath path)
{
  static_assert(sizeof(PixelDescriptor) == 4 * sizeof(std::uint64_t), "256-bit descriptors without padding");
  int x = 0;
  for (; x < shift && x < width; ++x)
    out[x] = missing;
  if (x < width)
    biovision_common::hammingDistancesPairwise(path, a[x].words.data(), b[x - shift].words.data(),
                                               static_cast<size_t>(width - x), 4, out + x);
}

namespace
{
// hammingWindowRow() compiled for AVX-512BW and AVX2 as well (byte arithmetic the compiler vectorises), as
// it is inside each clone of BioBin's cost rows, so that benchmarks of windowRow() time what BioBin runs.
struct WindowRows
{
  const std::uint8_t *a_above, *a_centre, *a_below, *b_above, *b_centre, *b_below;
};

inline void windowRowOn(const WindowRows& r, int w, int k, float missing, float* out)
{
  thread_local HammingWindowScratch scratch;  // no allocation per row
  hammingWindowRow(r.a_above, r.a_centre, r.a_below, r.b_above, r.b_centre, r.b_below, w, k, missing, out, scratch);
}

BIOVISION_STEREO_AVX512_CLONE void windowRowAvx512(const WindowRows& r, int w, int k, float missing, float* out)
{
  windowRowOn(r, w, k, missing, out);
}

__attribute__((target("avx2"), flatten)) void windowRowAvx2(const WindowRows& r, int w, int k, float missing,
                                                            float* out)
{
  windowRowOn(r, w, k, missing, out);
}

__attribute__((flatten)) void windowRowGeneric(const WindowRows& r, int w, int k, float missing, float* out)
{
  windowRowOn(r, w, k, missing, out);
}
}  // namespace

void Hamming::windowRow(const PixelDescriptorImage& a, const PixelDescriptorImage& b, int y, int shift, float missing,
                        float* out)
{
  if (a.width() != b.width() || a.height() != b.height() || y < 0 || y >= a.height() || shift < 0)
    throw std::invalid_argument(
        "Hamming::windowRow: images of different sizes, a row outside them or a negative shift");
  const int h = a.height(), up = std::max(y - 1, 0), down = std::min(y + 1, h - 1);
  const WindowRows rows{a.comparisons(up), a.comparisons(y), a.comparisons(down),
                        b.comparisons(up), b.comparisons(y), b.comparisons(down)};
  static const CostSimd simd = bestCostSimd();
  if (simd == CostSimd::kAvx512)
    windowRowAvx512(rows, a.width(), shift, missing, out);
  else if (simd == CostSimd::kAvx2)
    windowRowAvx2(rows, a.width(), shift, missing, out);
  else
    windowRowGeneric(rows, a.width(), shift, missing, out);
}

int Hamming::distance(const PixelDescriptor& a, const PixelDescriptor& b)
{
  float d;
  row(&a, &b, 1, 0, 0.f, &d);
  return static_cast<int>(d);
}

int Hamming::distanceScalar(const PixelDescriptor& a, const PixelDescriptor& b)
{
  return biovision_common::hammingDistanceReference(a.words.data(), b.words.data(), 4);
}

std::string Hamming::pathName()
{
  return biovision_common::toString(biovision_common::bestHammingPath());
}
}  // namespace biovision_stereo
