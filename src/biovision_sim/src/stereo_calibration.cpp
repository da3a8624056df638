#include "biovision_sim/stereo_calibration.hpp"

#include <cmath>
#include <stdexcept>
#include <string>

namespace biovision_sim
{
namespace
{
void require(bool ok, const std::string& what)
{
  if (!ok)
    throw std::invalid_argument("StereoCalibration: " + what);
}

void checkImageAndBaseline(int width, int height, double baseline)
{
  require(width >= 1, "width " + std::to_string(width) + " px must be >= 1");
  require(height >= 1, "height " + std::to_string(height) + " px must be >= 1");
  require(std::isfinite(baseline) && baseline >= 0.0,
          "baseline " + std::to_string(baseline) + " m must be finite and >= 0");
}
}  // namespace

StereoCalibration StereoCalibration::fromFieldOfView(int width, int height, double horizontal_fov, double baseline)
{
  checkImageAndBaseline(width, height, baseline);
  require(horizontal_fov > 0.0 && horizontal_fov < M_PI,
          "horizontal_fov " + std::to_string(horizontal_fov) + " rad outside (0, pi)");
  return StereoCalibration(PinholeCamera::fromFieldOfView(width, height, horizontal_fov), baseline);
}

StereoCalibration StereoCalibration::fromFocalLength(int width, int height, double focal_length, double baseline)
{
  checkImageAndBaseline(width, height, baseline);
  require(std::isfinite(focal_length) && focal_length > 0.0,
          "focal_length " + std::to_string(focal_length) + " px must be finite and > 0");
  return StereoCalibration(PinholeCamera::fromFocalLength(width, height, focal_length), baseline);
}

StereoCalibration::StereoCalibration(const PinholeCamera& camera, double baseline)
  : camera_(camera), baseline_(baseline)
{
}

StereoCalibration::Camera StereoCalibration::describe(double offset) const
{
  const PinholeCamera& c = camera_;
  Camera out;
  out.width = c.width;
  out.height = c.height;
  out.K = {c.fx, 0, c.cx, 0, c.fy, c.cy, 0, 0, 1};
  out.P = {c.fx, 0, c.cx, -c.fx * offset, 0, c.fy, c.cy, 0, 0, 0, 1, 0};
  return out;
}
}  // namespace biovision_sim
