#include "biovision_recognition/object_locator.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace biovision_recognition
{
namespace
{
bool valid(float d, float min_disparity)
{
  return std::isfinite(d) && d > min_disparity && d > 0.f;
}

float median(std::vector<float>& values)
{
  std::nth_element(values.begin(), values.begin() + values.size() / 2, values.end());
  return values[values.size() / 2];
}
}  // namespace

ObjectLocator::Source ObjectLocator::locate(const cv::Mat& disparity, const Camera& camera, const cv::Size& image_size,
                                            const cv::Rect& box, const std::vector<cv::Point2f>& matches,
                                            cv::Point3d& position)
{
  if (disparity.type() != CV_32FC1)
    throw std::invalid_argument("ObjectLocator::locate: the disparity must be CV_32FC1");
  if (image_size.width <= 0 || image_size.height <= 0)
    throw std::invalid_argument("ObjectLocator::locate: empty image size");
  if (!(camera.focal_length > 0) || !(camera.baseline > 0) || !(camera.fx > 0) || !(camera.fy > 0))
    throw std::invalid_argument("ObjectLocator::locate: focal lengths and baseline must be > 0");
  if (disparity.empty())
    return Source::None;
  const double sx = double(disparity.cols) / image_size.width, sy = double(disparity.rows) / image_size.height;
  const cv::Rect bounds(0, 0, disparity.cols, disparity.rows);

  // Each match: the median of its 3x3 neighbourhood's valid disparities (a keypoint sits on an edge, where
  // one pixel may have none).
  std::vector<float> at_matches, around;
  for (const cv::Point2f& m : matches)
  {
    const int u = cvFloor(m.x * sx), v = cvFloor(m.y * sy);
    around.clear();
    for (int y = v - 1; y <= v + 1; ++y)
      for (int x = u - 1; x <= u + 1; ++x)
        if (bounds.contains({x, y}) && valid(disparity.at<float>(y, x), camera.min_disparity))
          around.push_back(disparity.at<float>(y, x));
    if (!around.empty())
      at_matches.push_back(median(around));
  }
  Source source = Source::None;
  float d = 0.f;
  if (static_cast<int>(at_matches.size()) >= kMinMatchDisparities)
  {
    d = median(at_matches);
    source = Source::Matches;
  }
  else
  {
    const cv::Rect r = cv::Rect(cvRound(box.x * sx), cvRound(box.y * sy), cvRound(box.width * sx),
                                cvRound(box.height * sy)) &
                       bounds;
    std::vector<float> values;
    for (int y = r.y; y < r.y + r.height; ++y)
      for (int x = r.x; x < r.x + r.width; ++x)
        if (valid(disparity.at<float>(y, x), camera.min_disparity))
          values.push_back(disparity.at<float>(y, x));
    if (static_cast<int>(values.size()) < kMinBoxDisparities)
      return Source::None;
    d = median(values);
    source = Source::WholeBox;
  }
  const double z = camera.focal_length * camera.baseline / d;
  const double u = (box.x + box.width / 2.0) * sx, v = (box.y + box.height / 2.0) * sy;
  const cv::Point3d p((u - camera.cx) * z / camera.fx, (v - camera.cy) * z / camera.fy, z);
  if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.z))
    return Source::None;
  position = p;
  return source;
}
}  // namespace biovision_recognition
