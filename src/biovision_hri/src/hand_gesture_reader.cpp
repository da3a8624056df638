#include "biovision_hri/hand_gesture_reader.hpp"

#include <stdexcept>

namespace biovision_hri
{
std::vector<GestureReading> HandGestureReader::read(const cv::Mat& gray, const std::vector<cv::Rect>& keypoint_boxes,
                                                    const std::vector<cv::Rect>& posture_boxes) const
{
  if (keypoint_boxes.size() != posture_boxes.size())
    throw std::invalid_argument("HandGestureReader::read: " + std::to_string(keypoint_boxes.size()) +
                                " keypoint boxes but " + std::to_string(posture_boxes.size()) + " posture boxes");
  // Checked here too: with only the keypoint templates on, an empty image would read as "no gesture".
  if (gray.empty() || gray.type() != CV_32FC1)
    throw std::invalid_argument("HandGestureReader::read: expected a non-empty CV_32FC1 image");
  std::vector<GestureReading> readings(keypoint_boxes.size());
  if (readings.empty())
    return readings;
  if (keypoints_)
  {
    const std::vector<GestureResult> results = keypoints_->recognize(gray, keypoint_boxes);
    for (size_t i = 0; i < readings.size(); ++i)
      readings[i] = {results[i], kKeypoints};
  }
  if (postures_)
    for (size_t i = 0; i < readings.size(); ++i)
      if (readings[i].result.label.empty())
        readings[i] = {postures_->classify(gray, {posture_boxes[i]}).front(), kPostureSvm};
  return readings;
}
}  // namespace biovision_hri
