#include "biovision_recognition/multi_index_hash.hpp"

#include <algorithm>

namespace biovision_recognition
{
void MultiIndexHash::build(const BinaryCodeSet& library)
{
  library_ = library;
  substrings_ = library.bits() / kSubstringBits;
  offsets_.assign(substrings_, std::vector<uint32_t>(65537, 0));
  ids_.assign(substrings_, std::vector<uint32_t>(library.size()));
  for (int s = 0; s < substrings_; ++s)
  {
    auto& off = offsets_[s];
    for (size_t i = 0; i < library.size(); ++i)
      ++off[substring(library.code(i), s) + 1];
    for (size_t b = 1; b < off.size(); ++b)
      off[b] += off[b - 1];
    std::vector<uint32_t> fill(off.begin(), off.end() - 1);
    for (size_t i = 0; i < library.size(); ++i)
      ids_[s][fill[substring(library.code(i), s)]++] = static_cast<uint32_t>(i);
  }
  seen_.assign(library.size(), 0);
  stamp_ = 0;
}

const std::vector<uint16_t>& MultiIndexHash::flipMasks(int radius) const
{
  radius = std::min(radius, kSubstringBits);
  if (static_cast<int>(flip_masks_.size()) <= radius)
    flip_masks_.resize(radius + 1);
  auto& masks = flip_masks_[radius];
  if (masks.empty())
  {
    for (uint32_t m = 0; m < 65536; ++m)
      if (__builtin_popcount(m) <= radius)
        masks.push_back(static_cast<uint16_t>(m));
    std::stable_sort(masks.begin(), masks.end(),
                     [](uint16_t a, uint16_t b) { return __builtin_popcount(a) < __builtin_popcount(b); });
  }
  return masks;
}

double MultiIndexHash::candidateFraction(int radius) const
{
  if (substrings_ == 0)
    return 1.0;
  return std::min(1.0, substrings_ * static_cast<double>(flipMasks(radius / substrings_).size()) / 65536.0);
}

std::vector<HammingMatch> MultiIndexHash::radiusSearch(const uint64_t* query, int radius) const
{
  std::vector<HammingMatch> out;
  if (library_.empty() || radius < 0)
    return out;
  if (++stamp_ == 0)  // wrapped: clear the stamps once every 2^32 searches
  {
    std::fill(seen_.begin(), seen_.end(), 0);
    stamp_ = 1;
  }
  const auto& masks = flipMasks(radius / substrings_);
  const int words = library_.words();
  for (int s = 0; s < substrings_; ++s)
  {
    const uint16_t key = substring(query, s);
    const auto& off = offsets_[s];
    const auto& ids = ids_[s];
    for (uint16_t m : masks)
    {
      const uint16_t bucket = key ^ m;
      for (uint32_t k = off[bucket]; k < off[bucket + 1]; ++k)
      {
        const uint32_t id = ids[k];
        if (seen_[id] == stamp_)
          continue;
        seen_[id] = stamp_;
        int d = 0;
        const uint64_t* c = library_.code(id);
        for (int w = 0; w < words; ++w)
          d += __builtin_popcountll(query[w] ^ c[w]);
        if (d <= radius)
          out.push_back({0, id, static_cast<uint16_t>(d)});
      }
    }
  }
  std::sort(out.begin(), out.end(), [](const HammingMatch& a, const HammingMatch& b) {
    return a.distance != b.distance ? a.distance < b.distance : a.train < b.train;
  });
  return out;
}
}  // namespace biovision_recognition
