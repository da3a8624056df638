#include "biovision_saliency/blob_filter_bank.hpp"

#include <opencv2/imgproc.hpp>

namespace biovision_saliency
{
BlobFilterBank::BlobFilterBank(std::vector<double> sigmas) : sigmas_(std::move(sigmas))
{
}

void BlobFilterBank::positiveAndNegative(const cv::Mat& map, cv::Mat& on, cv::Mat& off) const
{
  CV_Assert(map.type() == CV_32FC1);
  on = cv::Mat::zeros(map.size(), CV_32F);
  off = cv::Mat::zeros(map.size(), CV_32F);
  cv::Mat centre, surround, dog;
  // Each scale's surround (2 sigma) is the next scale's centre when sigmas double: blur once per sigma.
  for (double s : sigmas_)
  {
    cv::GaussianBlur(map, centre, cv::Size(), s, s, cv::BORDER_REPLICATE);
    cv::GaussianBlur(map, surround, cv::Size(), 2 * s, 2 * s, cv::BORDER_REPLICATE);
    cv::subtract(centre, surround, dog);
    on += cv::max(dog, 0.0);
    off -= cv::min(dog, 0.0);
  }
}

cv::Mat BlobFilterBank::positive(const cv::Mat& map) const
{
  cv::Mat on, off;
  positiveAndNegative(map, on, off);
  return on;
}
}  // namespace biovision_saliency
