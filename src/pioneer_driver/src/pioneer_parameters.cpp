#include "pioneer_driver/pioneer_parameters.hpp"

#include <sstream>
#include <stdexcept>

namespace pioneer_driver
{
void PioneerParameters::validate() const
{
  auto range = [](const char* name, double v, double lo, double hi, bool open_lo, const char* unit) {
    if (!(open_lo ? v > lo : v >= lo) || !(v <= hi))
    {
      std::ostringstream s;
      s << "PioneerParameters: " << name << " = " << v << " outside " << (open_lo ? "(" : "[") << lo << ", " << hi
        << "] " << unit;
      throw std::invalid_argument(s.str());
    }
  };
  if (port.empty())
    throw std::invalid_argument("PioneerParameters: port is empty");
  if (baud != 9600 && baud != 19200 && baud != 38400 && baud != 57600 && baud != 115200)
    throw std::invalid_argument("PioneerParameters: baud = " + std::to_string(baud) +
                                " is not one of 9600, 19200, 38400, 57600, 115200");
  range("max_linear_speed", max_linear_speed, 0.0, 2.2, true, "m/s");
  range("max_angular_speed", max_angular_speed, 0.0, 8.7, true, "rad/s");
  range("cmd_vel_timeout", cmd_vel_timeout, 0.05, 2.0, false, "s");
  range("pulse_period", pulse_period, 0.05, 1.9, false, "s");
  range("sip_timeout", sip_timeout, 0.3, 10.0, false, "s");
  range("reconnect_period", reconnect_period, 0.1, 60.0, false, "s");
  range("sync_timeout", sync_timeout, 0.05, 5.0, false, "s");
  range("angle_conv_factor", angle_conv_factor, 0.0, 0.1, true, "rad");
  range("dist_conv_factor", dist_conv_factor, 0.0, 10.0, true, "mm");
  range("vel_conv_factor", vel_conv_factor, 0.0, 10.0, true, "mm/s");
  range("diff_conv_factor", diff_conv_factor, 0.0, 1.0, true, "rad/s per mm/s");
  if (odom_frame.empty() || base_frame.empty() || odom_frame == base_frame)
    throw std::invalid_argument("PioneerParameters: odom_frame and base_frame must be set and differ");
}
}  // namespace pioneer_driver
