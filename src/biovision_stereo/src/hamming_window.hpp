#pragma once

// Private to the library's sources: inlined into each instruction-set clone of the cost rows.

#include <cstddef>
#include <cstdint>
#include <vector>

namespace biovision_stereo
{
/// Scratch of hammingWindowRow(), reused from call to call.
struct HammingWindowScratch
{
  std::vector<std::uint8_t> centre, sides, centre2, sides2;
};

/// Per position j < n: c[j] = bits differing between ac[j] and bc[j]; s[j] = the same summed over the rows
/// above and below. In byte arithmetic (SWAR), so that it vectorises on every target; restrict parameters,
/// so that the compiler needs no run-time alias checks (six inputs were too many for it).
inline void windowBits(const std::uint8_t* __restrict ac, const std::uint8_t* __restrict aa,
                       const std::uint8_t* __restrict ab, const std::uint8_t* __restrict bc,
                       const std::uint8_t* __restrict ba, const std::uint8_t* __restrict bb, int n,
                       std::uint8_t* __restrict c, std::uint8_t* __restrict s)
{
  for (int j = 0; j < n; ++j)
  {
    std::uint8_t v = static_cast<std::uint8_t>(ac[j] ^ bc[j]);
    v = static_cast<std::uint8_t>(v - ((v >> 1) & 0x55));
    v = static_cast<std::uint8_t>((v & 0x33) + ((v >> 2) & 0x33));
    c[j] = static_cast<std::uint8_t>((v + (v >> 4)) & 0x0F);
    std::uint8_t u = static_cast<std::uint8_t>(aa[j] ^ ba[j]);
    u = static_cast<std::uint8_t>(u - ((u >> 1) & 0x55));
    u = static_cast<std::uint8_t>((u & 0x33) + ((u >> 2) & 0x33));
    std::uint8_t t = static_cast<std::uint8_t>(ab[j] ^ bb[j]);
    t = static_cast<std::uint8_t>(t - ((t >> 1) & 0x55));
    t = static_cast<std::uint8_t>((t & 0x33) + ((t >> 2) & 0x33));
    // u and t hold a count per nibble (at most 4): add them before the last fold.
    const std::uint8_t sum = static_cast<std::uint8_t>(u + t);  // each nibble <= 8: no carry between nibbles
    s[j] = static_cast<std::uint8_t>((sum & 0x0F) + (sum >> 4));
  }
}

/// The Hamming distances of a row of BioBin descriptors from their comparison bytes (PixelDescriptorImage's
/// layout: a descriptor is the comparison bytes x-8..x+7 of its row and x-4..x+3 of the rows above and
/// below), without forming a descriptor: per byte position p the bits that differ, popcount(a[p] ^ b[p - k])
/// (at most 8), summed over the 16-wide window of the centre row and the 8-wide windows of the rows above and
/// below by doubling (2, 4, 8, 16), all on bytes (a 16-window sums to at most 128, the two 8-windows together
/// to 128). out[x] = distance(a(x), b(x - k)) for k <= x < w, `missing` for x < k. Each row pointer is a
/// row's position 0, valid from -8 to w + 7 (zero margins). Equals Hamming::row() on the descriptors exactly.
inline void hammingWindowRow(const std::uint8_t* a_above, const std::uint8_t* a_centre, const std::uint8_t* a_below,
                             const std::uint8_t* b_above, const std::uint8_t* b_centre, const std::uint8_t* b_below,
                             int w, int k, float missing, float* out, HammingWindowScratch& scratch)
{
  int x = 0;
  for (; x < k && x < w; ++x)
    out[x] = missing;
  if (x >= w)
    return;
  // Positions j = p - (k - 8), p from k - 8 to w + 7: a at p, b at p - k = j - 8.
  // Loops run to a multiple of 64 (no scalar epilogues, which cost more than the vector bodies on rows of a
  // few hundred pixels): the rows' right margins (PixelDescriptorImage::kRightMargin) and the scratch's
  // padding make the extra reads valid; what they compute is never used.
  const int n = (w - k + 16 + 63) & ~63;
  for (auto* v : {&scratch.centre, &scratch.sides, &scratch.centre2, &scratch.sides2})
    if (v->size() < std::size_t(n) + 16)
      v->resize(std::size_t(n) + 16);
  std::uint8_t* __restrict c = scratch.centre.data();
  std::uint8_t* __restrict s = scratch.sides.data();
  std::uint8_t* __restrict c2 = scratch.centre2.data();
  std::uint8_t* __restrict s2 = scratch.sides2.data();
  const std::uint8_t *ac = a_centre + k - 8, *aa = a_above + k - 8, *ab = a_below + k - 8;
  const std::uint8_t *bc = b_centre - 8, *ba = b_above - 8, *bb = b_below - 8;
  windowBits(ac, aa, ab, bc, ba, bb, n, c, s);
  // Window sums by doubling, ping-pong between two buffers, constant offsets (so each loop vectorises).
  for (int j = 0; j < n; ++j)
  {
    c2[j] = static_cast<std::uint8_t>(c[j] + c[j + 1]);
    s2[j] = static_cast<std::uint8_t>(s[j] + s[j + 1]);
  }
  for (int j = 0; j < n; ++j)
  {
    c[j] = static_cast<std::uint8_t>(c2[j] + c2[j + 2]);
    s[j] = static_cast<std::uint8_t>(s2[j] + s2[j + 2]);
  }
  for (int j = 0; j < n; ++j)
  {
    c2[j] = static_cast<std::uint8_t>(c[j] + c[j + 4]);
    s2[j] = static_cast<std::uint8_t>(s[j] + s[j + 4]);  // the sides' 8-windows
  }
  for (int j = 0; j < n; ++j)
    c[j] = static_cast<std::uint8_t>(c2[j] + c2[j + 8]);  // the centre's 16-windows
  // Centre window of x starts at j = x - k, the sides' window at j = x - k + 4.
  for (int i = 0; x < w; ++x, ++i)
    out[x] = static_cast<float>(static_cast<int>(c[i]) + static_cast<int>(s2[i + 4]));
}
}  // namespace biovision_stereo
