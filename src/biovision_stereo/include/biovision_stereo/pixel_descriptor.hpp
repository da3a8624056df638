#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include <opencv2/core.hpp>

namespace biovision_stereo
{
/// 256-bit BioBin pixel descriptor (thesis §4.4.3): for each of 8 orientations, odd simple-cell
/// responses R^O compared with their right neighbour, bit = R(x+i) > R(x+i+1):
///   row y:     i = -8..7 (16 bits, R at x-8..x+8)
///   rows y-1, y+1: i = -4..3 (8 bits each, R at x-4..x+4)
/// = 32 bits per orientation. Orientation o occupies bits [32(o%2), 32(o%2)+32) of word o/2; inside,
/// row y is bits 16..31 (oldest comparison highest), row y-1 bits 8..15, row y+1 bits 0..7.
/// Outside the image, responses are those of the nearest pixel (replicated border).
struct PixelDescriptor
{
  std::array<std::uint64_t, 4> words{};
  bool operator==(const PixelDescriptor& o) const { return words == o.words; }
};

/// Descriptors of a whole image, row-major.
class PixelDescriptorImage
{
public:
  PixelDescriptorImage() = default;
  PixelDescriptorImage(int width, int height) : width_(width), height_(height), data_(size_t(width) * height) {}

  /// Rolling computation: each pixel's code is the previous one shifted by one with one new
  /// comparison appended per segment (thesis §4.4.3). odd: 8 CV_32FC1 maps of equal size, or 4 CV_32FC2
  /// maps with orientations 2i and 2i+1 in channels 0 and 1 (SimpleCellBank::computeOddPairs, no split);
  /// throws std::invalid_argument otherwise.
  static PixelDescriptorImage compute(const std::vector<cv::Mat>& odd);
  /// The same into `out`, reusing its memory: no allocation when `out` held an image of this size
  /// before (a fresh 450x375 image was 7 MB of page faults per call, a third of BioBin's cell stage).
  static void compute(const std::vector<cv::Mat>& odd, PixelDescriptorImage& out);
  /// The same descriptor computed from scratch at one pixel (the reference for tests); odd as compute().
  static PixelDescriptor fromScratch(const std::vector<cv::Mat>& odd, int x, int y);

  /// compute()'s comparison step for one row of an orientation pair (CV_32FC2 row, orientations a and b
  /// interleaved), public for its tests: out_a[w - 1 - x] = R_a(x) > R_a(x + 1) ? 0xFF : 0 for
  /// 0 <= x < width - 1, likewise out_b; out_a[0], out_b[0] untouched. avx2 false: the scalar fallback;
  /// true: 8 pixels per step (throws std::invalid_argument when this CPU lacks AVX2). Both give the same bytes.
  static void comparePairRow(const float* pair_row, int width, std::uint8_t* out_a, std::uint8_t* out_b, bool avx2);

  int width() const { return width_; }
  int height() const { return height_; }
  const PixelDescriptor& at(int x, int y) const { return data_[size_t(y) * width_ + x]; }
  PixelDescriptor& at(int x, int y) { return data_[size_t(y) * width_ + x]; }
  const PixelDescriptor* row(int y) const { return data_.data() + size_t(y) * width_; }

private:
  int width_ = 0, height_ = 0;
  std::vector<PixelDescriptor> data_;
  std::vector<std::uint8_t> comparisons_;  // compute()'s scratch, kept with the image for reuse
};
}  // namespace biovision_stereo
