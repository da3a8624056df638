#include "biovision_ros_common/input_check.hpp"

#include <sstream>

namespace biovision_ros_common
{
namespace
{
std::string number(double x)
{
  std::ostringstream s;
  s << x;
  return s.str();
}

// Focal length [px] that gives field of view `fov` over `size` pixels.
double focalFor(double size, double fov)
{
  return 0.5 * size / std::tan(0.5 * fov);
}
}  // namespace

void InputCheck::cameraInfo(const sensor_msgs::CameraInfo& info, uint32_t image_width, uint32_t image_height)
{
  const std::string what = "camera_info (" + std::to_string(info.width) + "x" + std::to_string(info.height) + ")";
  if (info.width == 0 || info.height == 0)
    throw InputError(what + " has a zero width or height");
  for (size_t i = 0; i < info.P.size(); ++i)
    if (!std::isfinite(info.P[i]))
      throw InputError(what + ": P[" + std::to_string(i) + "] is " + number(info.P[i]));
  const double fx = info.P[0], fy = info.P[5], cx = info.P[2], cy = info.P[6];
  if (fx == 0.0 && fy == 0.0)
    throw InputError(what + " is uncalibrated (P[0] = P[5] = 0)");
  auto checkFocal = [&](const char* name, double f, double size) {
    const double lo = focalFor(size, kMaxFieldOfView), hi = focalFor(size, kMinFieldOfView);
    if (!(f >= lo && f <= hi))
      throw InputError(what + ": " + name + " = " + number(f) + " px is outside [" + number(lo) + ", " + number(hi) +
                       "] (a field of view between 0.1 and 170 degrees)");
  };
  checkFocal("fx (P[0])", fx, info.width);
  checkFocal("fy (P[5])", fy, info.height);
  if (std::abs(cx - 0.5 * info.width) > info.width || std::abs(cy - 0.5 * info.height) > info.height)
    throw InputError(what + ": principal point (" + number(cx) + ", " + number(cy) + ") lies far outside the image");
  if (image_width != 0 && image_height != 0 && (info.width != image_width || info.height != image_height))
    throw InputError(what + " does not match the " + std::to_string(image_width) + "x" + std::to_string(image_height) +
                     " image");
}

std::map<std::string, double> InputCheck::jointPositions(const sensor_msgs::JointState& msg,
                                                         const std::vector<std::string>& joints, double max_abs)
{
  std::map<std::string, double> found;
  if (msg.position.empty())
    return found;
  if (msg.position.size() != msg.name.size())
    throw InputError("joint_states with " + std::to_string(msg.name.size()) + " names and " +
                     std::to_string(msg.position.size()) + " positions");
  for (size_t i = 0; i < msg.name.size(); ++i)
    for (const auto& joint : joints)
      if (msg.name[i] == joint)
      {
        bounded("joint_states position of " + joint, msg.position[i], max_abs);
        found[joint] = msg.position[i];
      }
  return found;
}

void InputCheck::bounded(const std::string& what, double value, double max_abs)
{
  if (!std::isfinite(value) || std::abs(value) > max_abs)
    throw InputError(what + " is " + number(value) + " (expected a finite value within +-" + number(max_abs) + ")");
}
}  // namespace biovision_ros_common
