#include "biovision_common/hamming_distance.hpp"

// GCC 12 warns inside its own AVX-512 intrinsics (their undefined pass-through operand): not ours.
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wmaybe-uninitialized"
#include <immintrin.h>

#include <cstring>
#include <stdexcept>
#include <type_traits>

#include "biovision_common/bit_count.hpp"
#include "biovision_common/cpu_features.hpp"

namespace biovision_common
{
namespace
{
void scalarDistances(const uint64_t* q, const uint64_t* c, size_t count, int words, uint16_t* out)
{
  for (size_t i = 0; i < count; ++i, c += words)
    out[i] = static_cast<uint16_t>(hammingDistanceReference(q, c, words));
}

__attribute__((target("popcnt"))) void popcntDistances(const uint64_t* q, const uint64_t* c, size_t count, int words,
                                                       uint16_t* out)
{
  switch (words)
  {
    case 1:
      for (size_t i = 0; i < count; ++i)
        out[i] = static_cast<uint16_t>(_mm_popcnt_u64(q[0] ^ c[i]));
      return;
    case 2:
      for (size_t i = 0; i < count; ++i, c += 2)
        out[i] = static_cast<uint16_t>(_mm_popcnt_u64(q[0] ^ c[0]) + _mm_popcnt_u64(q[1] ^ c[1]));
      return;
    default:
      for (size_t i = 0; i < count; ++i, c += words)
      {
        uint64_t d = 0;
        for (int w = 0; w < words; ++w)
          d += _mm_popcnt_u64(q[w] ^ c[w]);
        out[i] = static_cast<uint16_t>(d);
      }
  }
}

// Per-64-bit-lane popcount of a 256-bit vector: nibble look-up, then SAD against zero.
__attribute__((target("avx2"))) inline __m256i popcountLanes256(__m256i v)
{
  const __m256i lut = _mm256_setr_epi8(0, 1, 1, 2, 1, 2, 2, 3, 1, 2, 2, 3, 2, 3, 3, 4, 0, 1, 1, 2, 1, 2, 2, 3, 1, 2, 2,
                                       3, 2, 3, 3, 4);
  const __m256i low = _mm256_set1_epi8(0x0f);
  const __m256i lo = _mm256_shuffle_epi8(lut, _mm256_and_si256(v, low));
  const __m256i hi = _mm256_shuffle_epi8(lut, _mm256_and_si256(_mm256_srli_epi16(v, 4), low));
  return _mm256_sad_epu8(_mm256_add_epi8(lo, hi), _mm256_setzero_si256());
}

// Per-byte popcount of a 256-bit vector (nibble look-up, vpshufb), values 0..8.
__attribute__((target("avx2"))) inline __m256i popcountBytes256(__m256i v)
{
  const __m256i lut = _mm256_setr_epi8(0, 1, 1, 2, 1, 2, 2, 3, 1, 2, 2, 3, 2, 3, 3, 4, 0, 1, 1, 2, 1, 2, 2, 3, 1, 2, 2,
                                       3, 2, 3, 3, 4);
  const __m256i low = _mm256_set1_epi8(0x0f);
  return _mm256_add_epi8(_mm256_shuffle_epi8(lut, _mm256_and_si256(v, low)),
                         _mm256_shuffle_epi8(lut, _mm256_and_si256(_mm256_srli_epi16(v, 4), low)));
}

// 16 distances of 128-bit codes with no scalar step: SAD gives each code's two 64-bit halves, two rounds of
// packus + madd add the halves and narrow to 16 bits, one unpack restores the order. (The 4-code loop below
// stored the lanes and copied them one by one: only 1.1x the POPCNT path, issue 21.)
__attribute__((target("avx2"))) inline void sixteen128(const uint64_t* c, __m256i qv, uint16_t* out)
{
  const __m256i zero = _mm256_setzero_si256(), ones = _mm256_set1_epi16(1);
  const __m256i* p = reinterpret_cast<const __m256i*>(c);
  __m256i s[8];
  for (int k = 0; k < 8; ++k)  // s[k] = [c(2k).w0, c(2k).w1 | c(2k+1).w0, c(2k+1).w1] as 64-bit lanes
    s[k] = _mm256_sad_epu8(popcountBytes256(_mm256_xor_si256(_mm256_loadu_si256(p + k), qv)), zero);
  // 16-bit halves, lane 0 = [c0 c2 c4 c6] and lane 1 = [c1 c3 c5 c7], two halves each; madd adds them.
  const __m256i a = _mm256_madd_epi16(
      _mm256_packus_epi32(_mm256_packus_epi32(s[0], s[1]), _mm256_packus_epi32(s[2], s[3])), ones);
  const __m256i b = _mm256_madd_epi16(
      _mm256_packus_epi32(_mm256_packus_epi32(s[4], s[5]), _mm256_packus_epi32(s[6], s[7])), ones);
  const __m256i d = _mm256_packus_epi32(a, b);  // lane 0 = even codes 0..14, lane 1 = odd codes 1..15
  const __m128i even = _mm256_castsi256_si128(d), odd = _mm256_extracti128_si256(d, 1);
  _mm_storeu_si128(reinterpret_cast<__m128i*>(out), _mm_unpacklo_epi16(even, odd));
  _mm_storeu_si128(reinterpret_cast<__m128i*>(out + 8), _mm_unpackhi_epi16(even, odd));
}

__attribute__((target("avx2,popcnt"))) void avx2Distances(const uint64_t* q, const uint64_t* c, size_t count, int words,
                                                          uint16_t* out)
{
  size_t i = 0;
  if (words == 1)
  {
    const __m256i qv = _mm256_set1_epi64x(static_cast<long long>(q[0]));
    alignas(32) uint64_t lanes[4];
    for (; i + 4 <= count; i += 4)
    {
      const __m256i v = _mm256_loadu_si256(reinterpret_cast<const __m256i*>(c + i));
      _mm256_store_si256(reinterpret_cast<__m256i*>(lanes), popcountLanes256(_mm256_xor_si256(v, qv)));
      for (int k = 0; k < 4; ++k)
        out[i + k] = static_cast<uint16_t>(lanes[k]);
    }
  }
  else if (words == 2)
  {
    const __m256i qv = _mm256_setr_epi64x(static_cast<long long>(q[0]), static_cast<long long>(q[1]),
                                          static_cast<long long>(q[0]), static_cast<long long>(q[1]));
    for (; i + 16 <= count; i += 16)
      sixteen128(c + 2 * i, qv, out + i);
    alignas(32) uint64_t lanes[4];
    for (; i + 4 <= count; i += 4)
    {
      const __m256i a = popcountLanes256(
          _mm256_xor_si256(_mm256_loadu_si256(reinterpret_cast<const __m256i*>(c + 2 * i)), qv));
      const __m256i b = popcountLanes256(
          _mm256_xor_si256(_mm256_loadu_si256(reinterpret_cast<const __m256i*>(c + 2 * i + 4)), qv));
      // a = [c0w0 c0w1 c1w0 c1w1], b = [c2w0 c2w1 c3w0 c3w1] -> [c0 c2 c1 c3] -> [c0 c1 c2 c3]
      const __m256i sum = _mm256_add_epi64(_mm256_unpacklo_epi64(a, b), _mm256_unpackhi_epi64(a, b));
      _mm256_store_si256(reinterpret_cast<__m256i*>(lanes), _mm256_permute4x64_epi64(sum, 0xD8));
      for (int k = 0; k < 4; ++k)
        out[i + k] = static_cast<uint16_t>(lanes[k]);
    }
  }
  else
  {
    alignas(32) uint64_t lanes[4];
    for (; i < count; ++i)
    {
      const uint64_t* ci = c + i * words;
      __m256i acc = _mm256_setzero_si256();
      for (int w = 0; w < words; w += 4)
      {
        const __m256i v = _mm256_xor_si256(_mm256_loadu_si256(reinterpret_cast<const __m256i*>(ci + w)),
                                           _mm256_loadu_si256(reinterpret_cast<const __m256i*>(q + w)));
        acc = _mm256_add_epi64(acc, popcountLanes256(v));
      }
      _mm256_store_si256(reinterpret_cast<__m256i*>(lanes), acc);
      out[i] = static_cast<uint16_t>(lanes[0] + lanes[1] + lanes[2] + lanes[3]);
    }
  }
  if (i < count)
    popcntDistances(q, c + i * words, count - i, words, out + i);
}

__attribute__((target("avx512f,avx512vpopcntdq,popcnt"))) void avx512Distances(const uint64_t* q, const uint64_t* c,
                                                                               size_t count, int words, uint16_t* out)
{
  size_t i = 0;
  if (words == 1)
  {
    const __m512i qv = _mm512_set1_epi64(static_cast<long long>(q[0]));
    for (; i + 8 <= count; i += 8)
    {
      const __m512i p = _mm512_popcnt_epi64(_mm512_xor_si512(_mm512_loadu_si512(c + i), qv));
      _mm_storeu_si128(reinterpret_cast<__m128i*>(out + i), _mm512_cvtepi64_epi16(p));
    }
  }
  else if (words == 2)
  {
    const __m512i qv = _mm512_set4_epi64(static_cast<long long>(q[1]), static_cast<long long>(q[0]),
                                         static_cast<long long>(q[1]), static_cast<long long>(q[0]));
    const __m512i even = _mm512_setr_epi64(0, 2, 4, 6, 8, 10, 12, 14);
    const __m512i odd = _mm512_setr_epi64(1, 3, 5, 7, 9, 11, 13, 15);
    for (; i + 8 <= count; i += 8)
    {
      const __m512i a = _mm512_popcnt_epi64(_mm512_xor_si512(_mm512_loadu_si512(c + 2 * i), qv));
      const __m512i b = _mm512_popcnt_epi64(_mm512_xor_si512(_mm512_loadu_si512(c + 2 * i + 8), qv));
      const __m512i sum = _mm512_add_epi64(_mm512_permutex2var_epi64(a, even, b), _mm512_permutex2var_epi64(a, odd, b));
      _mm_storeu_si128(reinterpret_cast<__m128i*>(out + i), _mm512_cvtepi64_epi16(sum));
    }
  }
  else if (words == 8)
  {
    for (; i < count; ++i)
    {
      const __m512i v = _mm512_xor_si512(_mm512_loadu_si512(c + i * 8), _mm512_loadu_si512(q));
      out[i] = static_cast<uint16_t>(_mm512_reduce_add_epi64(_mm512_popcnt_epi64(v)));
    }
  }
  else  // 4 words: two codes per vector
  {
    const __m512i qv = _mm512_broadcast_i64x4(_mm256_loadu_si256(reinterpret_cast<const __m256i*>(q)));
    for (; i + 2 <= count; i += 2)
    {
      const __m512i p = _mm512_popcnt_epi64(_mm512_xor_si512(_mm512_loadu_si512(c + 4 * i), qv));
      out[i] = static_cast<uint16_t>(_mm512_mask_reduce_add_epi64(0x0F, p));
      out[i + 1] = static_cast<uint16_t>(_mm512_mask_reduce_add_epi64(0xF0, p));
    }
  }
  if (i < count)
    popcntDistances(q, c + i * words, count - i, words, out + i);
}

// The pairwise kernels write 16-bit counts or the same counts as floats (a stereo cost volume's type).
template <class T>
void scalarPairwise(const uint64_t* a, const uint64_t* b, size_t count, int words, T* out)
{
  for (size_t i = 0; i < count; ++i, a += words, b += words)
    out[i] = static_cast<T>(hammingDistanceReference(a, b, words));
}

template <class T>
__attribute__((target("popcnt"))) void popcntPairwise(const uint64_t* a, const uint64_t* b, size_t count, int words,
                                                      T* out)
{
  if (words == 4)  // unrolled: the stereo cost volume's case
  {
    for (size_t i = 0; i < count; ++i, a += 4, b += 4)
      out[i] = static_cast<T>(_mm_popcnt_u64(a[0] ^ b[0]) + _mm_popcnt_u64(a[1] ^ b[1]) + _mm_popcnt_u64(a[2] ^ b[2]) +
                              _mm_popcnt_u64(a[3] ^ b[3]));
    return;
  }
  for (size_t i = 0; i < count; ++i, a += words, b += words)
  {
    uint64_t d = 0;
    for (int w = 0; w < words; ++w)
      d += _mm_popcnt_u64(a[w] ^ b[w]);
    out[i] = static_cast<T>(d);
  }
}

// 8 pairs of 256-bit codes: per-64-bit-lane counts (SAD of the byte counts), then packus + madd add each
// code's halves and narrow to 16 bits, as sixteen128 does; one 128-bit add joins the halves of the lanes.
// Returns the 8 counts as 32-bit lanes, in order.
__attribute__((target("avx2"))) inline __m256i eight256Pairwise(const uint64_t* a, const uint64_t* b)
{
  const __m256i zero = _mm256_setzero_si256(), ones = _mm256_set1_epi16(1);
  const __m256i* pa = reinterpret_cast<const __m256i*>(a);
  const __m256i* pb = reinterpret_cast<const __m256i*>(b);
  __m256i s[8];
  for (int k = 0; k < 8; ++k)  // s[k] = [c(k).w0, c(k).w1 | c(k).w2, c(k).w3] as 64-bit lanes
    s[k] = _mm256_sad_epu8(popcountBytes256(_mm256_xor_si256(_mm256_loadu_si256(pa + k), _mm256_loadu_si256(pb + k))),
                           zero);
  // 16-bit words per lane: lane 0 = [c0.w0 c0.w1 c1.w0 c1.w1 c2.. c3..], lane 1 the same of w2, w3; madd
  // adds pairs: lane 0 = (w0 + w1) of c0..c3, lane 1 = (w2 + w3) of c0..c3 as 32-bit.
  const __m256i lo = _mm256_madd_epi16(
      _mm256_packus_epi32(_mm256_packus_epi32(s[0], s[1]), _mm256_packus_epi32(s[2], s[3])), ones);
  const __m256i hi = _mm256_madd_epi16(
      _mm256_packus_epi32(_mm256_packus_epi32(s[4], s[5]), _mm256_packus_epi32(s[6], s[7])), ones);
  return _mm256_add_epi32(_mm256_permute2x128_si256(lo, hi, 0x20),
                          _mm256_permute2x128_si256(lo, hi, 0x31));  // [c0..c3 | c4..c7]
}

__attribute__((target("avx2"))) inline void storeCounts(__m256i counts32, uint16_t* out)
{
  const __m256i packed = _mm256_permute4x64_epi64(_mm256_packus_epi32(counts32, counts32), 0x08);
  _mm_storeu_si128(reinterpret_cast<__m128i*>(out), _mm256_castsi256_si128(packed));
}

__attribute__((target("avx2"))) inline void storeCounts(__m256i counts32, float* out)
{
  _mm256_storeu_ps(out, _mm256_cvtepi32_ps(counts32));
}

template <class T>
__attribute__((target("avx2,popcnt"))) void avx2Pairwise(const uint64_t* a, const uint64_t* b, size_t count, int words,
                                                         T* out)
{
  if (words != 4)
  {
    popcntPairwise(a, b, count, words, out);
    return;
  }
  size_t i = 0;
  for (; i + 8 <= count; i += 8)
    storeCounts(eight256Pairwise(a + 4 * i, b + 4 * i), out + i);
  if (i == count)
    return;
  // The last 1..7 pairs copied into zeroed blocks of 8 (a zero xor counts 0) and run through the same
  // kernel: on short rows the scalar tail cost as much as the vector part.
  alignas(32) uint64_t ta[32] = {}, tb[32] = {};
  std::memcpy(ta, a + 4 * i, 32 * (count - i));
  std::memcpy(tb, b + 4 * i, 32 * (count - i));
  alignas(32) int32_t counts[8];
  _mm256_store_si256(reinterpret_cast<__m256i*>(counts), eight256Pairwise(ta, tb));
  for (size_t j = 0; i + j < count; ++j)
    out[i + j] = static_cast<T>(counts[j]);
}

// Counts of 8 consecutive pairs of 256-bit codes as 64-bit lanes, in order; words k * 8 .. k * 8 + 7 of the
// 32 are loaded where bit k of `present` (a word mask per vector) says so, zero elsewhere (a zero xor counts 0).
__attribute__((target("avx512f,avx512vpopcntdq"))) inline __m512i eight256PairwiseAvx512(const uint64_t* a,
                                                                                         const uint64_t* b,
                                                                                         const __mmask8 present[4])
{
  // Two codes per vector; two rounds of even/odd lane pairing add each code's four counts in order.
  const __m512i even = _mm512_setr_epi64(0, 2, 4, 6, 8, 10, 12, 14);
  const __m512i odd = _mm512_setr_epi64(1, 3, 5, 7, 9, 11, 13, 15);
  __m512i p[4];
  for (int k = 0; k < 4; ++k)
    p[k] = _mm512_popcnt_epi64(_mm512_xor_si512(_mm512_maskz_loadu_epi64(present[k], a + 8 * k),
                                                _mm512_maskz_loadu_epi64(present[k], b + 8 * k)));
  const __m512i e = _mm512_add_epi64(_mm512_permutex2var_epi64(p[0], even, p[1]),
                                     _mm512_permutex2var_epi64(p[0], odd, p[1]));  // c0..c3, two halves each
  const __m512i f = _mm512_add_epi64(_mm512_permutex2var_epi64(p[2], even, p[3]),
                                     _mm512_permutex2var_epi64(p[2], odd, p[3]));  // c4..c7
  return _mm512_add_epi64(_mm512_permutex2var_epi64(e, even, f), _mm512_permutex2var_epi64(e, odd, f));
}

template <class T>
__attribute__((target("avx512f,avx512vpopcntdq,popcnt"))) void avx512Pairwise(const uint64_t* a, const uint64_t* b,
                                                                              size_t count, int words, T* out)
{
  if (words != 4)
  {
    popcntPairwise(a, b, count, words, out);
    return;
  }
  const __mmask8 all[4] = {0xFF, 0xFF, 0xFF, 0xFF};
  size_t i = 0;
  for (; i + 8 <= count; i += 8)
  {
    const __m512i sum = eight256PairwiseAvx512(a + 4 * i, b + 4 * i, all);
    if constexpr (std::is_same_v<T, float>)
      _mm256_storeu_ps(out + i, _mm256_cvtepi32_ps(_mm512_cvtepi64_epi32(sum)));
    else
      _mm_storeu_si128(reinterpret_cast<__m128i*>(out + i), _mm512_cvtepi64_epi16(sum));
  }
  if (i == count)
    return;
  // The last 1..7 pairs through masked loads (never beyond the codes' end): a short row's scalar tail was
  // as costly as its vector part (BioBin's fast mode: 113 px rows).
  const int words_left = static_cast<int>(4 * (count - i));
  __mmask8 present[4];
  for (int k = 0; k < 4; ++k)
    present[k] = static_cast<__mmask8>(words_left <= 8 * k       ? 0
                                       : words_left >= 8 * k + 8 ? 0xFF
                                                                 : (1u << (words_left - 8 * k)) - 1);
  alignas(32) int32_t counts[8];
  _mm256_store_si256(reinterpret_cast<__m256i*>(counts),
                     _mm512_cvtepi64_epi32(eight256PairwiseAvx512(a + 4 * i, b + 4 * i, present)));
  for (size_t j = 0; i + j < count; ++j)
    out[i + j] = static_cast<T>(counts[j]);
}

bool available(HammingPath path)
{
  switch (path)
  {
    case HammingPath::Scalar:
      return true;
    case HammingPath::Popcnt:
      return CpuFeatures::host().popcnt;
    case HammingPath::Avx2:
      return CpuFeatures::host().avx2 && CpuFeatures::host().popcnt;
    case HammingPath::Avx512:
      // The kernels' tails run the POPCNT loop.
      return CpuFeatures::host().avx512f && CpuFeatures::host().avx512vpopcntdq && CpuFeatures::host().popcnt;
  }
  return false;
}
}  // namespace

std::string toString(HammingPath path)
{
  switch (path)
  {
    case HammingPath::Scalar:
      return "scalar";
    case HammingPath::Popcnt:
      return "popcnt";
    case HammingPath::Avx2:
      return "avx2";
    case HammingPath::Avx512:
      return "avx512-vpopcntdq";
  }
  return "?";
}

std::vector<HammingPath> availableHammingPaths()
{
  std::vector<HammingPath> paths;
  for (HammingPath p : {HammingPath::Scalar, HammingPath::Popcnt, HammingPath::Avx2, HammingPath::Avx512})
    if (available(p))
      paths.push_back(p);
  return paths;
}

HammingPath bestHammingPath()
{
  static const HammingPath best = availableHammingPaths().back();
  return best;
}

int hammingDistanceReference(const uint64_t* a, const uint64_t* b, int words)
{
  int d = 0;
  for (int w = 0; w < words; ++w)
    d += countBits(a[w] ^ b[w]);
  return d;
}

namespace
{
/// Checks `words` and that this CPU runs `path` (std::invalid_argument naming `function` otherwise), then
/// runs the kernel of that path.
template <class Scalar, class Popcnt, class Avx2, class Avx512>
void dispatch(const char* function, HammingPath path, int words, Scalar scalar, Popcnt popcnt, Avx2 avx2, Avx512 avx512)
{
  if (words != 1 && words != 2 && words != 4 && words != 8)
    throw std::invalid_argument(std::string(function) + ": words must be 1, 2, 4 or 8");
  if (!available(path))
    throw std::invalid_argument(std::string(function) + ": this CPU cannot run the " + toString(path) + " path");
  switch (path)
  {
    case HammingPath::Scalar:
      return scalar();
    case HammingPath::Popcnt:
      return popcnt();
    case HammingPath::Avx2:
      return avx2();
    case HammingPath::Avx512:
      return avx512();
  }
}

template <class T>
void pairwise(HammingPath path, const uint64_t* a, const uint64_t* b, size_t count, int words, T* out)
{
  dispatch(
      "hammingDistancesPairwise", path, words, [&] { scalarPairwise(a, b, count, words, out); },
      [&] { popcntPairwise(a, b, count, words, out); }, [&] { avx2Pairwise(a, b, count, words, out); },
      [&] { avx512Pairwise(a, b, count, words, out); });
}
}  // namespace

void hammingDistancesPairwise(HammingPath path, const uint64_t* a, const uint64_t* b, size_t count, int words,
                              uint16_t* out)
{
  pairwise(path, a, b, count, words, out);
}

void hammingDistancesPairwise(HammingPath path, const uint64_t* a, const uint64_t* b, size_t count, int words,
                              float* out)
{
  pairwise(path, a, b, count, words, out);
}

void hammingDistances(HammingPath path, const uint64_t* query, const uint64_t* codes, size_t count, int words,
                      uint16_t* out)
{
  dispatch(
      "hammingDistances", path, words, [&] { scalarDistances(query, codes, count, words, out); },
      [&] { popcntDistances(query, codes, count, words, out); },
      [&] { avx2Distances(query, codes, count, words, out); },
      [&] { avx512Distances(query, codes, count, words, out); });
}
}  // namespace biovision_common
