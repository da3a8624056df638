#include "biovision_recognition/pooled_cell_features.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include <opencv2/core/utility.hpp>

namespace biovision_recognition
{
namespace
{
/// Bilinear sample positions along one axis, clamped to the map: p is read from [i0, i1] with weight f.
struct AxisSample
{
  int i0, i1;
  float f;
};

AxisSample axisSample(float v, int size)
{
  v = std::min(std::max(v, 0.f), static_cast<float>(size - 1));
  const int i0 = std::min(static_cast<int>(v), size - 2 < 0 ? 0 : size - 2);
  return {i0, std::min(i0 + 1, size - 1), v - i0};
}

/// out[c] = bilinear blend of the four neighbours' channel c, for every channel of a pooling field.
__attribute__((target_clones("arch=skylake-avx512", "arch=haswell", "default"))) void blendChannels(
    const float* p00, const float* p01, const float* p10, const float* p11, float w00, float w01, float w10, float w11,
    int channels, float* out)
{
  for (int c = 0; c < channels; ++c)
    out[c] = w00 * p00[c] + w01 * p01[c] + w10 * p10[c] + w11 * p11[c];
}
}  // namespace

PooledCellFeatures::PooledCellFeatures(const DescriptorLayout& layout)
  : layout_(layout), shape_adaptation_(layout.shape)
{
  layout_.validate();
}

void PooledCellFeatures::sampleLevels(const V1FeaturePyramid& pyramid, const cv::Point2f& position, int base,
                                      float size_ratio, const cv::Matx22f& shape, float* out) const
{
  const float centre_offset = static_cast<float>(pyramid.poolingCentreOffset());
  const int channels = layout_.phases * layout_.orientations;  // the layout's (the pyramid may hold more)
  for (int j : layout_.scales)
  {
    const int n = layout_.gridSide(j);
    const int k = base + j;
    if (k >= pyramid.levels())
    {
      out += channels * n * n;  // stays zero
      continue;
    }
    const cv::Point2f c = pyramid.toLevel(position, k);
    const float step = layout_.pooling_step * size_ratio;
    const float first = -0.5f * (n - 1) * step;
    // The grid is separable: its sample columns and rows (and their weights) are the same for every
    // channel, so they are worked out once per scale.
    const cv::Mat& map = pyramid.pooled(k);
    const cv::Size size = map.size();
    const int stride = map.channels();
    auto blendAt = [&](const AxisSample& x, const AxisSample& y, float* field) {
      const float* r0 = map.ptr<float>(y.i0);
      const float* r1 = map.ptr<float>(y.i1);
      blendChannels(r0 + x.i0 * stride, r0 + x.i1 * stride, r1 + x.i0 * stride, r1 + x.i1 * stride,
                    (1 - y.f) * (1 - x.f), (1 - y.f) * x.f, y.f * (1 - x.f), y.f * x.f, channels, field);
    };
    if (shape != cv::Matx22f::eye())
    {
      // An affine grid: every field has its own sample position.
      for (int gy = 0; gy < n; ++gy)
        for (int gx = 0; gx < n; ++gx, out += channels)
        {
          const float ox = first + gx * step, oy = first + gy * step;
          blendAt(axisSample(c.x + shape(0, 0) * ox + shape(0, 1) * oy + centre_offset, size.width),
                  axisSample(c.y + shape(1, 0) * ox + shape(1, 1) * oy + centre_offset, size.height), out);
        }
      continue;
    }
    AxisSample xs[DescriptorLayout::kMaxGridSide], ys[DescriptorLayout::kMaxGridSide];
    for (int g = 0; g < n; ++g)
    {
      xs[g] = axisSample(c.x + first + g * step + centre_offset, size.width);
      ys[g] = axisSample(c.y + first + g * step + centre_offset, size.height);
    }
    for (int gy = 0; gy < n; ++gy)
      for (int gx = 0; gx < n; ++gx, out += channels)
        blendAt(xs[gx], ys[gy], out);
  }
}

void PooledCellFeatures::extract(const V1FeaturePyramid& pyramid, const biovision_v1::Keypoint& keypoint,
                                 float* out) const
{
  if (pyramid.parameters().orientations != layout_.orientations ||
      pyramid.parameters().pooling_diameter != layout_.pooling_diameter ||
      pyramid.parameters().pooling_phases < layout_.phases)  // ON phases come first: a 4-phase pyramid serves 2
    throw std::invalid_argument(
        "PooledCellFeatures: the pyramid's orientations, pooling or phases do not fit the layout");
  std::fill(out, out + layout_.featureCount(), 0.f);
  // Snapped to the nearest half-octave level; the grid is scaled so the patch keeps its size. (Blending
  // the two nearest levels was measured: better on the strongest viewpoint change, worse pooled fpr95.)
  const int base = V1FeaturePyramid::levelOfWavelength(keypoint.wavelength);
  const float ratio = keypoint.wavelength > 0
                          ? static_cast<float>(keypoint.wavelength / V1FeaturePyramid::wavelengthOfLevel(base))
                          : 1.f;
  const cv::Matx22f shape = shape_adaptation_.estimate(pyramid, keypoint);
  sampleLevels(pyramid, cv::Point2f(keypoint.x, keypoint.y), base, ratio, shape, out);
  for (int j : layout_.scales)
  {
    const int count = layout_.phases * layout_.orientations * layout_.gridSide(j) * layout_.gridSide(j);
    double norm = 0.0;
    for (int i = 0; i < count; ++i)
      norm += double(out[i]) * out[i];
    if (norm > 1e-20)
    {
      const float inv = static_cast<float>(1.0 / std::sqrt(norm));
      for (int i = 0; i < count; ++i)
        out[i] *= inv;
    }
    out += count;
  }
}

cv::Mat PooledCellFeatures::extract(const V1FeaturePyramid& pyramid,
                                    const std::vector<biovision_v1::Keypoint>& keypoints) const
{
  cv::Mat x(static_cast<int>(keypoints.size()), layout_.featureCount(), CV_32F);
  // Keypoints are independent: both cores (cv::parallel_for_ follows cv::setNumThreads).
  cv::parallel_for_(cv::Range(0, static_cast<int>(keypoints.size())), [&](const cv::Range& r) {
    for (int i = r.start; i < r.end; ++i)
      extract(pyramid, keypoints[i], x.ptr<float>(i));
  });
  return x;
}
}  // namespace biovision_recognition
