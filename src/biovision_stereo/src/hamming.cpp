#include "biovision_stereo/hamming.hpp"

namespace biovision_stereo
{
namespace
{
int popcountScalar(std::uint64_t v)
{
  // SWAR bit count: the portable reference.
  v = v - ((v >> 1) & 0x5555555555555555ULL);
  v = (v & 0x3333333333333333ULL) + ((v >> 2) & 0x3333333333333333ULL);
  v = (v + (v >> 4)) & 0x0F0F0F0F0F0F0F0FULL;
  return static_cast<int>((v * 0x0101010101010101ULL) >> 56);
}

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

const bool kHasPopcnt = __builtin_cpu_supports("popcnt");
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
    n += popcountScalar(a.words[i] ^ b.words[i]);
  return n;
}

bool Hamming::usesPopcnt()
{
  return kHasPopcnt;
}
}  // namespace biovision_stereo
