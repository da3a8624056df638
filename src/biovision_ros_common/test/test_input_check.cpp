#include <gtest/gtest.h>

#include <limits>

#include "biovision_ros_common/input_check.hpp"

using biovision_ros_common::InputCheck;
using biovision_ros_common::InputError;

namespace
{
sensor_msgs::CameraInfo calibration(double fx = 100, double cx = 80, double cy = 60)
{
  sensor_msgs::CameraInfo info;
  info.width = 160;
  info.height = 120;
  info.P = {fx, 0, cx, 0, 0, fx, cy, 0, 0, 0, 1, 0};
  return info;
}

std::string problemOf(const sensor_msgs::CameraInfo& info)
{
  try
  {
    InputCheck::cameraInfo(info, 160, 120);
  }
  catch (const InputError& e)
  {
    return e.what();
  }
  return "";
}
}  // namespace

TEST(InputCheck, CameraInfoRefusesEachKindOfBadCalibrationNamingIt)
{
  EXPECT_EQ(problemOf(calibration()), "");
  const double nan = std::numeric_limits<double>::quiet_NaN(), inf = std::numeric_limits<double>::infinity();
  EXPECT_NE(problemOf(calibration(0)).find("uncalibrated"), std::string::npos);
  EXPECT_NE(problemOf(calibration(nan)).find("P[0]"), std::string::npos);
  EXPECT_NE(problemOf(calibration(inf)).find("P[0]"), std::string::npos);
  EXPECT_NE(problemOf(calibration(1e-9)).find("fx"), std::string::npos);
  EXPECT_NE(problemOf(calibration(1e9)).find("fx"), std::string::npos);
  EXPECT_NE(problemOf(calibration(-100)).find("fx"), std::string::npos);
  EXPECT_NE(problemOf(calibration(100, nan)).find("P[2]"), std::string::npos);
  EXPECT_NE(problemOf(calibration(100, 1e6)).find("principal point"), std::string::npos);
  sensor_msgs::CameraInfo zero_width = calibration();
  zero_width.width = 0;
  EXPECT_NE(problemOf(zero_width).find("zero width"), std::string::npos);
  sensor_msgs::CameraInfo other_size = calibration();
  other_size.width = 320;
  other_size.P[2] = 160;
  EXPECT_NE(problemOf(other_size).find("does not match"), std::string::npos);
}

TEST(InputCheck, JointPositionsRefuseMismatchedNonFiniteAndHugeValues)
{
  sensor_msgs::JointState js;
  js.name = {"pan", "tilt", "wheel"};
  js.position = {0.3, -0.2, 1e30};  // an unwanted joint may hold anything
  auto found = InputCheck::jointPositions(js, {"pan", "tilt"});
  EXPECT_EQ(found.size(), 2u);
  EXPECT_DOUBLE_EQ(found["pan"], 0.3);
  js.position = {1e30, 0, 0};
  EXPECT_THROW(InputCheck::jointPositions(js, {"pan", "tilt"}), InputError);
  js.position = {0, std::numeric_limits<double>::quiet_NaN(), 0};
  EXPECT_THROW(InputCheck::jointPositions(js, {"pan", "tilt"}), InputError);
  js.position = {0, 0};
  EXPECT_THROW(InputCheck::jointPositions(js, {"pan"}), InputError);
  js.position.clear();  // no positions at all (a velocity-only publisher): nothing found, no error
  EXPECT_TRUE(InputCheck::jointPositions(js, {"pan"}).empty());
}
