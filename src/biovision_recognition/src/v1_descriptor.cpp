#include "biovision_recognition/v1_descriptor.hpp"

#include <stdexcept>

namespace biovision_recognition
{
V1Descriptor::V1Descriptor(const DescriptorModel& model) : model_(model), features_(model.layout)
{
  model_.validate();
  projection_ = PackedProjection(model_.projection.data(), static_cast<size_t>(model_.projection.rows()),
                                 static_cast<size_t>(model_.projection.cols()));
}

V1FeaturePyramid::Parameters V1Descriptor::pyramidParameters() const
{
  V1FeaturePyramid::Parameters p;
  p.orientations = model_.layout.orientations;
  p.pooling_diameter = model_.layout.pooling_diameter;
  p.pooling_phases = model_.layout.phases;
  return p;
}

cv::Mat V1Descriptor::project(const cv::Mat& features, ProjectionPath path) const
{
  if (features.type() != CV_32F || features.cols != model_.projection.cols())
    throw std::invalid_argument("V1Descriptor: features must be CV_32F with " +
                                std::to_string(model_.projection.cols()) + " columns");
  cv::Mat y(features.rows, model_.bits(), CV_32F);
  if (features.rows == 0)
    return y;
  const cv::Mat x = features.isContinuous() ? features : features.clone();
  projection_.project(x.ptr<float>(), static_cast<size_t>(x.rows), y.ptr<float>(), path);
  return y;
}

BinaryCodeSet V1Descriptor::binarize(const cv::Mat& features) const
{
  const cv::Mat y = project(features);
  BinaryCodeSet codes(model_.bits(), static_cast<size_t>(y.rows));
  for (int i = 0; i < y.rows; ++i)
  {
    const float* row = y.ptr<float>(i);
    uint64_t* code = codes.code(i);
    for (int b = 0; b < y.cols; ++b)
      if (row[b] > model_.thresholds(b))
        code[b >> 6] |= uint64_t(1) << (b & 63);
  }
  return codes;
}

BinaryCodeSet V1Descriptor::compute(const V1FeaturePyramid& pyramid,
                                    const std::vector<biovision_v1::Keypoint>& keypoints) const
{
  return binarize(features_.extract(pyramid, keypoints));
}
}  // namespace biovision_recognition
