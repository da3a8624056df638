#include "phantomx_driver/phantomx_parameters.hpp"

#include <sstream>
#include <stdexcept>

#include "phantomx_driver/ax12_joint.hpp"

namespace phantomx_driver
{
void PhantomXParameters::validate() const
{
  auto fail = [](const std::string& what) { throw std::invalid_argument("PhantomXParameters: " + what); };
  auto range = [&](const char* name, double v, double lo, double hi, bool open_lo, const char* unit) {
    if (!(open_lo ? v > lo : v >= lo) || !(v <= hi))
    {
      std::ostringstream s;
      s << name << " = " << v << " outside " << (open_lo ? "(" : "[") << lo << ", " << hi << "] " << unit;
      fail(s.str());
    }
  };
  if (port.empty())
    fail("port is empty");
  if (baud != 57600 && baud != 115200 && baud != 500000 && baud != 1000000)
    fail("baud = " + std::to_string(baud) + " is not one of 57600, 115200, 500000, 1000000");
  if (pan_joint.empty() || tilt_joint.empty() || pan_joint == tilt_joint)
    fail("pan_joint and tilt_joint must be set and differ");
  range("pan_id", pan_id, 0, 253, false, "");
  range("tilt_id", tilt_id, 0, 253, false, "");
  if (pan_id == tilt_id)
    fail("pan_id and tilt_id are both " + std::to_string(pan_id));
  range("pan_offset", pan_offset, -0.5, 0.5, false, "rad");
  range("tilt_offset", tilt_offset, -0.5, 0.5, false, "rad");
  if (pan_direction != 1 && pan_direction != -1)
    fail("pan_direction = " + std::to_string(pan_direction) + " is not +1 or -1");
  if (tilt_direction != 1 && tilt_direction != -1)
    fail("tilt_direction = " + std::to_string(tilt_direction) + " is not +1 or -1");
  const double half_range = 512 * Ax12Joint::kRadPerTick;  // ±150° around the centre
  range("pan_lower", pan_lower, -half_range, 0.0, false, "rad");
  range("pan_upper", pan_upper, 0.0, half_range, false, "rad");
  range("tilt_lower", tilt_lower, -half_range, 0.0, false, "rad");
  range("tilt_upper", tilt_upper, 0.0, half_range, false, "rad");
  range("max_speed", max_speed, 0.0, 6.17, true, "rad/s");
  range("poll_rate", poll_rate, 30.0, 200.0, false, "Hz");
  range("response_timeout", response_timeout, 0.002, 0.5, false, "s");
  range("lost_after", lost_after, 1, 100, false, "polls");
  range("retry_period", retry_period, 0.1, 60.0, false, "s");
}
}  // namespace phantomx_driver
