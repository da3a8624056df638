#include <gtest/gtest.h>

#include "biovision_ros_common/clock_jump_guard.hpp"

using biovision_ros_common::ClockJumpGuard;

TEST(ClockJumpGuard, ResetsRunOnceOnEachBackwardJumpOnly)
{
  ClockJumpGuard guard(0.05);
  int first = 0, second = 0;
  guard.onJumpBack([&] { ++first; });
  guard.onJumpBack([&] { ++second; });
  EXPECT_FALSE(guard.observe(ros::Time(100.0)));
  EXPECT_FALSE(guard.observe(ros::Time(101.0)));
  EXPECT_FALSE(guard.observe(ros::Time(100.97)));  // jitter within the tolerance
  EXPECT_EQ(first, 0);
  EXPECT_TRUE(guard.observe(ros::Time(10.0)));  // the bag looped
  EXPECT_EQ(first, 1);
  EXPECT_EQ(second, 1);
  EXPECT_FALSE(guard.observe(ros::Time(11.0)));  // time runs on from the new start
  EXPECT_TRUE(guard.observe(ros::Time(5.0)));
  EXPECT_EQ(guard.jumps(), 2u);
  EXPECT_EQ(first, 2);
}

TEST(ClockJumpGuard, AResetMayObserveAgainWithoutDeadlock)
{
  ClockJumpGuard guard;
  bool nested = true;
  guard.onJumpBack([&] { nested = guard.observe(ros::Time(2.0)); });  // a reset that reads the clock
  guard.observe(ros::Time(3.0));
  EXPECT_TRUE(guard.observe(ros::Time(2.0)));
  EXPECT_FALSE(nested);
}
