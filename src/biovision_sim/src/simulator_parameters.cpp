#include "biovision_sim/simulator_parameters.hpp"

#include <cmath>
#include <sstream>
#include <stdexcept>
#include <string>

namespace biovision_sim
{
namespace
{
std::string format(double value)
{
  std::ostringstream s;
  s << value;
  return s.str();
}

template <typename T>
void require(bool ok, const char* field, T value, const std::string& range)
{
  if (ok)
    return;
  std::ostringstream s;
  s << "SimulatorParameters: " << field << " = " << value << " outside " << range;
  throw std::invalid_argument(s.str());
}
}  // namespace

void SimulatorParameters::validate() const
{
  if (world.empty())
    throw std::invalid_argument("SimulatorParameters: world (a world YAML file) is required");
  // Each test is true inside the range, so NaN (every comparison false) fails it.
  require(std::isfinite(camera_rate) && camera_rate > 0, "camera_rate", camera_rate, "(0, inf) Hz");
  require(std::isfinite(physics_rate) && physics_rate >= camera_rate, "physics_rate", physics_rate,
          "[camera_rate = " + format(camera_rate) + ", inf) Hz");
  // Upper bounds: a 4096-px side at supersample 4 renders 16384 px wide, which still fits cv::Mat; beyond it
  // allocation failed with an uncaught cv::Exception (issue #23 item 13).
  require(width >= 32 && width <= kMaxImageSide, "width", width, "[32, " + std::to_string(kMaxImageSide) + "] px");
  require(height >= 24 && height <= kMaxImageSide, "height", height, "[24, " + std::to_string(kMaxImageSide) + "] px");
  require(horizontal_fov_deg > 1 && horizontal_fov_deg < 179, "horizontal_fov_deg", horizontal_fov_deg, "(1, 179) deg");
  require(supersample >= 1 && supersample <= 4, "supersample", supersample, "[1, 4]");
  require(std::isfinite(noise_sigma) && noise_sigma >= 0, "noise_sigma", noise_sigma, "[0, inf) grey levels");
  require(blur_sigma >= 0 && blur_sigma <= 10, "blur_sigma", blur_sigma, "[0, 10] px");
  require(real_time_factor >= 0, "real_time_factor", real_time_factor, "[0, inf]");
  require(std::isfinite(start_x), "start_x", start_x, "(-inf, inf) m");
  require(std::isfinite(start_y), "start_y", start_y, "(-inf, inf) m");
  require(std::isfinite(start_yaw), "start_yaw", start_yaw, "(-inf, inf) rad");
  require(servo_speed > 0, "servo_speed", servo_speed, "(0, inf] rad/s");
}
}  // namespace biovision_sim
