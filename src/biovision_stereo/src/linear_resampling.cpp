#include "biovision_stereo/linear_resampling.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

namespace biovision_stereo
{
LinearResampling::LinearResampling(cv::Size input, cv::Size output) : input_(input), output_(output)
{
  if (input.width <= 0 || input.height <= 0 || output.width <= 0 || output.height <= 0)
    throw std::invalid_argument("LinearResampling: empty size " + std::to_string(input.width) + "x" +
                                std::to_string(input.height) + " -> " + std::to_string(output.width) + "x" +
                                std::to_string(output.height));
  // The scale as cv::resize forms it: the inverse of out / in, in double.
  const double scale_x = 1.0 / (double(output.width) / input.width);
  const double scale_y = 1.0 / (double(output.height) / input.height);
  x_offset_.resize(output.width);
  alpha_.resize(2 * size_t(output.width));
  x_max_ = output.width;
  for (int dx = 0; dx < output.width; ++dx)
  {
    float fx = static_cast<float>((dx + 0.5) * scale_x - 0.5);
    int sx = static_cast<int>(std::floor(fx));
    fx -= static_cast<float>(sx);
    if (sx < 0)
      fx = 0.f, sx = 0;
    if (sx + 1 >= input.width)
    {
      x_max_ = std::min(x_max_, dx);
      if (sx >= input.width - 1)
        fx = 0.f, sx = input.width - 1;
    }
    x_offset_[dx] = sx;
    alpha_[2 * dx] = 1.f - fx;
    alpha_[2 * dx + 1] = fx;
  }
  row0_.resize(output.height);
  row1_.resize(output.height);
  beta_.resize(2 * size_t(output.height));
  for (int dy = 0; dy < output.height; ++dy)
  {
    float fy = static_cast<float>((dy + 0.5) * scale_y - 0.5);
    const int sy = static_cast<int>(std::floor(fy));
    fy -= static_cast<float>(sy);
    row0_[dy] = std::clamp(sy, 0, input.height - 1);  // rows are clipped, the weights kept (as OpenCV does)
    row1_[dy] = std::clamp(sy + 1, 0, input.height - 1);
    beta_[2 * dy] = 1.f - fy;
    beta_[2 * dy + 1] = fy;
  }
}
}  // namespace biovision_stereo
