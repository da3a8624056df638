#pragma once

#include <memory>
#include <vector>

#include <opencv2/core.hpp>

#include "biovision_saliency/blob_filter_bank.hpp"
#include "biovision_saliency/head_direction.hpp"
#include "biovision_saliency/inhibition_of_return.hpp"
#include "biovision_saliency/saliency_parameters.hpp"
#include "biovision_saliency/salient_region.hpp"

namespace cv
{
class DenseOpticalFlow;
}

namespace biovision_saliency
{
/// What SaliencyPipeline computes for one frame.
struct SaliencyResult
{
  cv::Mat colour, disparity, motion;   ///< normalised channels at working resolution, CV_32F [0, 1] (empty if absent)
  cv::Mat map;                         ///< fused saliency, CV_32F [0, 1], working resolution
  cv::Mat thresholded;                 ///< CV_8U 255 where map >= threshold
  std::vector<SalientRegion> regions;  ///< in Focus-of-Attention order (highest priority first)
  cv::Point2f global_flow;             ///< ego-motion flow removed from the motion channel [working px/frame]
  double scale = 1.0;                  ///< full-resolution px per working px
};

/// Colour + disparity + motion saliency with Focus-of-Attention and Inhibition-of-Return (thesis
/// §2.2.3, §4.5). Colour always works; disparity and motion are used when given/available.
class SaliencyPipeline
{
public:
  explicit SaliencyPipeline(const SaliencyParameters& parameters);
  ~SaliencyPipeline();

  /// bgr: 8-bit BGR (or grey) full-resolution left image. disparity: CV_32F at any resolution with
  /// the image's aspect (invalid: < 0 or NaN), values in full-resolution px, or empty. head: pose and
  /// focal length (focal <= 0: from horizontal_fov). t: frame time [s], increasing.
  /// Throws std::invalid_argument on unusable input (empty, wrong depth, disparity of another aspect).
  SaliencyResult process(const cv::Mat& bgr, const cv::Mat& disparity, const HeadDirection& head, double t);

  /// Forgets the previous frame (motion restarts) and the IoR memory.
  void reset();
  InhibitionOfReturn& inhibitionOfReturn() { return ior_; }
  const SaliencyParameters& parameters() const { return parameters_; }

  // The channels, exposed for tests and evaluation.
  cv::Mat colourChannel(const cv::Mat& bgr_working) const;
  cv::Mat disparityChannel(const cv::Mat& disparity_working, double max_disparity_working) const;
  cv::Mat motionChannel(const cv::Mat& gray_working, const cv::Point2f& predicted_flow, cv::Point2f* global_flow);
  /// The spatial prior of `parameters().prior` at working size `working`, CV_32F in (0, 1] (all ones for
  /// PriorMode::none). scale: full-resolution px per working px; head: focal > 0 and principal point at
  /// full resolution (the horizon row is v = cy - f tan(tilt)).
  cv::Mat priorMap(cv::Size working, double scale, const HeadDirection& head) const;

private:
  std::vector<SalientRegion> extractRegions(const cv::Mat& map, double scale, cv::Size full, const HeadDirection& head,
                                            double t);

  SaliencyParameters parameters_;
  BlobFilterBank blobs_;
  InhibitionOfReturn ior_;
  cv::Ptr<cv::DenseOpticalFlow> flow_;
  cv::Mat previous_gray_;
  HeadDirection previous_head_;
  double last_attend_time_ = -1e300;
};
}  // namespace biovision_saliency
