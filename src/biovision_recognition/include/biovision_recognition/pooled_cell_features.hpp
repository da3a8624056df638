#pragma once

#include <vector>

#include <opencv2/core.hpp>

#include "biovision_recognition/descriptor_layout.hpp"
#include "biovision_recognition/v1_feature_pyramid.hpp"
#include "biovision_v1/keypoint.hpp"

namespace biovision_recognition
{
/// The descriptor's input: around a keypoint, the max-pooled even and odd simple cells of every scale
/// of the layout, each scale normalised to a unit vector (thesis 3.3.2), so a brightness offset (the
/// cells are DC-free) and a contrast gain leave it unchanged. The pooling grid is laid on the keypoint's
/// affine shape when the layout asks for it (DescriptorLayout::shape).
class PooledCellFeatures
{
public:
  explicit PooledCellFeatures(const DescriptorLayout& layout);

  /// x of one keypoint into `out` (layout.featureCount() floats). Scales whose level the pyramid does
  /// not have (keypoint too coarse for the image) are zero.
  void extract(const V1FeaturePyramid& pyramid, const biovision_v1::Keypoint& keypoint, float* out) const;
  /// x of every keypoint, one row each (CV_32F, keypoints x featureCount()).
  cv::Mat extract(const V1FeaturePyramid& pyramid, const std::vector<biovision_v1::Keypoint>& keypoints) const;

  const DescriptorLayout& layout() const { return layout_; }

private:
  /// The pooled samples of pyramid levels base + j (grid scaled by size_ratio, offsets mapped by shape)
  /// into out.
  void sampleLevels(const V1FeaturePyramid& pyramid, const cv::Point2f& position, int base, float size_ratio,
                    const cv::Matx22f& shape, float* out) const;

  DescriptorLayout layout_;
  AffineShapeAdaptation shape_adaptation_;
};
}  // namespace biovision_recognition
