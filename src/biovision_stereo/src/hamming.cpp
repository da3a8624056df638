#include "biovision_stereo/hamming.hpp"

#include "biovision_common/bit_count.hpp"
#include "biovision_common/cpu_features.hpp"

namespace biovision_stereo
{
namespace
{
__attribute__((target("popcnt"))) void rowPopcnt(const PixelDescriptor* a, const PixelDescriptor* b, int width,
                                                 int shift, float missing, float* out)
{
  int x = 0;
  for (; x < shift && x < width; ++x)
    out[x] = missing;
  for (; x < width; ++x)
  {
    const auto& p = a[x].words;
    const auto& q = b[x - shift].words;
    out[x] = static_cast<float>(__builtin_popcountll(p[0] ^ q[0]) + __builtin_popcountll(p[1] ^ q[1]) +
                                __builtin_popcountll(p[2] ^ q[2]) + __builtin_popcountll(p[3] ^ q[3]));
  }
}

void rowScalar(const PixelDescriptor* a, const PixelDescriptor* b, int width, int shift, float missing, float* out)
{
  int x = 0;
  for (; x < shift && x < width; ++x)
    out[x] = missing;
  for (; x < width; ++x)
    out[x] = static_cast<float>(Hamming::distanceScalar(a[x], b[x - shift]));
}

const bool kHasPopcnt = biovision_common::CpuFeatures::host().popcnt;
}  // namespace

void Hamming::row(const PixelDescriptor* a, const PixelDescriptor* b, int width, int shift, float missing, float* out)
{
  if (kHasPopcnt)
    rowPopcnt(a, b, width, shift, missing, out);
  else
    rowScalar(a, b, width, shift, missing, out);
}

int Hamming::distance(const PixelDescriptor& a, const PixelDescriptor& b)
{
  float d;
  row(&a, &b, 1, 0, 0.f, &d);
  return static_cast<int>(d);
}

int Hamming::distanceScalar(const PixelDescriptor& a, const PixelDescriptor& b)
{
  int n = 0;
  for (int i = 0; i < 4; ++i)
    n += biovision_common::countBits(a.words[i] ^ b.words[i]);
  return n;
}

bool Hamming::usesPopcnt()
{
  return kHasPopcnt;
}
}  // namespace biovision_stereo
