#include "biovision_stereo/pixel_descriptor.hpp"

#include <algorithm>
#include <stdexcept>

namespace biovision_stereo
{
namespace
{
constexpr int kOrientations = 8;

// Comparison bits of one response row: bits[x] = R(x) > R(x + 1), replicated border.
void comparisonRow(const float* r, int width, std::vector<std::uint8_t>& bits)
{
  bits.resize(width);
  for (int x = 0; x + 1 < width; ++x)
    bits[x] = r[x] > r[x + 1];
  bits[width - 1] = 0;  // R(w-1) > R(w-1) is false
}

inline std::uint8_t bitAt(const std::vector<std::uint8_t>& bits, int x)
{
  // Left of the image the replicated response is constant, so the comparison is false as well.
  return x < 0 || x >= static_cast<int>(bits.size()) ? 0 : bits[x];
}

void checkInput(const std::vector<cv::Mat>& odd)
{
  if (odd.size() != kOrientations)
    throw std::invalid_argument("PixelDescriptor: needs 8 orientation maps");
  for (const cv::Mat& m : odd)
    if (m.type() != CV_32FC1 || m.size() != odd.front().size() || m.empty())
      throw std::invalid_argument("PixelDescriptor: orientation maps must be CV_32FC1 of one size");
}
}  // namespace

PixelDescriptorImage PixelDescriptorImage::compute(const std::vector<cv::Mat>& odd)
{
  checkInput(odd);
  const int w = odd.front().cols, h = odd.front().rows;
  PixelDescriptorImage image(w, h);
  std::vector<std::vector<std::uint8_t>> bits(h);  // comparisons of every row, once per orientation
  for (int o = 0; o < kOrientations; ++o)
  {
    const int word = o / 2, shift = 32 * (o % 2);
    for (int y = 0; y < h; ++y)
      comparisonRow(odd[o].ptr<float>(y), w, bits[y]);
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
  return image;
}

PixelDescriptor PixelDescriptorImage::fromScratch(const std::vector<cv::Mat>& odd, int x, int y)
{
  checkInput(odd);
  const int w = odd.front().cols, h = odd.front().rows;
  auto response = [&](int o, int xx, int yy) {
    return odd[o].at<float>(std::clamp(yy, 0, h - 1), std::clamp(xx, 0, w - 1));
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
