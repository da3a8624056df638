#include "biovision_sim/servo.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace biovision_sim
{
Servo::Servo(double lower, double upper, double max_speed, double position)
  : lower_(lower),
    upper_(upper),
    max_speed_(max_speed),
    position_(std::clamp(position, lower, upper)),
    target_(position_)
{
  if (!(lower < upper) || !(max_speed > 0))
    throw std::invalid_argument("Servo: needs lower < upper and max_speed > 0");
}

bool Servo::command(double target)
{
  if (!std::isfinite(target))
    return true;
  target_ = std::clamp(target, lower_, upper_);
  return target_ != target;
}

void Servo::step(double dt)
{
  const double delta = std::clamp(target_ - position_, -max_speed_ * dt, max_speed_ * dt);
  position_ = std::clamp(position_ + delta, lower_, upper_);
  velocity_ = dt > 0 ? delta / dt : 0.0;
}
}  // namespace biovision_sim
