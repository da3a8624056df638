// monitor_panel and the plot node against a real master: lazy (no subscription, no rendering without a
// listener), the panel's eight tiles (data where it was published, "no data" elsewhere), the plot's
// image, bad input -> ERROR diagnostics while the panel keeps coming.
#include <cmath>

#include <biovision_msgs/AttractorState.h>
#include <biovision_msgs/EgoMap.h>
#include <gtest/gtest.h>
#include <ros/ros.h>
#include <sensor_msgs/Image.h>

#include "biovision_ros_common/rostest_helpers.hpp"

using biovision_ros_common::DiagnosticsWatch;
using biovision_ros_common::TopicProbe;
using biovision_ros_common::waitFor;

namespace
{
biovision_msgs::AttractorState headState()
{
  biovision_msgs::AttractorState s;
  s.header.stamp = ros::Time::now();
  s.controller = "head_pan";
  s.behaviour = "explore";
  for (int i = 0; i < 9; ++i)
  {
    s.section_angles.push_back(float((-80 + 20 * i) * M_PI / 180));
    s.attraction.push_back(i == 6 ? 1.0f : 0.0f);
    s.repulsion.push_back(i == 2 ? 1.0f : 0.0f);
    s.forcelet.push_back(0.0f);
  }
  s.angle = 0.1f;
  s.rate = 0.3f;
  s.target = float(40 * M_PI / 180);
  return s;
}

// Spread of the grey levels of a bgr8 message's region (0 = uniform).
int spread(const sensor_msgs::Image& m, int x0, int y0, int w, int h)
{
  int lo = 255, hi = 0;
  for (int y = y0; y < y0 + h; ++y)
    for (int x = x0; x < x0 + w; ++x)
    {
      const uint8_t* p = &m.data[size_t(y) * m.step + size_t(x) * 3];
      const int g = (p[0] + p[1] + p[2]) / 3;
      lo = std::min(lo, g);
      hi = std::max(hi, g);
    }
  return hi - lo;
}
}  // namespace

TEST(MonitorNodes, LazyThenEightTilesAndAPlotThenBadInputIsReported)
{
  ros::NodeHandle nh;
  ros::Publisher head_pub = nh.advertise<biovision_msgs::AttractorState>("attractor/head", 1);
  ros::Publisher stm_pub = nh.advertise<biovision_msgs::EgoMap>("memory/stm", 1);
  ros::Publisher saliency_pub = nh.advertise<sensor_msgs::Image>("saliency/map", 1);
  DiagnosticsWatch diagnostics(nh, "monitor panel");

  // Nobody listens: neither node subscribes to anything (give the connection callbacks time).
  ros::WallDuration(2.0).sleep();
  EXPECT_EQ(head_pub.getNumSubscribers(), 0u) << "a plot or the panel subscribed without a listener";
  EXPECT_EQ(stm_pub.getNumSubscribers(), 0u);

  TopicProbe<sensor_msgs::Image> panel(nh, "monitor/panel", 5);
  ASSERT_TRUE(waitFor([&] { return stm_pub.getNumSubscribers() > 0; }, 15.0)) << "the panel did not subscribe";
  ASSERT_TRUE(waitFor([&] { return head_pub.getNumSubscribers() == 1; }, 15.0));
  TopicProbe<sensor_msgs::Image> plot(nh, "monitor/head_attractor", 5);
  ASSERT_TRUE(waitFor([&] { return head_pub.getNumSubscribers() == 2; }, 15.0)) << "the plot did not subscribe";

  biovision_msgs::EgoMap stm;
  stm.section_width = float(M_PI / 9);
  for (int i = 0; i < 9; ++i)
  {
    stm.section_angles.push_back(float((-80 + 20 * i) * M_PI / 180));
    stm.obstacle_distance.push_back(i == 4 ? 1.0f : INFINITY);
    stm.confidence.push_back(1.0f);
  }
  stm.max_range = 2.0f;
  const size_t before = panel.count();
  ASSERT_TRUE(waitFor(
      [&] {
        head_pub.publish(headState());
        stm_pub.publish(stm);
        return plot.count() > 0 && panel.count() > before + 3;
      },
      20.0));
  const auto p = plot.last();
  EXPECT_EQ(p->width, 320u);
  EXPECT_EQ(p->height, 240u);
  EXPECT_EQ(p->encoding, "bgr8");
  EXPECT_GT(spread(*p, 40, 30, 260, 180), 100);

  const auto m = panel.last();
  ASSERT_EQ(m->width, 4u * 320 + 3 * 2);
  ASSERT_EQ(m->height, 2u * 240 + 2);
  // Tiles 6 (head attractor) and 7 (STM) hold plots: white backgrounds with curves; tile 0 (no left
  // image) is the dark "no data" tile: uniform below the title except its text.
  auto tile = [&](int i, int x, int y) {
    return &m->data[size_t((i / 4) * 242 + y) * m->step + size_t((i % 4) * 322 + x) * 3];
  };
  EXPECT_GT(tile(6, 160, 120)[0], 200) << "head attractor tile background";
  EXPECT_GT(tile(7, 5, 30)[0], 200) << "STM tile background";
  EXPECT_LT(tile(0, 5, 30)[0], 100) << "left image tile: no data";
  EXPECT_GT(spread(*m, 6 * 0 + 40, 100, 240, 40), 100) << "the no-data tile has its text";

  // Bad input: a saliency map the converter refuses -> ERROR, panel keeps coming.
  diagnostics.clear();
  sensor_msgs::Image bad;
  bad.encoding = "rgb8";
  bad.width = 4;
  bad.height = 4;
  bad.step = 12;
  bad.data.assign(48, 0);
  ASSERT_TRUE(waitFor([&] { return saliency_pub.getNumSubscribers() > 0; }, 10.0));
  const size_t seen = panel.count();
  EXPECT_TRUE(waitFor(
      [&] {
        saliency_pub.publish(bad);
        return diagnostics.sawError();
      },
      20.0))
      << diagnostics.lastMessage();
  EXPECT_TRUE(panel.waitForCount(seen + 3, 10.0));
}

int main(int argc, char** argv)
{
  return biovision_ros_common::RosTestRun(argc, argv, "test_monitor_nodes", 2).run();
}
