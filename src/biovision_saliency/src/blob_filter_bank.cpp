#include "biovision_saliency/blob_filter_bank.hpp"

#include <opencv2/imgproc.hpp>

namespace biovision_saliency
{
BlobFilterBank::BlobFilterBank(std::vector<double> sigmas) : sigmas_(std::move(sigmas))
{
}

void BlobFilterBank::filter(const cv::Mat& map, cv::Mat& on, cv::Mat* off) const
{
  CV_Assert(map.type() == CV_32FC1);
  on = cv::Mat::zeros(map.size(), CV_32F);
  if (off)
    *off = cv::Mat::zeros(map.size(), CV_32F);
  cv::Mat centre, surround, dog;
  for (double s : sigmas_)
  {
    cv::GaussianBlur(map, centre, cv::Size(), s, s, cv::BORDER_REPLICATE);
    cv::GaussianBlur(map, surround, cv::Size(), 2 * s, 2 * s, cv::BORDER_REPLICATE);
    cv::subtract(centre, surround, dog);
    on += cv::max(dog, 0.0);
    if (off)
      *off -= cv::min(dog, 0.0);
  }
}

void BlobFilterBank::positiveAndNegative(const cv::Mat& map, cv::Mat& on, cv::Mat& off) const
{
  filter(map, on, &off);
}

cv::Mat BlobFilterBank::positive(const cv::Mat& map) const
{
  cv::Mat on;
  filter(map, on, nullptr);
  return on;
}
}  // namespace biovision_saliency
