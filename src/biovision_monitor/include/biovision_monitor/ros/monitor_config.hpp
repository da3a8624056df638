#pragma once

#include <biovision_monitor/MonitorConfig.h>
#include <dynamic_reconfigure/Config.h>

#include "biovision_monitor/monitor_parameters.hpp"

namespace biovision_monitor
{
/// The one mapping of cfg/Monitor.cfg onto MonitorParameters, by parameter name. Does not validate.
inline MonitorParameters toMonitorParameters(const MonitorConfig& config)
{
  dynamic_reconfigure::Config message;
  config.__toMessage__(message);
  MonitorParameters p;
  for (const auto& d : message.doubles)
    for (const auto& [name, field] : MonitorParameters::namedDoubles())
      if (name == d.name)
        p.*field = d.value;
  for (const auto& i : message.ints)
    for (const auto& [name, field] : MonitorParameters::namedInts())
      if (name == i.name)
        p.*field = i.value;
  return p;
}
}  // namespace biovision_monitor
