#include <gtest/gtest.h>

#include "biovision_hri/greet_behaviour.hpp"

using namespace biovision_hri;

namespace
{
GreetBehaviour::Parameters parameters()
{
  GreetBehaviour::Parameters p;
  p.actions = {{"palm", "stop"}, {"index_up", "follow"}};
  return p;
}
const cv::Size kImage(320, 240);
cv::Rect2f faceAt(float cx, float cy)
{
  return cv::Rect2f(cx - 20, cy - 20, 40, 40);
}
}  // namespace

TEST(GreetBehaviour, LooksUpCentresTheFaceAndRunsTheGesturesAction)
{
  GreetBehaviour b(parameters());
  EXPECT_FALSE(b.update(0.0, kImage, {}, {}, 0.0, 0.3).head_active) << "idle: the head is not taken";
  b.start(0.0, 0.1, 0.3);
  auto out = b.update(0.1, kImage, {}, {}, 0.1, 0.3);
  EXPECT_EQ(b.state(), GreetBehaviour::State::LookUp);
  EXPECT_TRUE(out.head_active);
  EXPECT_DOUBLE_EQ(out.tilt, -0.35) << "looks up (tilt + = down)";
  EXPECT_DOUBLE_EQ(out.pan, 0.1);

  // A face right of and above the centre: pan decreases (right), tilt decreases (up).
  out = b.update(0.2, kImage, {faceAt(260, 60)}, {}, 0.1, -0.35);
  EXPECT_EQ(b.state(), GreetBehaviour::State::Centre);
  EXPECT_LT(out.pan, 0.1);
  EXPECT_LT(out.tilt, -0.35);
  // Centred: reads gestures; an unknown gesture does nothing, a known one gives its action once.
  out = b.update(0.3, kImage, {faceAt(160, 120)}, {"fist"}, 0.0, -0.4);
  EXPECT_EQ(b.state(), GreetBehaviour::State::ReadGesture);
  EXPECT_TRUE(out.action.empty());
  out = b.update(0.4, kImage, {faceAt(161, 120)}, {"palm"}, 0.0, -0.4);
  EXPECT_EQ(out.action, "stop");
  EXPECT_EQ(out.gesture, "palm");
  EXPECT_TRUE(out.finished);
  EXPECT_EQ(b.state(), GreetBehaviour::State::Idle);
}

TEST(GreetBehaviour, GivesUpWithoutAFaceAndWhenTheFaceIsLost)
{
  GreetBehaviour b(parameters());
  b.start(10.0, 0.0, 0.0);
  EXPECT_FALSE(b.update(17.9, kImage, {}, {}, 0.0, -0.35).finished);
  auto out = b.update(18.1, kImage, {}, {}, 0.0, -0.35);
  EXPECT_TRUE(out.finished);
  EXPECT_EQ(out.reason, "no face");

  b.start(20.0, 0.0, 0.0);
  b.update(20.5, kImage, {faceAt(200, 100)}, {}, 0.0, -0.35);
  EXPECT_FALSE(b.update(22.4, kImage, {}, {}, 0.0, -0.35).finished);
  out = b.update(22.6, kImage, {}, {}, 0.0, -0.35);
  EXPECT_TRUE(out.finished);
  EXPECT_EQ(out.reason, "face lost");

  b.start(30.0, 0.0, 0.0);
  out = b.update(29.0, kImage, {}, {}, 0.0, 0.0);
  EXPECT_TRUE(out.finished) << "a backward time jump ends the behaviour";
}

TEST(GreetBehaviour, CommandsStayInsideTheJointLimits)
{
  GreetBehaviour::Parameters p = parameters();
  p.centre_gain = 1.0;
  GreetBehaviour b(p);
  b.start(0.0, 1.55, 0.0);
  // The face at the left edge while the head is already at the pan limit; at the top while looking up.
  const auto out = b.update(0.1, kImage, {faceAt(5, 5)}, {}, 1.56, -0.78);
  EXPECT_LE(out.pan, p.pan_max);
  EXPECT_GE(out.tilt, p.tilt_min);
  p.look_up_tilt = -2.0;
  EXPECT_THROW(b.setParameters(p), std::invalid_argument);
}
