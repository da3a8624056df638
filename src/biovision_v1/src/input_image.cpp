#include "biovision_v1/input_image.hpp"

#include <stdexcept>
#include <string>

#include <opencv2/imgproc.hpp>

namespace biovision_v1
{
InputImage::InputImage(const cv::Mat& image)
{
  if (image.empty())
    throw std::invalid_argument("V1 input: empty image");
  if (image.cols < kMinSide || image.rows < kMinSide)
    throw std::invalid_argument("V1 input: image " + std::to_string(image.cols) + "x" + std::to_string(image.rows) +
                                " is smaller than the minimum " + std::to_string(kMinSide) + "x" +
                                std::to_string(kMinSide));
  double scale = 1.0;
  switch (image.depth())
  {
    case CV_8U:
      scale = 1.0 / 255.0;
      break;
    case CV_16U:
      scale = 1.0 / 65535.0;
      break;
    case CV_32F:
    case CV_64F:
      break;
    default:
      throw std::invalid_argument("V1 input: unsupported pixel depth (use 8U, 16U, 32F or 64F)");
  }
  cv::Mat gray;
  switch (image.channels())
  {
    case 1:
      gray = image;
      break;
    case 3:
      cv::cvtColor(image, gray, cv::COLOR_BGR2GRAY);
      break;
    case 4:
      cv::cvtColor(image, gray, cv::COLOR_BGRA2GRAY);
      break;
    default:
      throw std::invalid_argument("V1 input: unsupported channel count " + std::to_string(image.channels()));
  }
  gray.convertTo(gray_, CV_32F, scale);
  if (image.depth() == CV_32F || image.depth() == CV_64F)
  {
    // cvtColor of a NaN pixel gives NaN, so one pass over the grey image finds every bad pixel.
    for (int y = 0; y < gray_.rows; ++y)
    {
      float* row = gray_.ptr<float>(y);
      for (int x = 0; x < gray_.cols; ++x)
        if (!std::isfinite(row[x]))
        {
          row[x] = 0.0f;
          ++nonfinite_pixels_;
        }
    }
  }
  if (gray_.data == image.data)
    gray_ = gray_.clone();  // never alias the caller's buffer
}
}  // namespace biovision_v1
