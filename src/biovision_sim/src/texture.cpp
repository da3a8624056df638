#include "biovision_sim/texture.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

namespace biovision_sim
{
namespace
{
constexpr int kSize = 256;  // texels of a procedural texture

cv::Mat procedural(const Texture::Spec& s)
{
  cv::Mat img(kSize, kSize, CV_8UC3, cv::Scalar(s.colour_a[0], s.colour_a[1], s.colour_a[2]));
  const double tpm = kSize / s.period;  // texels per metre
  const int f = std::max(1, static_cast<int>(std::lround(s.feature * tpm)));
  const cv::Scalar b(s.colour_b[0], s.colour_b[1], s.colour_b[2]);
  if (s.type == "solid")
    return img;
  if (s.type == "checker")
  {
    for (int y = 0; y < kSize; ++y)
      for (int x = 0; x < kSize; ++x)
        if (((x / f) + (y / f)) % 2)
          img.at<cv::Vec3b>(y, x) = s.colour_b;
    return img;
  }
  if (s.type == "stripes")
  {
    for (int y = 0; y < kSize; ++y)
      for (int x = 0; x < kSize; ++x)
        if ((x / f) % 2)
          img.at<cv::Vec3b>(y, x) = s.colour_b;
    return img;
  }
  if (s.type == "bricks")
  {
    img.setTo(cv::Scalar(s.colour_a[0], s.colour_a[1], s.colour_a[2]));
    for (int y = 0; y < kSize; y += f)
    {
      cv::line(img, {0, y}, {kSize, y}, b, 2);
      const int offset = (y / f) % 2 ? f : 0;
      for (int x = offset; x < kSize; x += 2 * f)
        cv::line(img, {x, y}, {x, y + f}, b, 2);
    }
    return img;
  }
  if (s.type == "noise")
  {
    // Smooth random blobs of about `feature` size: texture a stereo matcher can lock on to. Generated
    // at the blob scale and upsampled, wrapped so that the texture tiles without seams.
    cv::RNG rng(s.seed);
    const int cells = std::max(2, kSize / f);
    cv::Mat small(cells, cells, CV_32F);
    rng.fill(small, cv::RNG::UNIFORM, -1.0, 1.0);
    cv::Mat tiled;
    cv::repeat(small, 3, 3, tiled);
    cv::Mat up;
    cv::resize(tiled, up, cv::Size(3 * kSize, 3 * kSize), 0, 0, cv::INTER_CUBIC);
    const cv::Mat n = up(cv::Rect(kSize, kSize, kSize, kSize));
    for (int y = 0; y < kSize; ++y)
      for (int x = 0; x < kSize; ++x)
      {
        const double t = 0.5 + 0.5 * s.contrast * std::clamp(static_cast<double>(n.at<float>(y, x)), -1.0, 1.0);
        cv::Vec3b& p = img.at<cv::Vec3b>(y, x);
        for (int c = 0; c < 3; ++c)
          p[c] = cv::saturate_cast<uchar>((1 - t) * s.colour_a[c] + t * s.colour_b[c]);
      }
    return img;
  }
  throw std::runtime_error("unknown texture type '" + s.type + "' (solid, checker, noise, stripes, bricks, image)");
}
}  // namespace

Texture::Texture(const Spec& spec)
{
  cv::Mat base;
  if (spec.type == "image")
  {
    base = cv::imread(spec.file, cv::IMREAD_COLOR);
    if (base.empty())
      throw std::runtime_error("cannot read texture image '" + spec.file + "'");
    const int side = 256;  // power of two: the renderer wraps coordinates with a mask
    cv::resize(base, base, cv::Size(side, side), 0, 0, cv::INTER_AREA);
  }
  else
    base = procedural(spec);
  if (!(spec.period > 0))
    throw std::runtime_error("texture period must be > 0");
  texels_per_metre_ = base.cols / spec.period;
  cv::Mat f;
  base.convertTo(f, CV_32FC3);
  mips_.push_back(f);
  while (mips_.back().cols > 4)
  {
    cv::Mat next;
    cv::pyrDown(mips_.back(), next);
    mips_.push_back(next);
  }
}

cv::Vec3f Texture::sample(float u, float v, int level) const
{
  const cv::Mat& m = mips_[std::clamp(level, 0, levels() - 1)];
  const float scale = static_cast<float>(texels_per_metre_) * m.cols / mips_.front().cols;
  const float x = u * scale - 0.5f, y = v * scale - 0.5f;
  const float fx = std::floor(x), fy = std::floor(y);
  const float ax = x - fx, ay = y - fy;
  const int n = m.cols;
  auto wrap = [n](int i) { return ((i % n) + n) % n; };
  const int x0 = wrap(static_cast<int>(fx)), x1 = wrap(static_cast<int>(fx) + 1);
  const int y0 = wrap(static_cast<int>(fy)), y1 = wrap(static_cast<int>(fy) + 1);
  const cv::Vec3f* r0 = m.ptr<cv::Vec3f>(y0);
  const cv::Vec3f* r1 = m.ptr<cv::Vec3f>(y1);
  return (r0[x0] * (1 - ax) + r0[x1] * ax) * (1 - ay) + (r1[x0] * (1 - ax) + r1[x1] * ax) * ay;
}
}  // namespace biovision_sim
