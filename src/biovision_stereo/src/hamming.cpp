#include "biovision_stereo/hamming.hpp"

#include <algorithm>
#include <stdexcept>

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

void Hamming::windowRow(const PixelDescriptorImage& a, const PixelDescriptorImage& b, int y, int shift, float missing,
                        float* out)
{
  if (a.width() != b.width() || a.height() != b.height() || y < 0 || y >= a.height() || shift < 0)
    throw std::invalid_argument(
        "Hamming::windowRow: images of different sizes, a row outside them or a negative shift");
  const int h = a.height(), up = std::max(y - 1, 0), down = std::min(y + 1, h - 1);
  HammingWindowScratch scratch;
  hammingWindowRow(a.comparisons(up), a.comparisons(y), a.comparisons(down), b.comparisons(up), b.comparisons(y),
                   b.comparisons(down), a.width(), shift, missing, out, scratch);
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
