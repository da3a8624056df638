#pragma once

#include <vector>

#include <opencv2/core.hpp>

#include "biovision_recognition/binary_code_set.hpp"
#include "biovision_recognition/descriptor_model.hpp"
#include "biovision_recognition/packed_projection.hpp"
#include "biovision_recognition/pooled_cell_features.hpp"
#include "biovision_recognition/v1_feature_pyramid.hpp"

namespace biovision_recognition
{
/// The learned binary V1 keypoint descriptor (thesis ch. 3): pooled cell features x, projected by the
/// model's P and thresholded at t. Upright: like the source it does not rotate patches, so it tolerates
/// small in-plane rotations (tested at 5 degrees), not large ones.
class V1Descriptor
{
public:
  explicit V1Descriptor(const DescriptorModel& model);

  /// One code per keypoint, in order.
  BinaryCodeSet compute(const V1FeaturePyramid& pyramid, const std::vector<biovision_v1::Keypoint>& keypoints) const;
  /// Codes of given feature rows (CV_32F, featureCount() columns): for tools that already have x.
  BinaryCodeSet binarize(const cv::Mat& features) const;
  /// The real-valued projections P x (rows x bits), before thresholding, on `path` (default: the CPU's
  /// fastest; std::invalid_argument when this CPU lacks it or the features are not CV_32F featureCount()).
  cv::Mat project(const cv::Mat& features, ProjectionPath path = bestProjectionPath()) const;

  const DescriptorModel& model() const { return model_; }
  const PooledCellFeatures& features() const { return features_; }
  /// A pyramid whose parameters fit this descriptor's layout.
  V1FeaturePyramid::Parameters pyramidParameters() const;

private:
  DescriptorModel model_;
  PooledCellFeatures features_;
  PackedProjection projection_;  ///< model_.projection, packed for the SIMD paths
};
}  // namespace biovision_recognition
