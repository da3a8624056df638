#include "biovision_common/eval/middlebury_flow.hpp"

#include <cmath>
#include <cstring>
#include <fstream>
#include <limits>
#include <stdexcept>

namespace biovision_common
{
cv::Mat MiddleburyFlow::read(const std::string& path)
{
  std::ifstream in(path, std::ios::binary);
  if (!in)
    throw std::runtime_error("flow " + path + ": cannot open");
  char tag[4];
  std::int32_t w = 0, h = 0;
  in.read(tag, 4);
  in.read(reinterpret_cast<char*>(&w), 4);
  in.read(reinterpret_cast<char*>(&h), 4);
  if (!in || std::memcmp(tag, "PIEH", 4) != 0)
    throw std::runtime_error("flow " + path + ": not a .flo file");
  if (w <= 0 || h <= 0 || w > 100000 || h > 100000)
    throw std::runtime_error("flow " + path + ": bad size");
  cv::Mat flow(h, w, CV_32FC2);
  for (int y = 0; y < h; ++y)
  {
    in.read(flow.ptr<char>(y), static_cast<std::streamsize>(size_t(w) * 2 * sizeof(float)));
    if (!in)
      throw std::runtime_error("flow " + path + ": truncated at row " + std::to_string(y));
  }
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x)
    {
      cv::Vec2f& v = flow.at<cv::Vec2f>(y, x);
      if (!(std::abs(v[0]) <= 1e9f && std::abs(v[1]) <= 1e9f))
        v = cv::Vec2f(std::numeric_limits<float>::quiet_NaN(), std::numeric_limits<float>::quiet_NaN());
    }
  return flow;
}
}  // namespace biovision_common
