#include "biovision_ros_common/clock_jump_guard.hpp"

namespace biovision_ros_common
{
void ClockJumpGuard::onJumpBack(std::function<void()> reset)
{
  std::lock_guard<std::mutex> lock(mutex_);
  resets_.push_back(std::move(reset));
}

bool ClockJumpGuard::observe(const ros::Time& time)
{
  std::vector<std::function<void()>> resets;
  {
    std::lock_guard<std::mutex> lock(mutex_);
    const bool jumped = !latest_.isZero() && (latest_ - time).toSec() > tolerance_;
    if (!jumped)
    {
      if (time > latest_)
        latest_ = time;
      return false;
    }
    latest_ = time;
    ++jumps_;
    resets = resets_;
  }
  // Outside the lock: a reset may itself take locks that another thread holds while observing.
  for (const auto& reset : resets)
    reset();
  return true;
}

unsigned ClockJumpGuard::jumps() const
{
  std::lock_guard<std::mutex> lock(mutex_);
  return jumps_;
}
}  // namespace biovision_ros_common
