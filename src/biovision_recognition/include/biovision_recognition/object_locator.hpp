#pragma once

#include <vector>

#include <opencv2/core.hpp>

namespace biovision_recognition
{
/// Where a recognised object is in 3-D, from the stereo disparity (thesis 4.6: the recognised object's
/// position for the memories). The depth is the median disparity at the object's verified matches — the
/// keypoints that agreed on the view's transform lie on the object itself — and falls back to the median
/// over the whole box only when too few of them have a disparity. The box median alone took the depth of
/// whatever covered most of the box: in the simulated mission the target box, seen through a doorway, was
/// remembered 2.0 m short of where it is, at the door frame's depth on the same ray. ROS-free.
class ObjectLocator
{
public:
  /// The rectified left camera at the disparity's resolution.
  struct Camera
  {
    double focal_length = 0;  ///< f of the disparity [px]: z = f * baseline / d
    double baseline = 0;      ///< [m], > 0
    double fx = 0, fy = 0;    ///< projection's focal lengths [px]
    double cx = 0, cy = 0;    ///< principal point [px]
    float min_disparity = 0;  ///< disparities at or below this are invalid [px]
  };
  /// Which disparities gave the depth.
  enum class Source
  {
    None,      ///< too few valid disparities: no position
    Matches,   ///< at the verified matches
    WholeBox,  ///< the box median (too few matches had a disparity)
  };

  /// Verified matches with a disparity needed before their median is used.
  static constexpr int kMinMatchDisparities = 3;
  /// Valid disparities the box fallback needs.
  static constexpr int kMinBoxDisparities = 10;

  /// disparity: CV_32FC1 [px], any resolution (image coordinates are scaled onto it); `image_size` is the
  /// size of the image `box` and `matches` are in [px]. Writes the box centre's ray at the chosen depth,
  /// in the camera's optical frame [m] (x right, y down, z forward), and returns where the depth came from
  /// (None: nothing written). Throws std::invalid_argument for a non-CV_32FC1 disparity, an empty image
  /// size or a camera with non-positive focal lengths or baseline.
  static Source locate(const cv::Mat& disparity, const Camera& camera, const cv::Size& image_size, const cv::Rect& box,
                       const std::vector<cv::Point2f>& matches, cv::Point3d& position);
};
}  // namespace biovision_recognition
