#include "biovision_attractor/base_attractor_parameters.hpp"

#include <cmath>
#include <sstream>
#include <stdexcept>

namespace biovision_attractor
{
const std::vector<BaseAttractorParameters::Named>& BaseAttractorParameters::namedDoubles()
{
  using P = BaseAttractorParameters;
  static const std::vector<Named> names = {
      {"alpha_goal", &P::alpha_goal, 0.0, 20.0},
      {"alpha_obstacle", &P::alpha_obstacle, 0.0, 200.0},
      {"decay_distance", &P::decay_distance, 0.01, 10.0},
      {"robot_radius", &P::robot_radius, 0.05, 2.0},
      {"max_range", &P::max_range, 0.1, 20.0},
      {"min_confidence", &P::min_confidence, 0.0, 1.0},
      {"symmetry_angle", &P::symmetry_angle, 0.0, 1.0},
      {"max_linear", &P::max_linear, 0.0, 1.2},
      {"max_angular", &P::max_angular, 0.0, 5.24},
      {"linear_accel", &P::linear_accel, 0.01, 5.0},
      {"angular_accel", &P::angular_accel, 0.01, 20.0},
      {"safety_distance", &P::safety_distance, 0.0, 2.0},
      {"slow_distance", &P::slow_distance, 0.01, 5.0},
      {"corridor_margin", &P::corridor_margin, 0.0, 1.0},
      {"margin_speed", &P::margin_speed, 0.0, 1.2},
      {"turn_brake_share", &P::turn_brake_share, 0.0, 1.0},
      {"turn_slowdown", &P::turn_slowdown, 0.1, 20.0},
      {"blind_turn_rate", &P::blind_turn_rate, 0.0, 20.0},
      {"blind_speed", &P::blind_speed, 0.0, 1.2},
      {"blind_distance", &P::blind_distance, 0.01, 10.0},
      {"heading_stop_angle", &P::heading_stop_angle, 0.1, 3.1416},
      {"turn_in_place_angle", &P::turn_in_place_angle, 0.05, 3.1416},
      {"goal_tolerance", &P::goal_tolerance, 0.01, 2.0},
      {"trap_time", &P::trap_time, 1.0, 600.0},
      {"trap_progress", &P::trap_progress, 0.01, 10.0},
      {"escape_time", &P::escape_time, 0.0, 60.0},
  };
  return names;
}

void BaseAttractorParameters::validate() const
{
  for (const Named& n : namedDoubles())
  {
    const double v = this->*n.field;
    if (!(v >= n.lower && v <= n.upper))
    {
      std::ostringstream s;
      s << "BaseAttractorParameters: " << n.name << " = " << v << " outside [" << n.lower << ", " << n.upper << "]";
      throw std::invalid_argument(s.str());
    }
  }
  if (!(slow_distance > safety_distance))
    throw std::invalid_argument("BaseAttractorParameters: slow_distance must be > safety_distance");
}
}  // namespace biovision_attractor
