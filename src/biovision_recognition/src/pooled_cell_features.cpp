#include "biovision_recognition/pooled_cell_features.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace biovision_recognition
{
namespace
{
float sampleClamped(const cv::Mat& m, float x, float y)
{
  x = std::min(std::max(x, 0.f), static_cast<float>(m.cols - 1));
  y = std::min(std::max(y, 0.f), static_cast<float>(m.rows - 1));
  const int x0 = std::min(static_cast<int>(x), m.cols - 2 < 0 ? 0 : m.cols - 2);
  const int y0 = std::min(static_cast<int>(y), m.rows - 2 < 0 ? 0 : m.rows - 2);
  const int x1 = std::min(x0 + 1, m.cols - 1), y1 = std::min(y0 + 1, m.rows - 1);
  const float fx = x - x0, fy = y - y0;
  const float* r0 = m.ptr<float>(y0);
  const float* r1 = m.ptr<float>(y1);
  return (1 - fy) * ((1 - fx) * r0[x0] + fx * r0[x1]) + fy * ((1 - fx) * r1[x0] + fx * r1[x1]);
}
}  // namespace

PooledCellFeatures::PooledCellFeatures(const DescriptorLayout& layout) : layout_(layout)
{
  layout_.validate();
}

void PooledCellFeatures::sampleLevels(const V1FeaturePyramid& pyramid, const cv::Point2f& position, int base,
                                      float size_ratio, float* out) const
{
  const float centre_offset = static_cast<float>(pyramid.poolingCentreOffset());
  const int channels = 2 * layout_.orientations;
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
    for (int ch = 0; ch < channels; ++ch)
    {
      const cv::Mat& map = pyramid.pooled(k)[ch];
      for (int gy = 0; gy < n; ++gy)
        for (int gx = 0; gx < n; ++gx)
          *out++ = sampleClamped(map, c.x + first + gx * step + centre_offset,
                                   c.y + first + gy * step + centre_offset);
    }
  }
}

void PooledCellFeatures::extract(const V1FeaturePyramid& pyramid, const biovision_v1::Keypoint& keypoint,
                                 float* out) const
{
  if (pyramid.parameters().orientations != layout_.orientations ||
      pyramid.parameters().pooling_diameter != layout_.pooling_diameter)
    throw std::invalid_argument("PooledCellFeatures: the pyramid's orientations or pooling differ from the layout's");
  std::fill(out, out + layout_.featureCount(), 0.f);
  // Snapped to the nearest half-octave level; the grid is scaled so the patch keeps its size. (Blending
  // the two nearest levels was measured: better on the strongest viewpoint change, worse pooled fpr95.)
  const int base = V1FeaturePyramid::levelOfWavelength(keypoint.wavelength);
  const float ratio =
      keypoint.wavelength > 0 ? static_cast<float>(keypoint.wavelength / V1FeaturePyramid::wavelengthOfLevel(base)) : 1.f;
  sampleLevels(pyramid, cv::Point2f(keypoint.x, keypoint.y), base, ratio, out);
  for (int j : layout_.scales)
  {
    const int count = 2 * layout_.orientations * layout_.gridSide(j) * layout_.gridSide(j);
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
  for (size_t i = 0; i < keypoints.size(); ++i)
    extract(pyramid, keypoints[i], x.ptr<float>(static_cast<int>(i)));
  return x;
}
}  // namespace biovision_recognition
