#include "biovision_recognition/affine_shape_adaptation.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <stdexcept>

namespace biovision_recognition
{
namespace
{
float bilinear(const cv::Mat& image, float x, float y)
{
  x = std::min(std::max(x, 0.f), static_cast<float>(image.cols - 1));
  y = std::min(std::max(y, 0.f), static_cast<float>(image.rows - 1));
  const int x0 = std::min(static_cast<int>(x), std::max(image.cols - 2, 0));
  const int y0 = std::min(static_cast<int>(y), std::max(image.rows - 2, 0));
  const int x1 = std::min(x0 + 1, image.cols - 1), y1 = std::min(y0 + 1, image.rows - 1);
  const float fx = x - x0, fy = y - y0;
  const float* r0 = image.ptr<float>(y0);
  const float* r1 = image.ptr<float>(y1);
  return (1 - fy) * ((1 - fx) * r0[x0] + fx * r0[x1]) + fy * ((1 - fx) * r1[x0] + fx * r1[x1]);
}

/// Symmetric square root of a symmetric positive-semidefinite 2x2 matrix, scaled to det 1.
cv::Matx22d unitSqrt(const cv::Matx22d& m)
{
  const double det = std::sqrt(std::max(m(0, 0) * m(1, 1) - m(0, 1) * m(1, 0), 0.0));
  const double t = std::sqrt(m(0, 0) + m(1, 1) + 2 * det);
  cv::Matx22d r((m(0, 0) + det) / t, m(0, 1) / t, m(1, 0) / t, (m(1, 1) + det) / t);
  const double d = std::sqrt(std::max(r(0, 0) * r(1, 1) - r(0, 1) * r(1, 0), 1e-30));
  return r * (1.0 / d);
}

/// Caps the ratio of a symmetric det-1 matrix's eigenvalues at max_ratio.
cv::Matx22d capAnisotropy(const cv::Matx22d& s, double max_ratio)
{
  const double half_trace = 0.5 * (s(0, 0) + s(1, 1));
  const double disc = std::sqrt(std::max(half_trace * half_trace - 1.0, 0.0));  // det = 1
  const double big = half_trace + disc;                                         // small = 1 / big
  const double limit = std::sqrt(max_ratio);
  if (big <= limit)
    return s;
  // Same eigenvectors, eigenvalues sqrt(max_ratio) and its inverse: s = a I + b (s - half_trace I).
  const double scale = (limit - 1.0 / limit) / (big - 1.0 / big);
  const double mean = 0.5 * (limit + 1.0 / limit);
  return cv::Matx22d(mean, 0, 0, mean) + scale * (s - cv::Matx22d(half_trace, 0, 0, half_trace));
}
}  // namespace

void AffineShapeAdaptation::validate(const Parameters& p)
{
  if (p.iterations < 0 || p.iterations > 16)
    throw std::invalid_argument("AffineShapeAdaptation: iterations must be in [0, 16]");
  if (!(p.window_wavelengths > 0 && p.window_wavelengths <= 8))
    throw std::invalid_argument("AffineShapeAdaptation: window_wavelengths must be in (0, 8]");
  if (p.level_offset < 0 || p.level_offset > 4)
    throw std::invalid_argument("AffineShapeAdaptation: level_offset must be in [0, 4]");
  if (!(p.max_anisotropy >= 1 && p.max_anisotropy <= 16))
    throw std::invalid_argument("AffineShapeAdaptation: max_anisotropy must be in [1, 16]");
}

AffineShapeAdaptation::AffineShapeAdaptation(const Parameters& parameters) : parameters_(parameters)
{
  validate(parameters);
}

cv::Matx22f AffineShapeAdaptation::estimate(const V1FeaturePyramid& pyramid,
                                            const biovision_v1::Keypoint& keypoint) const
{
  cv::Matx22d s = cv::Matx22d::eye();
  if (parameters_.iterations == 0 || pyramid.levels() == 0)
    return s;
  const int k = std::min(V1FeaturePyramid::levelOfWavelength(keypoint.wavelength) + parameters_.level_offset,
                         pyramid.levels() - 1);
  const cv::Mat& image = pyramid.image(k);
  const cv::Point2f c = pyramid.toLevel(cv::Point2f(keypoint.x, keypoint.y), k);
  const double level_px = pyramid.toLevel(cv::Point2f(keypoint.x + 1.f, keypoint.y), k).x -
                          c.x;  // level px per image px
  const double sigma = parameters_.window_wavelengths * keypoint.wavelength * level_px;
  constexpr int kHalf = 6;  // 13 x 13 samples over +-2 sigma
  const double spacing = 2.0 * sigma / kHalf;
  // The window's weights depend only on the sample's grid index (spacing is a fixed fraction of sigma).
  static const std::array<double, (2 * kHalf + 1) * (2 * kHalf + 1)> kWeights = [] {
    std::array<double, (2 * kHalf + 1) * (2 * kHalf + 1)> w{};
    for (int v = -kHalf; v <= kHalf; ++v)
      for (int u = -kHalf; u <= kHalf; ++u)
        w[(v + kHalf) * (2 * kHalf + 1) + u + kHalf] = std::exp(-2.0 * (u * u + v * v) / double(kHalf * kHalf));
    return w;
  }();
  for (int it = 0; it < parameters_.iterations; ++it)
  {
    // Gradients along the normalised frame's axes (derivatives warped with the window), one level px apart.
    const cv::Vec2d ax(s(0, 0), s(1, 0)), ay(s(0, 1), s(1, 1));
    double m00 = 0, m01 = 0, m11 = 0;
    for (int v = -kHalf; v <= kHalf; ++v)
      for (int u = -kHalf; u <= kHalf; ++u)
      {
        const double qx = u * spacing, qy = v * spacing;
        const double w = kWeights[(v + kHalf) * (2 * kHalf + 1) + u + kHalf];
        const float px = static_cast<float>(c.x + s(0, 0) * qx + s(0, 1) * qy);
        const float py = static_cast<float>(c.y + s(1, 0) * qx + s(1, 1) * qy);
        const double gx = 0.5 * (bilinear(image, px + ax[0], py + ax[1]) - bilinear(image, px - ax[0], py - ax[1]));
        const double gy = 0.5 * (bilinear(image, px + ay[0], py + ay[1]) - bilinear(image, px - ay[0], py - ay[1]));
        m00 += w * gx * gx;
        m01 += w * gx * gy;
        m11 += w * gy * gy;
      }
    if (!(m00 * m11 - m01 * m01 > 1e-12 * (m00 + m11) * (m00 + m11)) || !(m00 + m11 > 1e-12))
      break;  // flat or one straight edge: no shape to adapt to
    const cv::Matx22d inv_sqrt = unitSqrt(cv::Matx22d(m00, m01, m01, m11)).inv();
    const cv::Matx22d next = s * inv_sqrt;
    // Canonical upright frame: the symmetric factor of next (next next^T)^(1/2).
    s = capAnisotropy(unitSqrt(next * next.t()), parameters_.max_anisotropy);
  }
  return s;
}
}  // namespace biovision_recognition
