#pragma once

#include <string>
#include <vector>

#include <opencv2/core.hpp>
#include <opencv2/features2d.hpp>
#include <opencv2/saliency.hpp>

namespace biovision_bringup
{
/// The peer of our saliency + recognition in loop_bench: what a ROS user would assemble from OpenCV as
/// Debian ships it — spectral-residual saliency (Hou & Zhang 2007, opencv_contrib's saliency module), its
/// binary map's largest blobs as regions, ORB keypoints in each region matched with BFMatcher(NORM_HAMMING)
/// and Lowe's ratio test against ORB descriptors of taught views, verified by a RANSAC similarity
/// (cv::estimateAffinePartial2D) as our recogniser verifies its matches. Not thread-safe (one per nodelet).
class PeerSaliencyOrb
{
public:
  struct Parameters
  {
    int max_regions = 3;         ///< salient regions examined per image (recognition.yaml's max_regions)
    int region_margin = 15;      ///< [px] context around a region (recognition.yaml's region_margin)
    int orb_features = 400;      ///< ORB keypoints per region (recognition.yaml's max_keypoints)
    double ratio = 0.8;          ///< Lowe's ratio test
    int min_matches = 5;         ///< verified matches for a detection (recognition.yaml's min_matches)
    double inlier_distance = 4;  ///< [px] RANSAC reprojection threshold (recognition.yaml's inlier_distance)
  };
  struct Detection
  {
    std::string label;
    cv::Rect box;  ///< [px] the verified matches' bounding box in the image
    int matches = 0;
    int region_rank = 0;
  };

  /// `views`: labelled grey or colour images of the taught objects. Throws std::invalid_argument on an
  /// empty image or a parameter out of range.
  PeerSaliencyOrb(const std::vector<std::pair<std::string, cv::Mat>>& views, const Parameters& p);

  /// Loads the views of a folder laid out as teach_from_bag --views writes it: <dir>/<label>/*.{ppm,png}.
  /// Throws std::runtime_error when the folder has none.
  static std::vector<std::pair<std::string, cv::Mat>> loadViews(const std::string& dir);

  /// Salient regions of an 8-bit grey image, largest first [px].
  std::vector<cv::Rect> regions(const cv::Mat& gray);
  /// Regions, then the objects recognised in them. `gray`: CV_8UC1.
  std::vector<Detection> process(const cv::Mat& gray, std::vector<cv::Rect>* regions_out = nullptr);

private:
  struct View
  {
    std::string label;
    std::vector<cv::KeyPoint> keypoints;
    cv::Mat descriptors;
  };
  Parameters p_;
  std::vector<View> views_;
  cv::Ptr<cv::ORB> orb_;
  cv::BFMatcher matcher_{cv::NORM_HAMMING};
  cv::Ptr<cv::saliency::StaticSaliencySpectralResidual> saliency_;
};
}  // namespace biovision_bringup
