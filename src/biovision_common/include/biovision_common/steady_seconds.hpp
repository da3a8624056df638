#pragma once

#include <chrono>

namespace biovision_common
{
/// Seconds on the steady (monotonic) clock: for time-outs and rates that must not follow the wall clock or
/// ROS time (a clock jump, use_sim_time without /clock). Only differences are meaningful.
inline double steadySeconds()
{
  return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count();
}
}  // namespace biovision_common
