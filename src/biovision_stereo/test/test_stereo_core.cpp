// Unit tests of the ROS-free BioBin core.
#include <algorithm>
#include <cmath>
#include <limits>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <random>
#include <utility>
#include <vector>

#include <gtest/gtest.h>
#include <opencv2/imgproc.hpp>

#include "biovision_stereo/bio_bin_matcher.hpp"
#include "biovision_stereo/cost_simd.hpp"
#include "biovision_stereo/disparity_dog.hpp"
#include "biovision_common/eval/disparity_metrics.hpp"
#include "biovision_stereo/hamming.hpp"
#include "biovision_stereo/iterative_spatial_filter.hpp"
#include "biovision_stereo/linear_resampling.hpp"
#include "biovision_stereo/occlusion_filling.hpp"
#include "biovision_common/eval/middlebury_dataset.hpp"
#include "biovision_common/cpu_features.hpp"
#include "biovision_common/parallel_arena.hpp"
#include "biovision_stereo/pixel_descriptor.hpp"
#include "biovision_stereo/semi_global_aggregation.hpp"
#include "biovision_v1/fourier_transform.hpp"
#include "biovision_v1/gabor_parameters.hpp"
#include "biovision_v1/simple_cell_bank.hpp"
#include "biovision_common/eval/portable_float_map.hpp"

using biovision_common::DisparityMetrics;
using biovision_common::MiddleburyDataset;
using biovision_common::PortableFloatMap;
using biovision_common::StereoScene;

using namespace biovision_stereo;
namespace fs = std::filesystem;

namespace
{
// Smooth random colour texture: matchable everywhere, like a real textured surface.
cv::Mat texture(cv::Size size, unsigned seed, int blob = 3)
{
  cv::RNG rng(seed);
  cv::Mat small(size.height / blob + 2, size.width / blob + 2, CV_8UC3);
  rng.fill(small, cv::RNG::UNIFORM, 0, 256);
  cv::Mat big;
  cv::resize(small, big, cv::Size(small.cols * blob, small.rows * blob), 0, 0, cv::INTER_CUBIC);
  return big(cv::Rect(0, 0, size.width, size.height)).clone();
}

// A textured fronto-parallel plane at disparity d: a texture `extra` px wider than `size`, the left view
// from column `margin`, the right from margin + d, so that left(x) = right(x - d).
std::pair<cv::Mat, cv::Mat> shiftedPair(cv::Size size, int d, int margin, int extra, unsigned seed, int blob = 3)
{
  const cv::Mat wide = texture(cv::Size(size.width + extra, size.height), seed, blob);
  return {wide(cv::Rect(margin, 0, size.width, size.height)).clone(),
          wide(cv::Rect(margin + d, 0, size.width, size.height)).clone()};
}

std::string sharedData()
{
  const char* env = std::getenv("BIOVISION_SHARED");
  return std::string(env ? env : "../shared") + "/data";
}

std::vector<cv::Mat> randomResponses(cv::Size size, unsigned seed)
{
  cv::RNG rng(seed);
  std::vector<cv::Mat> odd(8);
  for (auto& m : odd)
  {
    m.create(size, CV_32F);
    rng.fill(m, cv::RNG::NORMAL, 0, 1);
  }
  return odd;
}

// Brute-force semi-global aggregation: every path direction on its own in 64-bit integers, straight from
// the recursion (Hirschmueller 2008), summed over the forward (predecessor left of / above p) or backward
// directions. Returns S(x, y, d) at (y * w + x) * nd + d.
std::vector<long> sgmReference(const std::vector<std::uint16_t>& costs, int w, int h, int nd, int p1, int p2,
                               int p2_barrier, const cv::Mat& barriers, int paths, bool backward)
{
  const int stride = SemiGlobalAggregation::stride(nd);
  std::vector<std::pair<int, int>> predecessor{{-1, 0}, {0, -1}};  // (dx, dy) of p - r
  if (paths == 8)
    predecessor = {{-1, 0}, {-1, -1}, {0, -1}, {1, -1}};
  std::vector<long> sum(size_t(w) * h * nd, 0);
  for (auto [dx, dy] : predecessor)
  {
    if (backward)
    {
      dx = -dx;
      dy = -dy;
    }
    std::vector<long> l(size_t(w) * h * nd);
    for (int i = 0; i < w * h; ++i)
    {
      const int index = backward ? w * h - 1 - i : i;  // predecessors come first in this order
      const int x = index % w, y = index / w, qx = x + dx, qy = y + dy;
      const long pen2 = !barriers.empty() && barriers.at<uchar>(y, x) ? std::max(p1, p2_barrier) : p2;
      const bool first = qx < 0 || qx >= w || qy < 0 || qy >= h;
      const long* q = first ? nullptr : &l[(size_t(qy) * w + qx) * nd];
      const long qmin = first ? 0 : *std::min_element(q, q + nd);
      for (int d = 0; d < nd; ++d)
      {
        long v = 0;
        if (!first)
        {
          v = std::min(q[d], qmin + pen2);
          if (d > 0)
            v = std::min(v, q[d - 1] + p1);
          if (d + 1 < nd)
            v = std::min(v, q[d + 1] + p1);
          v -= qmin;
        }
        l[size_t(index) * nd + d] = costs[size_t(index) * stride + d] + v;
      }
    }
    for (size_t i = 0; i < l.size(); ++i)
      sum[i] += l[i];
  }
  return sum;
}

// Background at disparity 4 and an 80x60 foreground square at disparity 14 (x 100..179, y 30..89 in the
// left image): left of the square a 10 px band of background is visible in the left image only.
void occludedScene(int width, int height, cv::Mat& left, cv::Mat& right)
{
  const cv::Mat bg = texture(cv::Size(width + 40, height), 21);
  const cv::Mat fg = texture(cv::Size(80, 60), 22, 2);
  left = bg(cv::Rect(20, 0, width, height)).clone();
  right = bg(cv::Rect(20 + 4, 0, width, height)).clone();
  fg.copyTo(left(cv::Rect(100, 30, 80, 60)));
  fg.copyTo(right(cv::Rect(100 - 14, 30, 80, 60)));
}
}  // namespace

TEST(PixelDescriptor, RollingEqualsFromScratchEverywhere)
{
  // Widths below, at and beyond the 16 comparisons of a segment, one-row images, and ties (rounded
  // responses: R(x) == R(x+1) is a 0 bit). `reused` goes through every size in turn, growing and shrinking:
  // what an earlier image left in its memory must never show.
  PixelDescriptorImage reused;
  for (const cv::Size size :
       {cv::Size(37, 9), cv::Size(1, 1), cv::Size(2, 3), cv::Size(16, 1), cv::Size(17, 2), cv::Size(100, 4)})
    for (const bool ties : {false, true})
    {
      auto odd = randomResponses(size, 5 + size.width);
      if (ties)
        for (cv::Mat& m : odd)
          m.forEach<float>([](float& v, const int*) { v = std::round(v); });
      const PixelDescriptorImage codes = PixelDescriptorImage::compute(odd);
      // The same responses as orientation pairs (SimpleCellBank::computeOddPairs), through a view.
      std::vector<cv::Mat> pairs(4);
      for (int i = 0; i < 4; ++i)
      {
        cv::Mat padded;
        cv::merge(std::vector<cv::Mat>{odd[2 * i], odd[2 * i + 1]}, padded);
        cv::copyMakeBorder(padded, padded, 1, 1, 2, 3, cv::BORDER_CONSTANT, cv::Scalar::all(1e9));
        pairs[i] = padded(cv::Rect(2, 1, size.width, size.height));
      }
      const PixelDescriptorImage from_pairs = PixelDescriptorImage::compute(pairs);
      PixelDescriptorImage::compute(ties ? pairs : odd, reused);
      ASSERT_EQ(reused.width(), size.width);
      ASSERT_EQ(reused.height(), size.height);
      for (int y = 0; y < size.height; ++y)
        for (int x = 0; x < size.width; ++x)
        {
          ASSERT_TRUE(codes.at(x, y) == PixelDescriptorImage::fromScratch(odd, x, y))
              << "at " << x << "," << y << " of " << size << (ties ? " with ties" : "");
          ASSERT_TRUE(from_pairs.at(x, y) == codes.at(x, y))
              << "pairs at " << x << "," << y << " of " << size << (ties ? " with ties" : "");
          ASSERT_TRUE(reused.at(x, y) == codes.at(x, y))
              << "reused image at " << x << "," << y << " of " << size << (ties ? " with ties" : "");
        }
    }
}

TEST(PixelDescriptor, ComparisonRowsAreTheSameOnEveryPath)
{
  // Widths around the 8-pixel step (the last pixel read is x + 8), ties and NaN (compare false), as 8 maps
  // and as 4 interleaved pairs.
  std::mt19937 rng(4);
  std::uniform_int_distribution<int> level(-3, 3);
  const bool avx2 = biovision_common::CpuFeatures::host().avx2;
  for (const int w : {1, 2, 8, 9, 10, 16, 17, 25, 113, 450})
    for (int trial = 0; trial < 4; ++trial)
    {
      std::vector<cv::Mat> odd(8);
      for (cv::Mat& m : odd)
      {
        m.create(2, w, CV_32F);
        m.forEach<float>([&](float& v, const int*) { v = static_cast<float>(level(rng)); });  // few levels: ties
      }
      if (trial == 3 && w > 3)
        odd[5].at<float>(1, 2) = odd[2].at<float>(1, w - 1) = std::numeric_limits<float>::quiet_NaN();
      std::vector<cv::Mat> pairs(4);
      for (int i = 0; i < 4; ++i)
        cv::merge(std::vector<cv::Mat>{odd[2 * i], odd[2 * i + 1]}, pairs[i]);
      std::vector<std::uint8_t> ref(w, 0);
      for (int x = 0; x + 1 < w; ++x)  // the definition, written out
        for (int o = 0; o < 8; ++o)
          ref[x] |= static_cast<std::uint8_t>((odd[o].at<float>(1, x) > odd[o].at<float>(1, x + 1)) << o);
      for (const auto* input : {&odd, &pairs})
        for (const bool simd : {false, true})
        {
          std::vector<std::uint8_t> got(w, 0xA5);
          if (simd && !avx2)
          {
            EXPECT_THROW(PixelDescriptorImage::comparisonRow(*input, 1, got.data(), true), std::invalid_argument);
            continue;
          }
          PixelDescriptorImage::comparisonRow(*input, 1, got.data(), simd);
          EXPECT_EQ(got, ref) << "width " << w << (input == &pairs ? " pairs" : " maps")
                              << (simd ? " avx2" : " generic");
        }
    }
}

TEST(Hamming, WindowRowEqualsTheDescriptorsDistances)
{
  // Every row (the first and last clamp their neighbours), every shift up to beyond the width, widths
  // around the 16-wide window; ties in the responses give zero comparisons, random ones about half.
  for (const cv::Size size : {cv::Size(1, 1), cv::Size(5, 3), cv::Size(17, 4), cv::Size(40, 5), cv::Size(113, 3)})
    for (const bool ties : {false, true})
    {
      auto left = randomResponses(size, 3 + size.width), right = randomResponses(size, 101 + size.width);
      if (ties)
        for (cv::Mat& m : right)
          m.forEach<float>([](float& v, const int*) { v = std::round(v * 0.5f); });
      const PixelDescriptorImage a = PixelDescriptorImage::compute(left), b = PixelDescriptorImage::compute(right);
      PixelDescriptorImage a_only, b_only;  // comparisons alone give the same
      PixelDescriptorImage::computeComparisons(left, a_only);
      PixelDescriptorImage::computeComparisons(right, b_only);
      std::vector<float> expected(size.width), got(size.width), got_only(size.width);
      for (int y = 0; y < size.height; ++y)
        for (int shift = 0; shift <= size.width + 1; ++shift)
        {
          Hamming::row(a.row(y), b.row(y), size.width, shift, -1.f, expected.data());
          Hamming::windowRow(a, b, y, shift, -1.f, got.data());
          Hamming::windowRow(a_only, b_only, y, shift, -1.f, got_only.data());
          ASSERT_EQ(got, expected) << size << " row " << y << " shift " << shift << (ties ? " ties" : "");
          ASSERT_EQ(got_only, expected) << size << " row " << y << " shift " << shift;
        }
    }
  const PixelDescriptorImage small = PixelDescriptorImage::compute(randomResponses(cv::Size(4, 2), 1));
  const PixelDescriptorImage other = PixelDescriptorImage::compute(randomResponses(cv::Size(5, 2), 1));
  std::vector<float> out(5);
  EXPECT_THROW(Hamming::windowRow(small, other, 0, 0, 0.f, out.data()), std::invalid_argument);
  EXPECT_THROW(Hamming::windowRow(small, small, 2, 0, 0.f, out.data()), std::invalid_argument);
}

TEST(PixelDescriptor, BitsFollowTheSamplingPattern)
{
  // One orientation with R increasing to the right except a single drop: only the comparisons that
  // see the drop are 1.
  std::vector<cv::Mat> odd(8);
  for (auto& m : odd)
    m = cv::Mat::zeros(5, 40, CV_32F);
  for (int x = 0; x < 40; ++x)
    odd[0].at<float>(2, x) = static_cast<float>(x);
  odd[0].at<float>(2, 20) = 100.f;  // R(20) > R(21): bit for position 20 on row 2
  const auto byteOf = [](const PixelDescriptor& d, int b) {
    return reinterpret_cast<const std::uint8_t*>(d.words.data())[b];
  };
  const auto ones = [&](const PixelDescriptor& d) {
    int n = 0;
    for (int b = 0; b < 32; ++b)
      n += __builtin_popcount(byteOf(d, b));
    return n;
  };
  // Row y: bytes 0..15 are positions x-8..x+7, so position 20 seen from x = 20 is byte 8, orientation 0 bit 0.
  const PixelDescriptor d = PixelDescriptorImage::fromScratch(odd, 20, 2);
  EXPECT_EQ(byteOf(d, 8), 1);
  EXPECT_EQ(ones(d), 1);
  // Seen from x = 25 it is position i = -5: byte 3.
  EXPECT_EQ(byteOf(PixelDescriptorImage::fromScratch(odd, 25, 2), 3), 1);
  // Row y-1 (from row 3): bytes 16..23 are positions x-4..x+3, position 20 is byte 16 + 4.
  const PixelDescriptor above = PixelDescriptorImage::fromScratch(odd, 20, 3);
  EXPECT_EQ(byteOf(above, 20), 1);
  EXPECT_EQ(ones(above), 1);
  // Row y+1 (from row 1): bytes 24..31.
  EXPECT_EQ(byteOf(PixelDescriptorImage::fromScratch(odd, 20, 1), 28), 1);
  // Beyond the window: nothing.
  EXPECT_EQ(ones(PixelDescriptorImage::fromScratch(odd, 29, 2)), 0);
  // Orientation 5's drop is bit 5.
  odd[5].at<float>(2, 10) = 50.f;
  EXPECT_EQ(byteOf(PixelDescriptorImage::fromScratch(odd, 10, 2), 8), 1 << 5);
}

TEST(Hamming, EveryPathEqualsTheScalarReference)
{
  std::mt19937_64 rng(11);
  std::vector<PixelDescriptor> a(64), b(64);
  for (size_t i = 0; i < a.size(); ++i)
    for (int w = 0; w < 4; ++w)
    {
      a[i].words[w] = rng();
      b[i].words[w] = rng();
    }
  a[0] = b[0];  // distance 0
  for (int w = 0; w < 4; ++w)
    b[1].words[w] = ~a[1].words[w];  // distance 256
  for (size_t i = 0; i < a.size(); ++i)
  {
    int bits = 0;
    for (int w = 0; w < 4; ++w)
      for (int j = 0; j < 64; ++j)
        bits += ((a[i].words[w] ^ b[i].words[w]) >> j) & 1;
    EXPECT_EQ(Hamming::distanceScalar(a[i], b[i]), bits);
    EXPECT_EQ(Hamming::distance(a[i], b[i]), bits);
  }
  EXPECT_EQ(Hamming::distance(a[0], b[0]), 0);
  EXPECT_EQ(Hamming::distance(a[1], b[1]), 256);
  std::vector<float> row(64);
  Hamming::row(a.data(), b.data(), 64, 3, 999.f, row.data());
  EXPECT_EQ(row[2], 999.f);
  for (int x = 3; x < 64; ++x)
    EXPECT_EQ(row[x], Hamming::distanceScalar(a[x], b[x - 3]));
  // A long row with a shift that leaves a SIMD tail (601 - 37 = 564 = 8 * 70 + 4 pixels).
  std::vector<PixelDescriptor> c(601), e(601);
  for (size_t i = 0; i < c.size(); ++i)
    for (int w = 0; w < 4; ++w)
    {
      c[i].words[w] = rng();
      e[i].words[w] = rng();
    }
  const int n = static_cast<int>(c.size());
  for (const auto path : biovision_common::availableHammingPaths())
    for (int shift : {0, 37, n - 1, n, n + 5})
    {
      std::vector<float> long_row(c.size(), -1.f);
      Hamming::row(c.data(), e.data(), n, shift, 999.f, long_row.data(), path);
      for (int x = 0; x < n; ++x)
        ASSERT_EQ(long_row[x], x < shift ? 999.f : Hamming::distanceScalar(c[x], e[x - shift]))
            << biovision_common::toString(path) << " shift " << shift << " x " << x;
    }
  float untouched = -1.f;
  Hamming::row(c.data(), e.data(), 0, 0, 999.f, &untouched);  // width 0: nothing written
  EXPECT_EQ(untouched, -1.f);
  EXPECT_FALSE(Hamming::pathName().empty());
}

TEST(DisparityDog, RecursiveBroadGaussianMatchesTheExactFir)
{
  CostVolume in(cv::Size(7, 3), 60);
  cv::RNG rng(2);
  for (int k = 0; k < 60; ++k)
    rng.fill(in.slice(k), cv::RNG::UNIFORM, 0, 256);
  const DisparityDog dog(1.0, 8.0, 0.4, 1.0, 0.5);
  CostVolume fast, exact;
  dog.apply(in, fast);
  dog.applyReference(in, exact);
  double worst = 0;
  for (int k = 0; k < 60; ++k)
    worst = std::max(worst, cv::norm(fast.slice(k), exact.slice(k), cv::NORM_INF));
  // Stated tolerance: 1% of the cost range (0..256): the Young-van Vliet recursion approximates the
  // sampled Gaussian (the ends are padded, so the border matches).
  EXPECT_LT(worst, 0.01 * 256) << "max |recursive - FIR| = " << worst;
  std::printf("DoG: max |recursive - FIR| = %.3f on costs in [0, 256]\n", worst);
  // In place (no second volume): the same arithmetic, so bit for bit the same costs.
  const auto deepCopy = [](const CostVolume& v) {
    CostVolume c(v.size(), v.disparities());
    for (int k = 0; k < v.disparities(); ++k)
      v.slice(k).copyTo(c.slice(k));
    return c;
  };
  CostVolume in_place = deepCopy(in);
  dog.applyInPlace(in_place);
  for (int k = 0; k < 60; ++k)
    EXPECT_EQ(cv::norm(fast.slice(k), in_place.slice(k), cv::NORM_INF), 0.0) << "slice " << k;
  // Narrow sigmas only (the exact FIR for both Gaussians): in place equals the reference exactly too.
  const DisparityDog narrow(0.5, 1.5, 0.4, 1.0, 0.5);
  CostVolume reference, narrow_in_place = deepCopy(in);
  narrow.applyReference(in, reference);
  narrow.applyInPlace(narrow_in_place);
  for (int k = 0; k < 60; ++k)
    EXPECT_EQ(cv::norm(reference.slice(k), narrow_in_place.slice(k), cv::NORM_INF), 0.0) << "slice " << k;
  // One row at a time needs a row per disparity in and out; a volume without disparities is left alone.
  std::vector<std::vector<float>> scratch;
  std::vector<float*> none;
  EXPECT_THROW(dog.applyRow({}, 5, none, scratch), std::invalid_argument);
  std::vector<float> row(5, 1.f), out_row(5);
  std::vector<float*> two{out_row.data(), out_row.data()};
  EXPECT_THROW(dog.applyRow({row.data()}, 5, two, scratch), std::invalid_argument);
  CostVolume empty(cv::Size(5, 3), 0), empty_out;
  EXPECT_NO_THROW(dog.applyInPlace(empty));
  EXPECT_NO_THROW(dog.apply(empty, empty_out));
  EXPECT_EQ(empty_out.disparities(), 0);
}

TEST(CostVolume, MinimumAndMaximumOverEverySliceIgnoreNaN)
{
  for (const cv::Size size : {cv::Size(1, 1), cv::Size(7, 3), cv::Size(8, 2), cv::Size(19, 5)})
  {
    CostVolume costs(size, 5);
    cv::RNG rng(size.width);
    for (int k = 0; k < 5; ++k)
      rng.fill(costs.slice(k), cv::RNG::UNIFORM, 0.0, 1.0);
    // The extremes at the last pixel of a row (the vector loops' tail or last lane) of a middle slice.
    costs.slice(2).at<float>(size.height - 1, size.width - 1) = -4.f;
    costs.slice(3).at<float>(0, size.width - 1) = 9.f;
    costs.slice(1).at<float>(0, 0) = std::numeric_limits<float>::quiet_NaN();
    if (size.area() > 1)
    {
      EXPECT_EQ(costs.min(), -4.f) << size;
      EXPECT_EQ(costs.max(), 9.f) << size;
    }
    // Row ranges: the extremes of those rows only, empty range = the identity.
    EXPECT_EQ(costs.min(size.height - 1, size.height), -4.f) << size;
    EXPECT_EQ(costs.max(0, 1), 9.f) << size;
    if (size.height > 1)
    {
      EXPECT_GT(costs.min(0, size.height - 1), -4.f) << size;
      EXPECT_LT(costs.max(1, size.height), 9.f) << size;
    }
    EXPECT_EQ(costs.max(1, 1), -HUGE_VALF) << size;
    EXPECT_THROW(costs.max(0, size.height + 1), std::out_of_range) << size;
    EXPECT_THROW(costs.min(-1, 1), std::out_of_range) << size;
    EXPECT_THROW(costs.min(1, 0), std::out_of_range) << size;
  }
  // Runs of values: every length around the 8-lane blocks, the extreme in the tail and in a block, NaN.
  for (int n = 0; n <= 19; ++n)
  {
    std::vector<float> v(n);
    for (int i = 0; i < n; ++i)
      v[i] = static_cast<float>((i * 7) % 5);
    if (n > 0)
    {
      v[n - 1] = -3.f;
      v[n / 2] = std::numeric_limits<float>::quiet_NaN();
      v[0] = n > 2 ? 11.f : v[0];
    }
    float lo = HUGE_VALF, hi = -HUGE_VALF;
    for (const float x : v)
      if (!std::isnan(x))
      {
        lo = std::min(lo, x);
        hi = std::max(hi, x);
      }
    EXPECT_EQ(CostVolume::lowestOf(v.data(), n), lo) << n;
    EXPECT_EQ(CostVolume::highestOf(v.data(), n), hi) << n;
    EXPECT_EQ(CostVolume::lowestOf(v.data(), n, -10.f), -10.f) << n;  // the running extreme carries over
    EXPECT_EQ(CostVolume::highestOf(v.data(), n, 20.f), 20.f) << n;
    EXPECT_EQ(CostVolume::lowestOf(v.data(), n, std::numeric_limits<float>::quiet_NaN()), lo) << n;
    EXPECT_EQ(CostVolume::highestOf(v.data(), n, std::numeric_limits<float>::quiet_NaN()), hi) << n;
  }
  EXPECT_EQ(CostVolume().min(), HUGE_VALF);
  EXPECT_EQ(CostVolume().max(), -HUGE_VALF);
}

TEST(SemiGlobalAggregation, PixelMajorCostsEqualTheScalarConversion)
{
  // Widths and disparity counts around the 8x8 transpose's blocks; costs from the minimum to beyond
  // saturation.
  for (const cv::Size size : {cv::Size(1, 1), cv::Size(7, 2), cv::Size(8, 3), cv::Size(21, 5)})
    for (int nd : {1, 7, 8, 9, 17, 40})
    {
      CostVolume costs(size, nd);
      cv::RNG rng(nd * 100 + size.width);
      for (int k = 0; k < nd; ++k)
        rng.fill(costs.slice(k), cv::RNG::UNIFORM, -3.0, 300.0);
      float lowest = HUGE_VALF;
      for (int k = 0; k < nd; ++k)
        for (int y = 0; y < size.height; ++y)
          for (int x = 0; x < size.width; ++x)
            lowest = std::min(lowest, costs.at(x, y, k));
      const float scale = 8.f;
      std::vector<std::uint16_t> out;
      SemiGlobalAggregation::toPixelMajor(costs, lowest, scale, out);
      const int stride = SemiGlobalAggregation::stride(nd);
      ASSERT_EQ(out.size(), size_t(size.area()) * stride);
      int wrong = 0, saturated = 0;
      for (int y = 0; y < size.height; ++y)
        for (int x = 0; x < size.width; ++x)
          for (int k = 0; k < nd; ++k)
          {
            const auto expected = static_cast<std::uint16_t>(
                std::min((costs.at(x, y, k) - lowest) * scale + 0.5f, float(SemiGlobalAggregation::kMaxCost)));
            wrong += out[(size_t(y) * size.width + x) * stride + k] != expected;
            saturated += expected == SemiGlobalAggregation::kMaxCost;
          }
      EXPECT_EQ(wrong, 0) << size << " nd " << nd;
      if (size.area() * nd > 100)
      {
        EXPECT_GT(saturated, 0) << "the test should reach saturation";
      }
    }
}

TEST(SemiGlobalAggregation, WinnersEqualTheScalarWinnerTakeAll)
{
  const std::vector<SemiGlobalAggregation::Simd> simds = SemiGlobalAggregation::availableSimds();
  std::mt19937 rng(11);
  for (int nd : {1, 2, 15, 16, 33})
    for (int w : {1, 5, 40})
    {
      const int h = 3, stride = SemiGlobalAggregation::stride(nd);
      // Sums up to each half's bound 4 (kMaxCost + P2); a narrow range in half the cases, for ties.
      const int top = nd % 2 ? 4 * 2 * SemiGlobalAggregation::kMaxCost : 6;
      std::uniform_int_distribution<int> value(0, top);
      std::vector<std::uint16_t> forward(size_t(w) * h * stride), backward(forward.size());
      for (size_t i = 0; i < forward.size(); ++i)
      {
        forward[i] = static_cast<std::uint16_t>(value(rng));
        backward[i] = static_cast<std::uint16_t>(value(rng));
      }
      for (const bool subpixel : {false, true})
        for (const auto simd : simds)
        {
          cv::Mat left, right_k;
          SemiGlobalAggregation::winners(forward, backward, w, h, nd, subpixel, left, right_k, simd);
          ASSERT_EQ(left.size(), cv::Size(w, h));
          int wrong = 0;
          for (int y = 0; y < h; ++y)
          {
            // The reference: 32-bit sums, the first least one, right pixels by a strict <.
            std::vector<std::uint32_t> best_right(w, ~0u);
            std::vector<int> k_right(w, -1);
            for (int x = 0; x < w; ++x)
            {
              const size_t index = (size_t(y) * w + x) * stride;
              const int kmax = std::min(nd - 1, x);
              std::vector<std::uint32_t> sum(kmax + 1);
              for (int k = 0; k <= kmax; ++k)
                sum[k] = std::uint32_t(forward[index + k]) + backward[index + k];
              int best = 0;
              for (int k = 1; k <= kmax; ++k)
                if (sum[k] < sum[best])
                  best = k;
              for (int k = 0; k <= kmax; ++k)
                if (sum[k] < best_right[x - k])
                {
                  best_right[x - k] = sum[k];
                  k_right[x - k] = k;
                }
              float d = float(best);
              if (subpixel && best > 0 && best < kmax)
              {
                const float cm = float(sum[best - 1]), c0 = float(sum[best]), cp = float(sum[best + 1]);
                const float den = cm - 2 * c0 + cp;
                if (den > 0)
                  d += std::clamp(0.5f * (cm - cp) / den, -0.5f, 0.5f);
              }
              wrong += left.at<float>(y, x) != d;
            }
            for (int x = 0; x < w; ++x)
              wrong += right_k.at<int>(y, x) != k_right[x];
          }
          EXPECT_EQ(wrong, 0) << SemiGlobalAggregation::name(simd) << " nd " << nd << " w " << w
                              << (subpixel ? " subpixel" : "");
        }
    }
  cv::Mat left, right_k;
  EXPECT_THROW(SemiGlobalAggregation::winners(std::vector<std::uint16_t>(10), std::vector<std::uint16_t>(10), 3, 3, 4,
                                              false, left, right_k, SemiGlobalAggregation::Simd::kGeneric),
               std::invalid_argument);  // sums do not match the sizes
  const size_t wide = size_t(SemiGlobalAggregation::stride(40000));
  EXPECT_THROW(SemiGlobalAggregation::winners(std::vector<std::uint16_t>(wide), std::vector<std::uint16_t>(wide), 1, 1,
                                              40000, false, left, right_k, SemiGlobalAggregation::Simd::kGeneric),
               std::invalid_argument);  // more disparities than 16 bits hold
}

TEST(SemiGlobalAggregation, EveryPathEqualsTheBruteForceReference)
{
  // Small random volumes: disparity counts below, at and just under a SIMD vector's end; costs up to the
  // largest allowed, so that saturation and the blocked lanes are exercised; random barriers.
  std::mt19937 rng(7);
  const std::vector<SemiGlobalAggregation::Simd> simds = SemiGlobalAggregation::availableSimds();
  if (simds.size() == 1)
    std::fprintf(stderr, "no AVX2 on this CPU: only the generic path is compared with the reference\n");
  for (int nd : {1, 5, 15, 16, 31, 40, 65})
    for (int paths : {4, 8})
    {
      const int w = 13, h = 9, stride = SemiGlobalAggregation::stride(nd);
      ASSERT_EQ(stride % 16, 0);
      ASSERT_GT(stride, nd);
      std::vector<std::uint16_t> costs(size_t(w) * h * stride);
      std::uniform_int_distribution<int> cost(0, SemiGlobalAggregation::kMaxCost);
      for (auto& c : costs)
        c = static_cast<std::uint16_t>(nd > 16 ? cost(rng) : cost(rng) % 64);  // small volumes: low costs
      cv::Mat barriers(h, w, CV_8U);
      cv::randu(barriers, 0, 2);
      const int p1 = 7, p2 = nd > 16 ? SemiGlobalAggregation::kMaxCost : 40, p2_barrier = 3;
      const SemiGlobalAggregation sgm(p1, p2, p2_barrier, paths);
      const auto forward_ref = sgmReference(costs, w, h, nd, p1, p2, p2_barrier, barriers, paths, false);
      const auto backward_ref = sgmReference(costs, w, h, nd, p1, p2, p2_barrier, barriers, paths, true);
      std::vector<std::uint16_t> first_forward, first_backward;
      for (const auto simd : simds)
      {
        // Sums of another size's last call: aggregate() must overwrite them, not add to them.
        std::vector<std::uint16_t> forward(costs.size() + 5, 0x1234), backward(costs.size() - 3, 0x4321);
        sgm.aggregate(costs, w, h, nd, barriers, forward, backward, simd);
        ASSERT_EQ(forward.size(), costs.size());
        int wrong = 0;
        for (int i = 0; i < w * h; ++i)
          for (int d = 0; d < nd; ++d)
          {
            wrong += forward[size_t(i) * stride + d] != forward_ref[size_t(i) * nd + d];
            wrong += backward[size_t(i) * stride + d] != backward_ref[size_t(i) * nd + d];
          }
        EXPECT_EQ(wrong, 0) << SemiGlobalAggregation::name(simd) << " nd " << nd << " paths " << paths;
        if (first_forward.empty())
        {
          first_forward = forward;
          first_backward = backward;
        }
        else  // every lane, blocked ones included: the SIMD paths agree bit for bit
        {
          EXPECT_EQ(forward, first_forward) << "nd " << nd << " paths " << paths;
          EXPECT_EQ(backward, first_backward) << "nd " << nd << " paths " << paths;
        }
      }
    }
  EXPECT_THROW(SemiGlobalAggregation(10, 5, 5, 8), std::invalid_argument);  // P1 > P2
  EXPECT_THROW(SemiGlobalAggregation(1, 5, 5, 6), std::invalid_argument);   // paths
  const SemiGlobalAggregation sgm(1, 5, 5, 4);
  std::vector<std::uint16_t> f, b;
  EXPECT_THROW(sgm.aggregate(std::vector<std::uint16_t>(10), 3, 3, 4, cv::Mat(), f, b,
                             SemiGlobalAggregation::Simd::kGeneric),
               std::invalid_argument);  // volume size
}

TEST(BioBinMatcher, ShiftedTextureGivesTheExactDisparity)
{
  const int width = 160, height = 100;
  for (const std::string aggregation : {"iterative", "semi_global"})
    for (int d : {0, 5, 12})
    {
      const auto [left, right] = shiftedPair(cv::Size(width, height), d, 20, 40, 3 + d);
      BioBinParameters p;
      p.max_disparity = 24;
      p.aggregation = aggregation;
      BioBinMatcher matcher(p);
      const cv::Mat disparity = matcher.compute(left, right).disparity;
      // The winner is the exact integer disparity; the sub-pixel parabola stays within half a pixel.
      int exact = 0, close = 0, n = 0;
      for (int y = 10; y < height - 10; ++y)
        for (int x = 40; x < width - 10; ++x)
        {
          const float v = disparity.at<float>(y, x);
          ++n;
          exact += v >= 0 && std::lround(v) == d;
          close += std::abs(v - d) < 0.5f;
        }
      EXPECT_GT(exact, 0.99 * n) << aggregation << " disparity " << d << ": " << exact << " of " << n << " exact";
      EXPECT_GT(close, 0.99 * n) << aggregation << " disparity " << d << ": " << close << " of " << n
                                 << " within 0.5 px";
    }
}

TEST(BioBinMatcher, ASmallerFrameAfterALargerOneMatchesAsAFreshMatcherDoes)
{
  // A smaller frame drops the caches the larger one grew (memory given back); its map stays that of a
  // matcher that never saw the larger frame. Not bit for bit: DFT plans measured meanwhile (FFTW's wisdom
  // is global) round differently, which moves sub-pixel values by up to 0.2 px on ~10% of the pixels.
  const int d = 7;
  const auto [small_l, small_r] = shiftedPair(cv::Size(160, 100), d, 20, 40, 5);
  const auto [large_l, large_r] = shiftedPair(cv::Size(240, 160), 9, 20, 40, 6);
  for (const std::string aggregation : {"iterative", "semi_global"})
  {
    BioBinParameters p;
    p.max_disparity = 24;
    p.aggregation = aggregation;
    BioBinMatcher used(p);
    used.compute(small_l, small_r);
    used.compute(large_l, large_r);
    const cv::Mat again = used.compute(small_l, small_r).disparity;
    const cv::Mat expected = BioBinMatcher(p).compute(small_l, small_r).disparity;
    ASSERT_EQ(again.size(), small_l.size());
    int agree = 0, exact = 0, n = 0;
    for (int y = 10; y < again.rows - 10; ++y)
      for (int x = 40; x < again.cols - 10; ++x)
      {
        ++n;
        agree += std::abs(again.at<float>(y, x) - expected.at<float>(y, x)) <= 0.25f;
        exact += std::abs(again.at<float>(y, x) - d) < 0.5f;
      }
    EXPECT_GT(agree, 0.99 * n) << aggregation << ": " << agree << " of " << n;
    EXPECT_GT(exact, 0.99 * n) << aggregation << ": " << exact << " of " << n;
  }
}

// The fast mode (one level, lambda 16: quarter size) on a pair.
static cv::Mat fastModeDisparity(const cv::Mat& left, const cv::Mat& right, int max_disparity)
{
  BioBinParameters p;
  p.wavelengths = {16.0};
  p.max_disparity = max_disparity;
  return BioBinMatcher(p).compute(left, right).disparity;
}

TEST(BioBinMatcher, FastModeFindsTheDisparityAtQuarterSize)
{
  const int width = 320, height = 240, d = 16;
  const auto [left, right] = shiftedPair(cv::Size(width, height), d, 40, 60, 9, 8);
  const cv::Mat disparity = fastModeDisparity(left, right, 48);
  ASSERT_EQ(disparity.size(), left.size()) << "output comes back at input resolution";
  int good = 0, n = 0;
  for (int y = 20; y < height - 20; y += 2)
    for (int x = 80; x < width - 20; x += 2)
    {
      ++n;
      good += std::abs(disparity.at<float>(y, x) - d) <= 1.0f;
    }
  EXPECT_GT(good, 0.9 * n) << good << " of " << n;
}

TEST(BioBinMatcher, DisparitiesStayWithinMaxDisparity)
{
  // One level at quarter size with max_disparity 30: the level's disparities run to ceil(30 / 4) = 8, i.e.
  // 32 px. A scene at 32 px must come back at 30, not beyond the map's declared range.
  const int width = 320, height = 120, d = 32;
  const auto [left, right] = shiftedPair(cv::Size(width, height), d, 60, 100, 19, 8);
  const cv::Mat disparity = fastModeDisparity(left, right, 30);
  double lowest = 0, highest = 0;
  cv::minMaxLoc(disparity, &lowest, &highest, nullptr, nullptr, disparity >= 0);
  EXPECT_EQ(highest, 30.0);  // reached (the scene lies beyond it) and never exceeded
  EXPECT_GE(cv::countNonZero(disparity == 30.f), width * height / 2);
}

TEST(BioBinMatcher, LeftRightCheckInvalidatesTheOccludedBand)
{
  // Background at disparity 4, a foreground square at disparity 14: left of the square, a band of
  // 10 px of background is visible only in the left image and must come out invalid.
  const int width = 200, height = 120;
  cv::Mat left, right;
  occludedScene(width, height, left, right);
  BioBinParameters p;
  p.max_disparity = 24;
  p.fill_occlusions = false;
  BioBinMatcher matcher(p);
  const cv::Mat disparity = matcher.compute(left, right).disparity;
  int invalid = 0, n = 0;
  for (int y = 40; y < 80; ++y)
    for (int x = 91; x < 99; ++x)
    {
      ++n;
      invalid += disparity.at<float>(y, x) < 0;
    }
  EXPECT_GT(invalid, 0.5 * n) << "occluded band: " << invalid << " of " << n << " invalid";
  // The square itself is found.
  int square = 0, m = 0;
  for (int y = 45; y < 75; ++y)
    for (int x = 115; x < 170; ++x)
    {
      ++m;
      square += std::abs(disparity.at<float>(y, x) - 14) <= 1.0f;
    }
  EXPECT_GT(square, 0.9 * m);
}

// Issue 21 item 3: the cost-volume loops (masked costs, DoG, fusion) compiled for AVX2 give the baseline
// path's values bit for bit (no FMA, no reassociation), so the speed-up changes no output.
// Results compared bit for bit: no DFT plan may be measured (and round differently) between their runs.
// RAII, so a failed assertion still restores the process-wide default.
namespace
{
struct EstimatedPlansOnly
{
  EstimatedPlansOnly() { biovision_v1::FourierTransform::setMeasurePolicy(0); }
  ~EstimatedPlansOnly()
  {
    biovision_v1::FourierTransform::setMeasurePolicy(biovision_v1::FourierTransform::kMeasureAfter);
  }
};
}  // namespace

TEST(BioBinMatcher, LevelCostsEqualTheStepByStepReference)
{
  // levelCosts() runs steps (b), (d), the modulation and (e) fused, one image row at a time; the reference
  // runs each step over the whole level: descriptors, Hamming rows, the N_th smallest SAD by sorting, the
  // modulation, then the two-volume DoG. Same arithmetic per cost, so the same bits.
  const EstimatedPlansOnly estimated_plans_only;
  const int width = 75, height = 30;  // 75: no multiple of 8 or 16
  const cv::Mat bg = texture(cv::Size(width + 20, height), 41);
  const cv::Mat left = bg(cv::Rect(10, 0, width, height)).clone(), right = bg(cv::Rect(14, 0, width, height)).clone();
  BioBinParameters p;
  p.max_disparity = 20;
  BioBinMatcher matcher(p);
  for (const size_t level : {size_t(0), size_t(1)})
  {
    const double sf = p.scaleFactor(level);
    const int nd = static_cast<int>(std::ceil(p.max_disparity / sf)) + 1;
    float max_cost = 0.f;
    const CostVolume fused = matcher.levelCosts(level, left, right, nd, nullptr, &max_cost);

    // Per view: 8-bit L*a*b* and the descriptors of the odd cells of its grey image in [0, 1].
    biovision_v1::GaborParameters gabor;
    gabor.wavelengths = {p.base_wavelength};
    gabor.orientations = 8;
    gabor.min_grid_wavelength = 0.0;
    biovision_v1::SimpleCellBank bank(gabor);
    const auto view = [&bank](const cv::Mat& bgr, cv::Mat& lab) {
      cv::Mat gray, unit;
      cv::cvtColor(bgr, lab, cv::COLOR_BGR2Lab);
      cv::cvtColor(bgr, gray, cv::COLOR_BGR2GRAY);
      gray.convertTo(unit, CV_32F, 1.0 / 255.0);
      return PixelDescriptorImage::compute(bank.computeOddPairs(unit)[0]);
    };
    cv::Mat left_lab, right_lab;
    const PixelDescriptorImage lc = view(left, left_lab), rc = view(right, right_lab);
    const int n_th = std::clamp(static_cast<int>(std::lround(std::log2(std::max(2.0, p.max_disparity / sf)))), 1, nd);
    const float damp = static_cast<float>(1.0 - p.kappa), boost = static_cast<float>(1.0 + p.kappa);
    CostVolume masked(left.size(), nd);
    for (int y = 0; y < height; ++y)
    {
      for (int k = 0; k < nd; ++k)
        Hamming::row(lc.row(y), rc.row(y), width, k, 256.f, masked.slice(k).ptr<float>(y));
      for (int x = 0; x < width; ++x)
      {
        std::vector<int> sad(nd);
        for (int k = 0; k < nd; ++k)
        {
          sad[k] = 3 * 255 + 1;  // the disparity leaves the right image
          if (x >= k)
          {
            sad[k] = 0;
            for (int c = 0; c < 3; ++c)
              sad[k] += std::abs(left_lab.at<cv::Vec3b>(y, x)[c] - right_lab.at<cv::Vec3b>(y, x - k)[c]);
          }
        }
        std::vector<int> sorted = sad;
        std::sort(sorted.begin(), sorted.end());
        for (int k = 0; k < nd; ++k)
          masked.slice(k).at<float>(y, x) *= sad[k] <= sorted[n_th - 1] ? damp : boost;
      }
    }
    CostVolume reference;
    DisparityDog(p.sigma1 / sf, p.sigma2 / sf, p.tau, p.alpha, p.beta).apply(masked, reference);
    ASSERT_EQ(fused.disparities(), nd);
    for (int k = 0; k < nd; ++k)
      EXPECT_EQ(cv::norm(fused.slice(k), reference.slice(k), cv::NORM_INF), 0.0) << "level " << level << " slice " << k;
    EXPECT_EQ(max_cost, reference.max()) << "level " << level;
    EXPECT_GT(reference.max(), reference.min()) << "level " << level;  // real costs, not a constant volume
  }
}

TEST(CostSimd, EveryPathGivesTheGenericBitsForBit)
{
  const EstimatedPlansOnly estimated_plans_only;
  const std::vector<CostSimd> simds = availableCostSimds();
  ASSERT_EQ(simds.front(), CostSimd::kGeneric);
  EXPECT_EQ(bestCostSimd(), simds.back());
  for (const CostSimd simd : {CostSimd::kAvx2, CostSimd::kAvx512})
    if (std::find(simds.begin(), simds.end(), simd) == simds.end())
    {
      std::fprintf(stderr, "no %s on this CPU: that cost path must be refused\n", costSimdName(simd).c_str());
      DisparityDog dog(1.0, 8.0, 0.4, 1.0, 0.5);
      EXPECT_THROW(dog.setSimd(simd), std::invalid_argument);
    }
  std::fprintf(stderr, "cost paths on this CPU:");
  for (const CostSimd simd : simds)
    std::fprintf(stderr, " %s", costSimdName(simd).c_str());
  std::fprintf(stderr, "\n");
  EXPECT_EQ(costSimdName(CostSimd::kGeneric), "generic");
  EXPECT_EQ(costSimdName(CostSimd::kAvx2), "avx2");
  EXPECT_EQ(costSimdName(CostSimd::kAvx512), "avx512");
  // DoG: widths that leave a remainder after 16, 8 and 4 lanes, the recursive (sigma2 >= 2) and FIR broad pass.
  for (const cv::Size size : {cv::Size(37, 3), cv::Size(64, 2), cv::Size(5, 4), cv::Size(93, 2)})
    for (const double sigma2 : {8.0, 1.5})
    {
      CostVolume in(size, 41);
      cv::RNG rng(5);
      for (int k = 0; k < in.disparities(); ++k)
        rng.fill(in.slice(k), cv::RNG::UNIFORM, 0, 256);
      std::vector<CostVolume> out;
      for (const CostSimd simd : simds)
      {
        DisparityDog dog(1.0, sigma2, 0.4, 1.0, 0.5);
        dog.setSimd(simd);
        EXPECT_EQ(dog.simd(), simd);
        CostVolume v(size, in.disparities());
        for (int k = 0; k < in.disparities(); ++k)
          in.slice(k).copyTo(v.slice(k));
        dog.applyInPlace(v);
        out.push_back(std::move(v));
      }
      for (size_t i = 1; i < out.size(); ++i)
        for (int k = 0; k < in.disparities(); ++k)
          EXPECT_EQ(cv::norm(out[0].slice(k), out[i].slice(k), cv::NORM_INF), 0.0)
              << size << " sigma2 " << sigma2 << " slice " << k;
    }
  // The whole matcher (both aggregations: the iterative one fuses and filters every level), on a scene with
  // an occluding square; width 150 is no multiple of 16.
  const int width = 150, height = 90;
  const cv::Mat bg = texture(cv::Size(width + 40, height), 31);
  const cv::Mat fg = texture(cv::Size(60, 40), 32, 2);
  cv::Mat left = bg(cv::Rect(20, 0, width, height)).clone();
  cv::Mat right = bg(cv::Rect(20 + 5, 0, width, height)).clone();
  fg.copyTo(left(cv::Rect(70, 25, 60, 40)));
  fg.copyTo(right(cv::Rect(70 - 13, 25, 60, 40)));
  for (const std::string aggregation : {"semi_global", "iterative"})
  {
    BioBinParameters p;
    p.max_disparity = 24;
    p.aggregation = aggregation;
    std::vector<cv::Mat> maps;
    for (const CostSimd simd : simds)
    {
      BioBinMatcher matcher(p);
      matcher.setCostSimd(simd);
      EXPECT_EQ(matcher.costSimd(), simd);
      maps.push_back(matcher.compute(left, right).disparity);
    }
    int valid = 0;
    for (int y = 0; y < height; ++y)
      for (int x = 0; x < width; ++x)
        valid += maps[0].at<float>(y, x) >= 0;
    EXPECT_GT(valid, width * height / 2) << aggregation;  // a real map, not an empty one
    for (size_t i = 1; i < maps.size(); ++i)
      for (int y = 0; y < height; ++y)
        EXPECT_EQ(std::memcmp(maps[0].ptr(y), maps[i].ptr(y), maps[0].cols * sizeof(float)), 0)
            << aggregation << ": row " << y << " differs between generic and " << costSimdName(simds[i]);
  }
}

TEST(BioBinMatcher, WinnerUpdatesAreTheSameOnEveryPathWithTiesAndNaN)
{
  std::mt19937 rng(8);
  std::uniform_int_distribution<int> level(0, 3);  // four cost levels: ties everywhere
  for (const int n : {1, 7, 8, 9, 31, 150})
  {
    std::vector<std::vector<float>> slices(6, std::vector<float>(n));
    for (auto& slice : slices)
      for (float& v : slice)
        v = static_cast<float>(level(rng));
    slices[2][0] = std::numeric_limits<float>::quiet_NaN();
    std::vector<float> ref_cost(n, HUGE_VALF), ref_right(n, HUGE_VALF);
    std::vector<int> ref_best(n, 0), ref_rk(n, -1);
    for (size_t k = 0; k < slices.size(); ++k)  // the definition: strict <, first (lowest) k wins
      for (int i = 0; i < n; ++i)
      {
        const float v = slices[k][i];
        if (v < ref_cost[i])
          ref_cost[i] = v, ref_best[i] = static_cast<int>(k);
        if (v < ref_right[i])
          ref_right[i] = v, ref_rk[i] = static_cast<int>(k);
      }
    for (const CostSimd simd : availableCostSimds())
    {
      std::vector<float> cost(n, HUGE_VALF), right(n, HUGE_VALF);
      std::vector<int> best(n, 0), rk(n, -1);
      for (size_t k = 0; k < slices.size(); ++k)
        BioBinMatcher::updateWinners(slices[k].data(), n, static_cast<int>(k), cost.data(), best.data(), right.data(),
                                     rk.data(), simd);
      EXPECT_EQ(best, ref_best) << n << " " << costSimdName(simd);
      EXPECT_EQ(rk, ref_rk) << n << " " << costSimdName(simd);
      EXPECT_EQ(cost, ref_cost) << n << " " << costSimdName(simd);
      EXPECT_EQ(right, ref_right) << n << " " << costSimdName(simd);
    }
  }
}

TEST(LinearResampling, EqualsOpenCvsBilinearResizeBitForBit)
{
  // BioBin's level pairs (Middlebury 450x375 and the robot's 320x240), odd sizes, a single pixel, an
  // unchanged size and a reduction; values over several orders of magnitude.
  cv::RNG rng(23);
  const std::vector<std::pair<cv::Size, cv::Size>> sizes{{{225, 188}, {450, 375}}, {{113, 94}, {225, 188}},
                                                         {{80, 60}, {160, 120}},   {{10, 7}, {37, 23}},
                                                         {{1, 1}, {5, 4}},         {{3, 2}, {1, 1}},
                                                         {{40, 30}, {40, 30}},     {{50, 40}, {20, 17}}};
  for (const auto& [in, out] : sizes)
  {
    cv::Mat src(in, CV_32F);
    rng.fill(src, cv::RNG::UNIFORM, -1e3, 1e3);
    cv::Mat expected;
    cv::resize(src, expected, out, 0, 0, cv::INTER_LINEAR);
    const LinearResampling resampling(in, out);
    std::vector<float> scratch;
    cv::Mat got(out, CV_32F, cv::Scalar(-7.f));
    int rows = 0;
    resampling.forEachRow(src, scratch, [&](int y, const float* row) {
      std::copy(row, row + out.width, got.ptr<float>(y));
      ++rows;
    });
    EXPECT_EQ(rows, out.height);
    EXPECT_EQ(std::memcmp(got.data, expected.data, got.total() * sizeof(float)), 0)
        << in << " -> " << out << ": max difference " << cv::norm(got, expected, cv::NORM_INF);
  }
  // An unchanged size is a copy, infinities beside a pixel included (a zero weight would make NaN of them).
  cv::Mat same(7, 9, CV_32F, cv::Scalar(2.f));
  same.at<float>(3, 4) = std::numeric_limits<float>::infinity();
  std::vector<float> scratch;
  LinearResampling(same.size(), same.size()).forEachRow(same, scratch, [&](int y, const float* row) {
    EXPECT_EQ(std::memcmp(row, same.ptr<float>(y), same.cols * sizeof(float)), 0) << "row " << y;
  });
  EXPECT_THROW(LinearResampling(cv::Size(0, 3), cv::Size(4, 4)), std::invalid_argument);
}

// Brute-force reference of OcclusionFilling: per invalid pixel, walk each of the 16 directions to the first valid
// pixel and take the lower median of what was found.
static cv::Mat referenceFill(const cv::Mat& in)
{
  cv::Mat out = in.clone();
  for (int y = 0; y < in.rows; ++y)
    for (int x = 0; x < in.cols; ++x)
    {
      if (in.at<float>(y, x) >= 0)
        continue;
      std::vector<float> found;
      for (const cv::Point& step : OcclusionFilling::directions())
        for (cv::Point q(x + step.x, y + step.y); q.x >= 0 && q.y >= 0 && q.x < in.cols && q.y < in.rows; q += step)
          if (in.at<float>(q) >= 0)
          {
            found.push_back(in.at<float>(q));
            break;
          }
      if (found.empty())
        continue;
      std::sort(found.begin(), found.end());
      out.at<float>(y, x) = found[(found.size() - 1) / 2];
    }
  return out;
}

TEST(OcclusionFilling, EqualsTheBruteForceReference)
{
  std::mt19937 rng(5);
  for (int trial = 0; trial < 40; ++trial)
  {
    const int w = 1 + trial * 3, h = 1 + trial % 7 * 3;
    std::uniform_real_distribution<float> value(0.f, 30.f);
    std::bernoulli_distribution invalid(trial % 5 == 4 ? 0.95 : 0.4);
    cv::Mat d(h, w, CV_32F);
    for (int y = 0; y < h; ++y)
      for (int x = 0; x < w; ++x)
        d.at<float>(y, x) = invalid(rng) ? -1.f : value(rng);
    if (trial == 3)
      d.setTo(-1.f);  // no valid pixel at all: everything stays invalid
    if (trial == 10)
      d(cv::Rect(w / 4, h / 4, w / 2, h / 2)).setTo(-1.f);  // a large hole: values carried across it
    const cv::Mat expected = referenceFill(d);
    OcclusionFilling::fill(d);
    EXPECT_EQ(cv::norm(d, expected, cv::NORM_INF), 0.0) << "trial " << trial;
  }
  // One hole in a known surrounding: 8 neighbours at 1, the 8 knight's-move pixels at 5: a tie, which goes to
  // the lower value (the farther surface: the occluded side).
  cv::Mat d(5, 5, CV_32F, cv::Scalar(5.f));
  d(cv::Rect(1, 1, 3, 3)).setTo(1.f);
  d.at<float>(2, 2) = -1.f;
  OcclusionFilling::fill(d);
  EXPECT_EQ(d.at<float>(2, 2), 1.f);
  d.at<float>(2, 2) = -1.f;
  d.at<float>(2, 3) = -1.f;  // the walk to the right passes it and finds the 5 beyond: 7 ones, 9 fives
  OcclusionFilling::fill(d);
  EXPECT_EQ(d.at<float>(2, 2), 5.f);
  EXPECT_EQ(d.at<float>(2, 3), 1.f);  // 7 ones, 7 fives (two knight's moves leave the image): the tie's lower
  cv::Mat wrong(2, 2, CV_16S);
  EXPECT_THROW(OcclusionFilling::fill(wrong), std::invalid_argument);
}

TEST(BioBinMatcher, OcclusionFillingGivesTheOccludedBandTheBackground)
{
  // The scene of LeftRightCheckInvalidatesTheOccludedBand: the band left of the square is background (4).
  const int width = 200, height = 120;
  cv::Mat left, right;
  occludedScene(width, height, left, right);
  BioBinParameters p;
  p.max_disparity = 24;
  p.fill_occlusions = true;
  const cv::Mat disparity = BioBinMatcher(p).compute(left, right).disparity;
  int background = 0, n = 0, invalid = 0;
  for (int y = 40; y < 80; ++y)
    for (int x = 91; x < 99; ++x)
    {
      ++n;
      background += std::abs(disparity.at<float>(y, x) - 4) <= 1.0f;
    }
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x)
      invalid += disparity.at<float>(y, x) < 0;
  EXPECT_GT(background, 0.8 * n) << "occluded band: " << background << " of " << n << " at the background";
  EXPECT_EQ(invalid, 0);
}

TEST(BioBinMatcher, MedianFilterKeepsTheShiftAndInvalidPixels)
{
  // With the median and without filling, the occluded band of the scene above stays invalid; the
  // square and the background keep their disparities.
  const int width = 200, height = 120;
  cv::Mat left, right;
  occludedScene(width, height, left, right);
  BioBinParameters p;
  p.max_disparity = 24;
  p.fill_occlusions = false;
  p.median_filter = false;
  const cv::Mat raw = BioBinMatcher(p).compute(left, right).disparity;
  p.median_filter = true;
  const cv::Mat median = BioBinMatcher(p).compute(left, right).disparity;
  int still_invalid = 0, invalid = 0, square = 0, m = 0;
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x)
      if (raw.at<float>(y, x) < 0)
      {
        ++invalid;
        still_invalid += median.at<float>(y, x) < 0;
      }
  EXPECT_GT(invalid, 0);
  EXPECT_EQ(still_invalid, invalid);
  for (int y = 45; y < 75; ++y)
    for (int x = 115; x < 170; ++x)
    {
      ++m;
      square += std::abs(median.at<float>(y, x) - 14) <= 1.0f;
    }
  EXPECT_GT(square, 0.9 * m);
}

TEST(BioBinMatcher, RejectsBadInputClearly)
{
  BioBinParameters p;
  p.max_disparity = 32;
  BioBinMatcher matcher(p);
  const cv::Mat a(100, 120, CV_8UC3, cv::Scalar::all(80));
  EXPECT_THROW(matcher.compute(a, cv::Mat(100, 110, CV_8UC3)), std::invalid_argument);  // sizes
  EXPECT_THROW(matcher.compute(a, cv::Mat(100, 120, CV_8UC1)), std::invalid_argument);  // types
  EXPECT_THROW(matcher.compute(cv::Mat(), a), std::invalid_argument);                   // empty
  EXPECT_THROW(matcher.compute(cv::Mat(100, 120, CV_16UC3), cv::Mat(100, 120, CV_16UC3)), std::invalid_argument);
  EXPECT_THROW(matcher.compute(cv::Mat(100, 30, CV_8UC3), cv::Mat(100, 30, CV_8UC3)),
               std::invalid_argument);  // md >= width
  EXPECT_THROW(matcher.compute(cv::Mat(8, 120, CV_8UC3), cv::Mat(8, 120, CV_8UC3)), std::invalid_argument);  // tiny
  BioBinParameters bad;
  bad.wavelengths = {8, 4};
  EXPECT_THROW(BioBinMatcher{bad}, std::invalid_argument);
  bad = BioBinParameters();
  bad.relaxation = 2.0;
  EXPECT_THROW(BioBinMatcher{bad}, std::invalid_argument);
  // Grey input is accepted (taken as colourless BGR).
  const cv::Mat g = texture(cv::Size(120, 100), 4);
  cv::Mat grey;
  cv::cvtColor(g, grey, cv::COLOR_BGR2GRAY);
  EXPECT_NO_THROW(matcher.compute(grey, grey));
}

TEST(DisparityMetrics, HandMadeGroundTruth)
{
  cv::Mat gt = (cv::Mat_<float>(2, 4) << 10, 10, 10, 0,  // last pixel unknown
                20, 20, 20, 20);
  cv::Mat d = (cv::Mat_<float>(2, 4) << 10.2f, 10.7f, 11.5f, 3, 25, -1, 19.1f, 20);
  DisparityMetrics m = DisparityMetrics::compute(d, gt);
  ASSERT_EQ(m.pixels, 7);
  // errors: 0.2, 0.7, 1.5, 5, invalid, 0.9, 0
  EXPECT_NEAR(m.bad05, 100.0 * 5 / 7, 1e-9);  // 0.7 1.5 5 inv 0.9
  EXPECT_NEAR(m.bad1, 100.0 * 3 / 7, 1e-9);   // 1.5 5 inv
  EXPECT_NEAR(m.bad2, 100.0 * 2 / 7, 1e-9);   // 5 inv
  EXPECT_NEAR(m.bad4, 100.0 * 2 / 7, 1e-9);   // 5 inv
  EXPECT_NEAR(m.invalid, 100.0 / 7, 1e-9);
  EXPECT_NEAR(m.avgerr, (0.2 + 0.7 + 1.5 + 5 + 0.9 + 0) / 6, 1e-5);
  cv::Mat mask = (cv::Mat_<uchar>(2, 4) << 255, 0, 0, 0, 0, 0, 0, 255);
  m = DisparityMetrics::compute(d, gt, mask);
  EXPECT_EQ(m.pixels, 2);
  EXPECT_NEAR(m.bad05, 0.0, 1e-9);
}

TEST(PortableFloatMap, ReadsHandWrittenFilesAsStored)
{
  // A 3x2 little-endian file with scale -0.5 (not +-1: OpenCV 4.6 would divide by it), rows bottom
  // to top, one infinite (unknown) value.
  const fs::path dir = fs::temp_directory_path() / "biovision_pfm_test";
  fs::create_directories(dir);
  const float bottom[3] = {4.f, 5.f, 6.f}, top[3] = {1.f, 2.f, INFINITY};
  {
    std::ofstream f(dir / "le.pfm", std::ios::binary);
    f << "Pf\n3  2\n-0.5\n";  // extra blank in the size line
    f.write(reinterpret_cast<const char*>(bottom), sizeof bottom);
    f.write(reinterpret_cast<const char*>(top), sizeof top);
  }
  cv::Mat m = PortableFloatMap::read((dir / "le.pfm").string());
  ASSERT_EQ(m.size(), cv::Size(3, 2));
  EXPECT_EQ(m.at<float>(0, 0), 1.f);
  EXPECT_EQ(m.at<float>(0, 1), 2.f);
  EXPECT_TRUE(std::isinf(m.at<float>(0, 2)));
  EXPECT_EQ(m.at<float>(1, 2), 6.f);
  // Big endian (positive scale 2.0): bytes swapped on disk, values still as stored.
  {
    std::ofstream f(dir / "be.pfm", std::ios::binary);
    f << "Pf\n1 1\n2.0\n";
    const float v = 7.25f;
    unsigned char b[4];
    std::memcpy(b, &v, 4);
    const unsigned char swapped[4] = {b[3], b[2], b[1], b[0]};
    f.write(reinterpret_cast<const char*>(swapped), 4);
  }
  EXPECT_EQ(PortableFloatMap::read((dir / "be.pfm").string()).at<float>(0, 0), 7.25f);
  // Round trip through the writer in both byte orders.
  cv::Mat r(4, 5, CV_32F);
  cv::randu(r, -100, 100);
  for (float scale : {-1.f, 1.f})
  {
    PortableFloatMap::write((dir / "rt.pfm").string(), r, scale);
    EXPECT_EQ(cv::norm(PortableFloatMap::read((dir / "rt.pfm").string()), r, cv::NORM_INF), 0.0);
  }
  // Truncated and foreign files are refused with the file named.
  {
    std::ofstream f(dir / "short.pfm", std::ios::binary);
    f << "Pf\n10 10\n-1\n";
    f.write(reinterpret_cast<const char*>(bottom), sizeof bottom);
  }
  EXPECT_THROW(PortableFloatMap::read((dir / "short.pfm").string()), std::runtime_error);
  {
    std::ofstream f(dir / "p6.pfm");
    f << "P6\n1 1\n255\nabc";
  }
  EXPECT_THROW(PortableFloatMap::read((dir / "p6.pfm").string()), std::runtime_error);
  fs::remove_all(dir);
}

TEST(MiddleburyDataset, CalibToleratesWhitespace)
{
  const fs::path dir = fs::temp_directory_path() / "biovision_calib_test";
  fs::create_directories(dir);
  {
    std::ofstream f(dir / "calib.txt");
    f << "cam0=[1 0 0; 0 1 0; 0 0 1]\n  ndisp = 290 \r\nvmin=0\n";
  }
  EXPECT_EQ(MiddleburyDataset::readCalibNdisp((dir / "calib.txt").string()), 290);
  {
    std::ofstream f(dir / "calib.txt");
    f << "width=10\n";
  }
  EXPECT_THROW(MiddleburyDataset::readCalibNdisp((dir / "calib.txt").string()), std::runtime_error);
  fs::remove_all(dir);
}

TEST(MiddleburyDataset, LoadsTheSharedLayouts)
{
  const std::string root = sharedData() + "/stereo";
  ASSERT_TRUE(fs::is_directory(root)) << "../shared/data/stereo not found (set BIOVISION_SHARED)";
  const StereoScene cones = MiddleburyDataset::loadScene(root + "/middlebury-v2-masks/cones");
  EXPECT_EQ(cones.layout, "v2-masks");
  EXPECT_EQ(cones.max_disparity, 59);
  EXPECT_FALSE(cones.nonoccluded.empty());
  double mx;
  cv::minMaxLoc(cones.ground_truth, nullptr, &mx);
  EXPECT_GT(mx, 50.0);  // groundtruth.png / 4: 55 at most; 59 is the search range of info.txt
  EXPECT_LE(mx, 59.0);
  const StereoScene art = MiddleburyDataset::loadScene(root + "/middlebury-2001-2006/Art");
  EXPECT_EQ(art.layout, "2005-2006");
  ASSERT_FALSE(art.nonoccluded.empty());
  const double nonocc = cv::countNonZero(art.nonoccluded) / double(art.left.total());
  EXPECT_GT(nonocc, 0.6);  // derived from disp1/disp5: most pixels are visible in both views
  EXPECT_LT(nonocc, 0.98);
  const auto all = MiddleburyDataset::load(root + "/middlebury-2001-2006");
  EXPECT_EQ(all.size(), 35u);
}

TEST(BioBinMatcher, BeatsBlockMatchingOnRealCones)
{
  // A real Middlebury scene (Scharstein & Szeliski 2003): the multi-scale model must be well inside
  // the error of a plain block matcher's typical range (measured: 9.7% bad 1.0 vs 22.6% for StereoBM).
  const std::string dir = sharedData() + "/stereo/middlebury-v2-masks/cones";
  ASSERT_TRUE(fs::is_directory(dir)) << dir << " not found (set BIOVISION_SHARED)";
  const StereoScene s = MiddleburyDataset::loadScene(dir);
  BioBinParameters p;
  p.max_disparity = s.max_disparity;
  BioBinMatcher matcher(p);
  const DisparityMetrics m = DisparityMetrics::compute(matcher.compute(s.left, s.right).disparity, s.ground_truth,
                                                       s.nonoccluded);
  EXPECT_LT(m.bad1, 13.0) << "bad 1.0 on cones";
  EXPECT_LT(m.avgerr, 2.5);
}

TEST(BioBinMatcher, OwnWorkerThreadsGiveTheSameMapBitForBit)
{
  // The nodelet runs BioBin on its own threads (ParallelArena, issue #21); every loop's split must not
  // change a bit of the map, against one thread and against OpenCV's own pool.
  const EstimatedPlansOnly estimated;
  const std::string dir = sharedData() + "/stereo/middlebury-v2-masks/cones";
  ASSERT_TRUE(fs::is_directory(dir)) << dir << " not found (set BIOVISION_SHARED)";
  const StereoScene s = MiddleburyDataset::loadScene(dir);
  const int opencv_threads = cv::getNumThreads();
  for (const std::string aggregation : {"semi_global", "iterative"})
  {
    BioBinParameters p;
    p.max_disparity = s.max_disparity;
    p.aggregation = aggregation;
    p.fill_occlusions = true;  // its loops too
    p.median_filter = true;
    cv::setNumThreads(1);
    const cv::Mat one = BioBinMatcher(p).compute(s.left, s.right).disparity;
    cv::setNumThreads(opencv_threads);
    const cv::Mat pool = BioBinMatcher(p).compute(s.left, s.right).disparity;
    cv::Mat own;
    biovision_common::ParallelArena arena(2);
    BioBinMatcher matcher(p);
    arena.run([&] { own = matcher.compute(s.left, s.right).disparity; });
    ASSERT_EQ(own.size(), one.size());
    // memcmp: NaN-free maps (invalid is -1), so equal bytes = equal values.
    EXPECT_EQ(0, std::memcmp(own.data, one.data, one.total() * one.elemSize())) << aggregation << ": own vs 1 thread";
    EXPECT_EQ(0, std::memcmp(pool.data, one.data, one.total() * one.elemSize())) << aggregation << ": pool vs 1";
  }
}

// The spatial filter's rows on 32-bit masks (every cost path of this CPU) equal its scalar formulation bit
// for bit: barriers (thin and a thick block with no open neighbour), frozen costs (values below Th_D), an
// early stop.
TEST(IterativeSpatialFilter, RowUpdateEqualsTheScalarFilter)
{
  const std::vector<CostSimd> simds = availableCostSimds();
  for (const cv::Size size : {cv::Size(37, 11), cv::Size(64, 9), cv::Size(5, 4), cv::Size(93, 3)})
    for (const double changing_fraction : {0.0, 0.5})
    {
      CostVolume in(size, 13);
      cv::RNG rng(11);
      for (int k = 0; k < in.disparities(); ++k)
        rng.fill(in.slice(k), cv::RNG::UNIFORM, 0, 80);  // some below Th_D = 25: frozen as they go
      cv::Mat barriers = cv::Mat::zeros(size, CV_8U);
      barriers.col(size.width / 2).setTo(255);
      barriers(cv::Rect(0, 0, std::min(4, size.width), std::min(3, size.height))).setTo(255);
      const IterativeSpatialFilter reference(1.6, 25.0, changing_fraction, 4);
      CostVolume expected(size, in.disparities());
      for (int k = 0; k < in.disparities(); ++k)
        in.slice(k).copyTo(expected.slice(k));
      reference.applyReference(expected, barriers);
      double moved = 0;
      for (int k = 0; k < in.disparities(); ++k)
        moved += cv::norm(in.slice(k), expected.slice(k), cv::NORM_L1);
      EXPECT_GT(moved, 0.0);  // the filter did something
      for (const CostSimd simd : simds)
      {
        IterativeSpatialFilter filter(1.6, 25.0, changing_fraction, 4);
        filter.setSimd(simd);
        CostVolume v(size, in.disparities());
        for (int k = 0; k < in.disparities(); ++k)
          in.slice(k).copyTo(v.slice(k));
        filter.apply(v, barriers);
        for (int k = 0; k < in.disparities(); ++k)
          EXPECT_EQ(cv::norm(v.slice(k), expected.slice(k), cv::NORM_INF), 0.0)
              << size << " fraction " << changing_fraction << " slice " << k << " " << costSimdName(simd);
      }
    }
  IterativeSpatialFilter filter(1.6, 25.0, 0.1, 2);
  CostVolume v(cv::Size(8, 8), 3);
  EXPECT_THROW(filter.apply(v, cv::Mat::zeros(4, 4, CV_8U)), std::invalid_argument);
}

int main(int argc, char** argv)
{
  testing::InitGoogleTest(&argc, argv);
  return RUN_ALL_TESTS();
}
