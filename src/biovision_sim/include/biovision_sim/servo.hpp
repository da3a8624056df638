#pragma once

namespace biovision_sim
{
/// A position-controlled servo (Dynamixel AX-12 of the PhantomX turret): moves towards its target at
/// no more than `max_speed`, and neither target nor position ever leaves [lower, upper].
class Servo
{
public:
  Servo(double lower, double upper, double max_speed, double position = 0.0);

  /// Sets the target, clamped to the limits; returns true when it had to be clamped. NaN is ignored.
  bool command(double target);
  void step(double dt);

  double position() const { return position_; }
  double velocity() const { return velocity_; }
  double target() const { return target_; }
  double lower() const { return lower_; }
  double upper() const { return upper_; }
  double maxSpeed() const { return max_speed_; }

private:
  double lower_, upper_, max_speed_;
  double position_, target_, velocity_ = 0.0;
};
}  // namespace biovision_sim
