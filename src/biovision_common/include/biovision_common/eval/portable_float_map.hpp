#pragma once

#include <string>

#include <opencv2/core.hpp>

namespace biovision_common
{
/// Reader and writer of PFM images (Middlebury ground truth).
/// The header's scale only gives the byte order (negative: little endian); values are used exactly as
/// stored — OpenCV 4.6's imread divides them by |scale|, which is wrong for files whose scale is not
/// +-1. Rows are stored bottom to top; read() returns them top to bottom. Infinite values (unknown
/// disparity in Middlebury v3) are kept. "Pf" is one channel, "PF" three (read returns CV_32FC3).
class PortableFloatMap
{
public:
  /// Throws std::runtime_error naming the file and the problem (missing, bad header, truncated).
  static cv::Mat read(const std::string& path);
  /// Writes CV_32FC1 or CV_32FC3 atomically (temporary file + rename) with the given scale; the sign
  /// of `scale` picks the byte order (negative = little endian).
  static void write(const std::string& path, const cv::Mat& image, float scale = -1.f);
};
}  // namespace biovision_common
