#include "biovision_stereo/occlusion_filling.hpp"

#include <algorithm>
#include <stdexcept>
#include <vector>

namespace biovision_stereo
{
void OcclusionFilling::fill(cv::Mat& disparity)
{
  if (disparity.empty())
    return;
  if (disparity.type() != CV_32FC1)
    throw std::invalid_argument("OcclusionFilling: disparity must be CV_32FC1");
  const int w = disparity.cols;
  std::vector<float> from_left(w);
  for (int y = 0; y < disparity.rows; ++y)
  {
    float* d = disparity.ptr<float>(y);
    // Nearest valid value to the left of each pixel (-1: none), then one sweep from the right.
    float last = -1.f;
    for (int x = 0; x < w; ++x)
    {
      if (d[x] >= 0)
        last = d[x];
      from_left[x] = last;
    }
    float right = -1.f;
    for (int x = w - 1; x >= 0; --x)
    {
      if (d[x] >= 0)
      {
        right = d[x];
        continue;
      }
      const float l = from_left[x];
      if (l >= 0 && right >= 0)
        d[x] = std::min(l, right);
      else if (l >= 0 || right >= 0)
        d[x] = std::max(l, right);
    }
  }
}
}  // namespace biovision_stereo
