#pragma once

#include <string>

#include <opencv2/core.hpp>

namespace biovision_common
{
/// Reader of Middlebury .flo optical-flow files ("PIEH", width, height, then (u, v) float pairs, little
/// endian). Unknown flow (|u| or |v| > 1e9) comes back as NaN. Throws std::runtime_error naming the file.
class MiddleburyFlow
{
public:
  static cv::Mat read(const std::string& path);  ///< CV_32FC2
};
}  // namespace biovision_common
