#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include <opencv2/core.hpp>

namespace biovision_stereo
{
/// 256-bit BioBin pixel descriptor (thesis §4.4.3): for each of 8 orientations, odd simple-cell
/// responses R^O compared with their right neighbour, bit = R(x+i) > R(x+i+1):
///   row y:     i = -8..7 (16 comparisons, R at x-8..x+8)
///   rows y-1, y+1: i = -4..3 (8 each, R at x-4..x+4)
/// = 32 comparisons per orientation. Layout: one byte per sampled position holding its 8 orientations
/// (bit o = orientation o): bytes 0..15 row y, i = -8..7; bytes 16..23 row y-1, i = -4..3; bytes 24..31
/// row y+1, i = -4..3, in this order in memory (on x86: byte b is bits 8(b%8).. of word b/8). (Only Hamming distances are taken,
/// which a fixed order of the bits does not change; this one makes a descriptor three copies of a row of
/// comparison bytes.) Outside the image, responses are those of the nearest pixel (replicated border): a
/// column beyond the left or right edge compares equal responses (0); the row above the first and below
/// the last is the edge row itself, its comparisons repeated.
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

  /// odd: 8 CV_32FC1 maps of equal size, or 4 CV_32FC2 maps with orientations 2i and 2i+1 in channels 0
  /// and 1 (SimpleCellBank::computeOddPairs, no split); throws std::invalid_argument otherwise. Each row's
  /// comparisons are computed once (one byte per pixel, 8 orientations), then every descriptor is copied
  /// together from three rows of them.
  static PixelDescriptorImage compute(const std::vector<cv::Mat>& odd);
  /// The same into `out`, reusing its memory: no allocation when `out` held an image of this size
  /// before (a fresh 450x375 image was 7 MB of page faults per call, a third of BioBin's cell stage).
  static void compute(const std::vector<cv::Mat>& odd, PixelDescriptorImage& out);
  /// Only the comparison bytes (comparisons()), not the descriptors (at() and row() are then empty): what
  /// Hamming::windowRow needs, 1/32 of the memory.
  static void computeComparisons(const std::vector<cv::Mat>& odd, PixelDescriptorImage& out);
  /// The same descriptor computed from scratch at one pixel (the reference for tests); odd as compute().
  static PixelDescriptor fromScratch(const std::vector<cv::Mat>& odd, int x, int y);

  /// compute()'s comparison step for row y, public for its tests: out[x] has bit o set iff
  /// R_o(x) > R_o(x + 1), for 0 <= x < width - 1; out[width - 1] = 0. odd as compute(). avx2 false: the
  /// scalar fallback; true: 8 pixels per step (throws std::invalid_argument when this CPU lacks AVX2).
  /// Both give the same bytes.
  static void comparisonRow(const std::vector<cv::Mat>& odd, int y, std::uint8_t* out, bool avx2);

  /// Zero bytes before position 0 and after width - 1 of every comparison row (the right side also lets a
  /// 64-byte vector loop run past the row's end).
  static constexpr int kLeftMargin = 8, kRightMargin = 72;
  /// Row y's comparison bytes (see comparisonRow): position 0 of the row; positions -kLeftMargin..-1 and
  /// width..width+kRightMargin-1 are readable zeros. Valid after compute() or computeComparisons().
  const std::uint8_t* comparisons(int y) const
  {
    return comparisons_.data() + size_t(y) * (width_ + kLeftMargin + kRightMargin) + kLeftMargin;
  }
  int width() const { return width_; }
  int height() const { return height_; }
  const PixelDescriptor& at(int x, int y) const { return data_[size_t(y) * width_ + x]; }
  PixelDescriptor& at(int x, int y) { return data_[size_t(y) * width_ + x]; }
  const PixelDescriptor* row(int y) const { return data_.data() + size_t(y) * width_; }

private:
  int width_ = 0, height_ = 0;
  std::vector<PixelDescriptor> data_;
  std::vector<std::uint8_t> comparisons_;  // per row: 8 zero bytes, width comparison bytes, 8 zero bytes
};
}  // namespace biovision_stereo
