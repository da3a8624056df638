#include "phantomx_driver/ax12_joint.hpp"

#include <algorithm>
#include <cmath>

namespace phantomx_driver
{
namespace
{
constexpr double kRpmPerUnit = 0.111;
}

int Ax12Joint::goalTicks(double rad) const
{
  if (!std::isfinite(rad))
    return -1;
  const double clamped = std::clamp(rad, lower, upper);
  long t = std::clamp(std::lround(kCenter + direction * (clamped + offset) / kRadPerTick), 0L, 1023L);
  // The nearest tick to a goal at a limit can lie up to half a tick (2.6 mrad) beyond it: one tick back
  // inside, when that tick is still within the limits (ticks grow with the angle when direction > 0).
  const long inward = direction > 0 ? -1 : 1;
  if (radians(static_cast<int>(t)) > upper && radians(static_cast<int>(t + inward)) >= lower)
    t += inward;
  else if (radians(static_cast<int>(t)) < lower && radians(static_cast<int>(t - inward)) <= upper)
    t -= inward;
  return static_cast<int>(std::clamp(t, 0L, 1023L));
}

double Ax12Joint::radians(int ticks) const
{
  return direction * (ticks - kCenter) * kRadPerTick - offset;
}

bool Ax12Joint::withinLimits(double rad) const
{
  return rad >= lower - 0.5 * kRadPerTick && rad <= upper + 0.5 * kRadPerTick;
}

int movingSpeedTicks(double rad_per_s)
{
  const double rpm = std::abs(rad_per_s) * 60.0 / (2.0 * M_PI);
  return static_cast<int>(std::clamp(std::lround(rpm / kRpmPerUnit), 1L, 1023L));
}

double presentSpeedRadPerS(int value)
{
  const double magnitude = (value & 0x3FF) * kRpmPerUnit * 2.0 * M_PI / 60.0;
  return (value & 0x400) != 0 ? -magnitude : magnitude;
}
}  // namespace phantomx_driver
