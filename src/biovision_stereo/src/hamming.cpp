#include "biovision_stereo/hamming.hpp"

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
