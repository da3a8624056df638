#include <gtest/gtest.h>

#include <boost/make_shared.hpp>
#include <sensor_msgs/Image.h>

#include "biovision_ros_common/stamped_history.hpp"

namespace
{
using biovision_ros_common::StampedHistory;
using History = StampedHistory<sensor_msgs::Image>;

History::ConstPtr at(double t)
{
  auto m = boost::make_shared<sensor_msgs::Image>();
  m->header.stamp = ros::Time(t);
  return m;
}

TEST(StampedHistory, FindsTheExactAndTheNearestMessageAndKnowsWhenOneWillNotCome)
{
  History h(3);
  EXPECT_FALSE(h.exact(ros::Time(1.0)));
  EXPECT_FALSE(h.nearest(ros::Time(1.0), 10.0));
  EXPECT_FALSE(h.passed(ros::Time(1.0)));
  for (double t : {1.0, 1.1, 1.2})
    h.add(at(t));
  EXPECT_EQ(h.exact(ros::Time(1.1))->header.stamp, ros::Time(1.1));
  EXPECT_FALSE(h.exact(ros::Time(1.15)));
  // Nearest within max_age, before or after; the earlier one on a tie; none beyond max_age.
  EXPECT_EQ(h.nearest(ros::Time(1.17), 0.5)->header.stamp, ros::Time(1.2));
  EXPECT_EQ(h.nearest(ros::Time(1.04), 0.5)->header.stamp, ros::Time(1.0));
  EXPECT_EQ(h.nearest(ros::Time(1.25), 0.5)->header.stamp, ros::Time(1.2));
  EXPECT_EQ(h.nearest(ros::Time(1.05), 0.5)->header.stamp.toSec(), 1.0);
  EXPECT_FALSE(h.nearest(ros::Time(2.0), 0.5));
  // Stamped before the newest: it may still come; after it: it will not.
  EXPECT_FALSE(h.passed(ros::Time(1.3)));
  EXPECT_FALSE(h.passed(ros::Time(1.2)));
  EXPECT_TRUE(h.passed(ros::Time(1.15)));
}

TEST(StampedHistory, StaysBoundedAndStartsAgainWhenTimeGoesBack)
{
  History h(3);
  for (int i = 0; i < 10; ++i)
    h.add(at(1.0 + 0.1 * i));
  EXPECT_EQ(h.size(), 3u);
  EXPECT_FALSE(h.exact(ros::Time(1.0)));
  EXPECT_EQ(h.latest()->header.stamp, ros::Time(1.9));
  h.add(History::ConstPtr());  // ignored
  EXPECT_EQ(h.size(), 3u);
  h.add(at(0.5));  // a looped bag
  EXPECT_EQ(h.size(), 1u);
  EXPECT_FALSE(h.passed(ros::Time(1.5)));
  EXPECT_THROW(History(0), std::invalid_argument);
}
}  // namespace
