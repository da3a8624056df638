#pragma once

#include <algorithm>
#include <string>
#include <vector>

#include <opencv2/core.hpp>

namespace biovision_sim
{
/// A repeating surface texture with a mip pyramid. Texture coordinates are metres on the surface:
/// the image covers `period` x `period` metres and repeats.
class Texture
{
public:
  /// Procedural kinds: "solid", "checker", "noise", "stripes", "bricks"; or "image" from a file.
  struct Spec
  {
    std::string type = "solid";
    cv::Vec3b colour_a{128, 128, 128};  ///< BGR
    cv::Vec3b colour_b{64, 64, 64};     ///< BGR
    double period = 1.0;                ///< metres covered by the texture image
    double feature = 0.1;               ///< checker cell / stripe width / noise blob size / brick height [m]
    double contrast = 1.0;              ///< noise amplitude, 0..1
    unsigned seed = 1;
    std::string file;  ///< for "image"
  };

  explicit Texture(const Spec& spec);

  /// Bilinear sample at (u, v) metres on mip level `level`; returns BGR as floats 0..255.
  cv::Vec3f sample(float u, float v, int level) const;
  int levels() const { return static_cast<int>(mips_.size()); }
  /// Texels per metre on level 0.
  double texelsPerMetre() const { return texels_per_metre_; }
  const cv::Mat& image() const { return mips_.front(); }
  /// Mip level (clamped), CV_32FC3, square with a power-of-two side.
  const cv::Mat& mip(int level) const { return mips_[std::clamp(level, 0, levels() - 1)]; }

private:
  std::vector<cv::Mat> mips_;  // CV_32FC3, level 0 = full
  double texels_per_metre_ = 256;
};
}  // namespace biovision_sim
