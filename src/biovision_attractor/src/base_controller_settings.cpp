#include "biovision_attractor/base_controller_settings.hpp"

#include <stdexcept>

namespace biovision_attractor
{
void BaseControllerSettings::validate() const
{
  auto fail = [](const std::string& what) { throw std::invalid_argument("BaseControllerSettings: " + what); };
  if (odom_frame.empty())
    fail("odom_frame is empty");
  if (!(control_rate >= 1 && control_rate <= 1000))
    fail("control_rate outside [1, 1000] Hz");
  for (double timeout : {stm_timeout, odom_timeout})
    if (!(timeout > 0 && timeout <= 10 && timeout >= 1.0 / control_rate))
      fail("stm_timeout/odom_timeout outside (0, 10] s or below one control period");
  if (!(max_goal_distance > 0))
    fail("max_goal_distance must be > 0");
}
}  // namespace biovision_attractor
