#include "biovision_stereo/occlusion_filling.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <utility>
#include <vector>

#include <opencv2/core/utility.hpp>

#include "biovision_common/parallel_arena.hpp"

namespace biovision_stereo
{
namespace
{
/// Compare-exchange pairs (a < b) of Batcher's odd-even merge sort of 16 values (63 pairs).
const std::vector<std::pair<int, int>>& sortingNetwork16()
{
  static const std::vector<std::pair<int, int>> kPairs = [] {
    constexpr int n = 16;
    std::vector<std::pair<int, int>> pairs;
    for (int p = 1; p < n; p <<= 1)
      for (int k = p; k >= 1; k >>= 1)
        for (int j = k % p; j + k < n; j += 2 * k)
          for (int i = 0; i < k && i + j + k < n; ++i)
            if ((i + j) / (2 * p) == (i + j + k) / (2 * p))
              pairs.emplace_back(i + j, i + j + k);
    return pairs;
  }();
  return kPairs;
}
}  // namespace

const std::array<cv::Point, 16>& OcclusionFilling::directions()
{
  static const std::array<cv::Point, 16> kDirections{
      cv::Point(1, 0),  cv::Point(-1, 0),  cv::Point(0, 1),  cv::Point(0, -1), cv::Point(1, 1),  cv::Point(1, -1),
      cv::Point(-1, 1), cv::Point(-1, -1), cv::Point(2, 1),  cv::Point(2, -1), cv::Point(-2, 1), cv::Point(-2, -1),
      cv::Point(1, 2),  cv::Point(1, -2),  cv::Point(-1, 2), cv::Point(-1, -2)};
  return kDirections;
}

void OcclusionFilling::fill(cv::Mat& disparity)
{
  if (disparity.empty())
    return;
  if (disparity.type() != CV_32FC1)
    throw std::invalid_argument("OcclusionFilling: disparity must be CV_32FC1");
  const int w = disparity.cols, h = disparity.rows;
  constexpr int kDirections = 16;
  // Invalid pixels, numbered in row-major order (index: per pixel its number, -1 where valid); found[r][i]:
  // the nearest valid value from invalid pixel i along direction r (-1: none). Both passes below visit the
  // invalid pixels only, so the time and the memory beyond the index grow with them.
  std::vector<int> index(size_t(w) * h, -1);
  std::vector<cv::Point> invalid;
  for (int y = 0; y < h; ++y)
  {
    const float* d = disparity.ptr<float>(y);
    for (int x = 0; x < w; ++x)
      if (!(d[x] >= 0))  // NaN counts as invalid
      {
        index[size_t(y) * w + x] = static_cast<int>(invalid.size());
        invalid.emplace_back(x, y);
      }
  }
  const int n_invalid = static_cast<int>(invalid.size());
  if (n_invalid == 0)
    return;
  std::vector<std::vector<float>> found(kDirections, std::vector<float>(n_invalid));
  // Directions in parallel: each pass reads the map and writes its own row of found.
  biovision_common::parallelFor(cv::Range(0, kDirections), [&](const cv::Range& rs) {
    for (int r = rs.start; r < rs.end; ++r)
    {
      const cv::Point step = directions()[r];
      // Each pixel after the one a step along r from it: in reverse row-major order where that one lies in
      // a later row or later in the same row, else in row-major order.
      const bool reverse = step.y > 0 || (step.y == 0 && step.x > 0);
      std::vector<float>& out = found[r];
      for (int j = 0; j < n_invalid; ++j)
      {
        const int i = reverse ? n_invalid - 1 - j : j;
        const int qx = invalid[i].x + step.x, qy = invalid[i].y + step.y;
        float v = -1.f;
        if (qx >= 0 && qx < w && qy >= 0 && qy < h)
        {
          const int q = index[size_t(qy) * w + qx];
          v = q < 0 ? disparity.at<float>(qy, qx) : out[q];
        }
        out[i] = v;
      }
    }
  });
  // The lower median of each pixel's found values: 8 pixels at a time through a sorting network (Batcher's
  // odd-even merge sort of 16 slots, empty slots +inf so that the n found values come first), each
  // compare-exchange one min and one max across the 8 lanes, so that it vectorises; then slot (n - 1) / 2.
  // std::nth_element per pixel had made the fill 2.8 ms of a 450 x 375 map.
  constexpr int kLanes = 8;
  const int blocks = (n_invalid + kLanes - 1) / kLanes;
  biovision_common::parallelFor(cv::Range(0, blocks), [&](const cv::Range& bs) {
    for (int block = bs.start; block < bs.end; ++block)
    {
      const int i0 = block * kLanes, lanes = std::min(kLanes, n_invalid - i0);
      float v[kDirections][kLanes];
      int n[kLanes] = {};
      for (int r = 0; r < kDirections; ++r)
        for (int l = 0; l < kLanes; ++l)
        {
          const float f = l < lanes ? found[r][i0 + l] : -1.f;
          v[r][l] = f >= 0 ? f : HUGE_VALF;
          n[l] += f >= 0;
        }
      for (const auto& [a, b] : sortingNetwork16())
        for (int l = 0; l < kLanes; ++l)
        {
          const float lo = std::min(v[a][l], v[b][l]), hi = std::max(v[a][l], v[b][l]);
          v[a][l] = lo;
          v[b][l] = hi;
        }
      for (int l = 0; l < lanes; ++l)
        if (n[l] > 0)
          disparity.at<float>(invalid[i0 + l]) = v[(n[l] - 1) / 2][l];
    }
  });
}
}  // namespace biovision_stereo
