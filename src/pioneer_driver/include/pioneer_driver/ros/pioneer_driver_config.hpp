#pragma once

#include "pioneer_driver/PioneerDriverConfig.h"
#include "pioneer_driver/pioneer_parameters.hpp"

namespace pioneer_driver
{
/// The reconfigurable fields of `parameters` set from a dynamic_reconfigure Config (the nodelet and the
/// parameter-file test use this one mapping). The result is not validated here.
inline PioneerParameters withConfig(PioneerParameters parameters, const PioneerDriverConfig& config)
{
  parameters.max_linear_speed = config.max_linear_speed;
  parameters.max_angular_speed = config.max_angular_speed;
  parameters.cmd_vel_timeout = config.cmd_vel_timeout;
  return parameters;
}
}  // namespace pioneer_driver
