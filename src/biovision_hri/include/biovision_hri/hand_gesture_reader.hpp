#pragma once

#include <string>
#include <vector>

#include <opencv2/core.hpp>

#include "biovision_hri/gesture_recognizer.hpp"
#include "biovision_hri/hand_posture_classifier.hpp"

namespace biovision_hri
{
/// One hand box's gesture and the method that read it.
struct GestureReading
{
  GestureResult result;  ///< label "" = no gesture
  std::string method;    ///< HandGestureReader::kKeypoints or kPostureSvm; "" when neither method is on
};

/// The node's gesture rule (ours, beyond thesis §2.4): the keypoint templates first (they verify the
/// matches' geometry, GestureRecognizer); a box they leave without a gesture goes to the hand posture
/// SVMs (HandPostureClassifier). Best of the three on the validation parts (`gesture_eval --validation
/// true`: LinTO 9/15, Triesch 41/41 with the rejection class); `gesture_eval` evaluates this very rule as
/// "keypoints_then_posture_svm", so the figure and the node cannot drift apart.
///
/// Holds the two methods without owning them: either may be null (that method off); both must outlive
/// the reader. Not thread-safe (neither method is).
class HandGestureReader
{
public:
  static constexpr const char* kKeypoints = "keypoints";
  static constexpr const char* kPostureSvm = "posture_svm";

  HandGestureReader(GestureRecognizer* keypoints, HandPostureClassifier* postures)
    : keypoints_(keypoints), postures_(postures)
  {
  }

  /// One reading per hand, in order. `keypoint_boxes[i]` and `posture_boxes[i]` are hand i's region for
  /// each method (the node enlarges the detected box for the keypoints, whose templates were cut with
  /// context; the SVMs were trained on boxes as annotated). `gray`: CV_32FC1 in [0, 1]. Throws
  /// std::invalid_argument when the two lists differ in length or the image is empty or not CV_32FC1
  /// (whichever methods are on), and what the methods throw (std::logic_error for untrained SVMs).
  std::vector<GestureReading> read(const cv::Mat& gray, const std::vector<cv::Rect>& keypoint_boxes,
                                   const std::vector<cv::Rect>& posture_boxes) const;

private:
  GestureRecognizer* keypoints_;
  HandPostureClassifier* postures_;
};
}  // namespace biovision_hri
