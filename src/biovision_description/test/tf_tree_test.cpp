// Checks the published tf tree of the robot model: both optical frames resolve from base_link,
// they are one baseline apart, the cameras sit at mast height, and the tree follows the pan joint.
#include <cmath>

#include <biovision_ros_common/rostest_helpers.hpp>
#include <gtest/gtest.h>
#include <ros/ros.h>
#include <sensor_msgs/JointState.h>
#include <tf2_ros/transform_listener.h>
#include <urdf/model.h>

namespace
{
constexpr double kBaseline = 0.12;

class TfTreeTest : public ::testing::Test
{
protected:
  TfTreeTest() : listener_(buffer_) { joints_pub_ = nh_.advertise<sensor_msgs::JointState>("joint_states", 10, true); }

  void publishHead(double pan, double tilt)
  {
    sensor_msgs::JointState js;
    js.header.stamp = ros::Time::now();
    js.name = {"head_pan_joint", "head_tilt_joint", "left_wheel_joint", "right_wheel_joint"};
    js.position = {pan, tilt, 0.0, 0.0};
    joints_pub_.publish(js);
  }

  // Publishes the head pose until the tree shows it (robot_state_publisher may start after us).
  geometry_msgs::TransformStamped waitForHead(double pan, double tilt, const std::string& frame)
  {
    const ros::WallTime deadline = ros::WallTime::now() + ros::WallDuration(20.0);
    geometry_msgs::TransformStamped last;
    while (ros::ok() && ros::WallTime::now() < deadline)
    {
      publishHead(pan, tilt);
      ros::WallDuration(0.05).sleep();
      try
      {
        last = buffer_.lookupTransform("base_link", frame, ros::Time(0));
        const auto& q = last.transform.rotation;
        // Optical z axis expressed in base_link: third column of the rotation matrix.
        const double zx = 2 * (q.x * q.z + q.w * q.y);
        const double zy = 2 * (q.y * q.z - q.w * q.x);
        const double zz = 1 - 2 * (q.x * q.x + q.y * q.y);
        const double yaw = std::atan2(zy, zx);
        const double pitch_down = std::asin(-zz);
        if (std::abs(yaw - pan) < 1e-3 && std::abs(pitch_down - tilt) < 1e-3)
          return last;
      }
      catch (const tf2::TransformException&)
      {
      }
    }
    ADD_FAILURE() << "tf tree never showed pan=" << pan << " tilt=" << tilt << " for " << frame;
    return last;
  }

  ros::NodeHandle nh_;
  ros::Publisher joints_pub_;
  tf2_ros::Buffer buffer_;
  tf2_ros::TransformListener listener_;
};

TEST_F(TfTreeTest, RobotDescriptionHasTurretLimits)
{
  urdf::Model model;
  ASSERT_TRUE(model.initParam("robot_description"));
  auto pan = model.getJoint("head_pan_joint");
  ASSERT_TRUE(pan);
  EXPECT_NEAR(pan->limits->lower, -M_PI / 2, 1e-3);
  EXPECT_NEAR(pan->limits->upper, M_PI / 2, 1e-3);
  ASSERT_TRUE(model.getJoint("head_tilt_joint"));
  ASSERT_TRUE(model.getLink("stereo_left_optical"));
  ASSERT_TRUE(model.getLink("stereo_right_optical"));
}

TEST_F(TfTreeTest, OpticalFramesResolveAndFollowPan)
{
  for (double pan : {0.0, 0.5, -1.2})
  {
    const auto left = waitForHead(pan, 0.0, "stereo_left_optical");
    const auto right = waitForHead(pan, 0.0, "stereo_right_optical");
    const auto& l = left.transform.translation;
    const auto& r = right.transform.translation;
    EXPECT_NEAR(std::hypot(l.x - r.x, l.y - r.y, l.z - r.z), kBaseline, 1e-6);
    EXPECT_NEAR(l.z, 1.10, 0.05) << "cameras should sit at child height";
    // The right camera is to the right of the left one, i.e. at pan + (-90 deg) from it.
    EXPECT_NEAR(std::atan2(r.y - l.y, r.x - l.x), pan - M_PI / 2, 1e-3);
  }
}

TEST_F(TfTreeTest, OpticalFrameFollowsTilt)
{
  waitForHead(0.3, 0.4, "stereo_left_optical");
}

TEST_F(TfTreeTest, RightOpticalIsPlusXOfLeft)
{
  waitForHead(0.0, 0.0, "stereo_right_optical");
  const auto t = buffer_.lookupTransform("stereo_left_optical", "stereo_right_optical", ros::Time(0),
                                         ros::Duration(5.0));
  EXPECT_NEAR(t.transform.translation.x, kBaseline, 1e-6);
  EXPECT_NEAR(t.transform.translation.y, 0.0, 1e-6);
  EXPECT_NEAR(t.transform.translation.z, 0.0, 1e-6);
}
}  // namespace

int main(int argc, char** argv)
{
  return biovision_ros_common::RosTestRun(argc, argv, "tf_tree_test", 1).run();
}
