// End to end in the simulator (issue 18: "the face in the simulator world is found and centred"): the
// sim renders test/greet_world.yaml; this test puts a person into it with sim/place_object — a standing
// figure (legs and torso 1.44 m, a 0.30 m head panel on top) whose head carries a real face photograph,
// an AT&T/ORL face from ../shared/data/hri (never trained on: the detector sees only Caltech WebFaces
// crops), read at test time and written to a temporary texture file. Then hri/greet: the node must find
// the face in the rendered left image and turn the head (pan and tilt, through the simulated servos) until
// the face is at the image centre, inside the joint limits; hri/stop_greet gives the head back.
//
// ~through (default "service"): "tasks" sends a `greet` task to biovision_tasks' task manager instead
// (greet_tasks_sim.test), which calls hri/greet; nobody shows a gesture, so the task fails at its time-out
// and the task manager's hri/stop_greet gives the head back.
//
// ~person (default "face"): "face" places the figure with the face; "none" places nothing and
// "blank" gives the head a procedural texture — both must make this test fail (how it was checked that
// it can fail: README, Tests).

#include <gtest/gtest.h>

#include <unistd.h>

#include <atomic>
#include <cmath>
#include <filesystem>
#include <iostream>
#include <memory>
#include <mutex>

#include <actionlib/client/simple_action_client.h>
#include <biovision_msgs/DetectionArray.h>
#include <biovision_msgs/ExecuteTaskAction.h>
#include <biovision_msgs/PlaceObject.h>
#include <biovision_msgs/SetHeadMode.h>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>
#include <ros/ros.h>
#include <sensor_msgs/JointState.h>
#include <std_msgs/Float64.h>
#include <std_srvs/Trigger.h>

#include "biovision_ros_common/rostest_helpers.hpp"

namespace fs = std::filesystem;
using biovision_ros_common::TopicProbe;
using biovision_ros_common::waitFor;

namespace
{
constexpr double kPanMin = -1.5708, kPanMax = 1.5708, kTiltMin = -0.7854, kTiltMax = 0.7854;  // URDF
// The person: 1.6 m in front of the robot's start, 0.3 m to its left (bearing ≈ 0.19 rad from the left
// camera), the face centre ≈ 1.57 m above the floor (the camera is ≈ 1.1 m high).
constexpr double kPersonX = 1.6, kPersonY = 0.3, kHeadSide = 0.30, kBodyHeight = 1.44;
// Centred: the face box centre within this many pixels of the 320x240 image centre (≈ 0.06 rad at the
// sim's 43° field of view; the behaviour stops correcting below `centred_tolerance` 0.05 rad).
constexpr double kCentreTolerancePx = 24.0;
// [s] the greet task's time-out (through the tasks): after the face search (hri's 8 s) and centring (~5 s),
// before hri's own gesture wait (15 s) would end the greeting by itself.
constexpr double kGreetTaskTimeout = 20.0;
using TaskClient = actionlib::SimpleActionClient<biovision_msgs::ExecuteTaskAction>;

std::string sharedRoot()
{
  const char* env = std::getenv("BIOVISION_SHARED");
  return env ? env : BIOVISION_DEFAULT_SHARED;
}

/// The head texture: an ORL face (92x112 grey, dark plain background) centred on a square canvas of its
/// height, the sides filled by replicating its border (the texture is mapped square). Returns the path.
std::string writeFaceTexture()
{
  const std::string source = sharedRoot() + "/data/hri/faces/att-orl/s7/1.pgm";
  const cv::Mat face = cv::imread(source, cv::IMREAD_COLOR);
  if (face.empty())
    return "";
  cv::Mat square;
  const int pad = face.rows - face.cols;
  cv::copyMakeBorder(face, square, 0, 0, pad / 2, pad - pad / 2, cv::BORDER_REPLICATE);
  const std::string path =
      (fs::temp_directory_path() / ("biovision_greet_face_" + std::to_string(::getpid()) + ".png")).string();
  return cv::imwrite(path, square) ? path : "";
}

bool place(const std::string& yaml)
{
  biovision_msgs::PlaceObject srv;
  srv.request.object = yaml;
  const bool ok = ros::service::call("sim/place_object", srv) && srv.response.success;
  EXPECT_TRUE(ok) << yaml << ": " << srv.response.message;
  return ok;
}

std::string fmt(double v)
{
  return std::to_string(v);
}

class GreetSim : public testing::Test
{
protected:
  void SetUp() override
  {
    ros::NodeHandle("~").param<std::string>("person", person_, "face");
    joints_ = nh_.subscribe<sensor_msgs::JointState>(
        "joint_states", 10, [this](const sensor_msgs::JointStateConstPtr& m) {
          std::lock_guard<std::mutex> lock(mutex_);
          for (size_t i = 0; i < m->name.size() && i < m->position.size(); ++i)
          {
            if (m->name[i] == "head_pan_joint")
              pan_ = m->position[i];
            if (m->name[i] == "head_tilt_joint")
              tilt_ = m->position[i];
          }
          ++joint_messages_;
        });
  }
  void TearDown() override
  {
    joints_.shutdown();  // main's spinner runs on: no callback into this fixture once it is destroyed
    if (!texture_.empty())
      fs::remove(texture_);
  }

  void placePerson()
  {
    if (person_ == "none")
      return;
    std::string head_texture =
        "{type: noise, colour: [200, 170, 150], colour_b: [120, 90, 70], period: 0.3, "
        "feature: 0.05, seed: 5}";
    if (person_ == "face")
    {
      texture_ = writeFaceTexture();
      ASSERT_FALSE(texture_.empty()) << "cannot read the ORL face from " << sharedRoot()
                                     << "/data/hri (BIOVISION_SHARED)";
      head_texture = "{type: image, file: '" + texture_ + "', period: " + fmt(kHeadSide) + "}";
    }
    // Legs and torso (dark clothes), then the head panel standing on them, its face towards the robot
    // (a box's -x side shows the texture upright and unmirrored from the robot's start).
    ASSERT_TRUE(place("{label: person_body, shape: box, position: [" + fmt(kPersonX) + ", " + fmt(kPersonY) + ", " +
                      fmt(kBodyHeight / 2) + "], size: [0.22, 0.44, " + fmt(kBodyHeight) +
                      "], texture: {type: noise, colour: [40, 50, 90], colour_b: [20, 25, 50], period: 0.5, "
                      "feature: 0.04, seed: 3}}"));
    ASSERT_TRUE(place("{label: person_head, shape: box, obstacle: false, position: [" + fmt(kPersonX) + ", " +
                      fmt(kPersonY) + ", " + fmt(kBodyHeight + kHeadSide / 2) + "], size: [0.04, " + fmt(kHeadSide) +
                      ", " + fmt(kHeadSide) + "], texture: " + head_texture + "}"));
  }

  std::pair<double, double> joints()
  {
    std::lock_guard<std::mutex> lock(mutex_);
    return {pan_, tilt_};
  }

  ros::NodeHandle nh_;
  ros::Subscriber joints_;
  std::mutex mutex_;
  double pan_ = NAN, tilt_ = NAN;
  std::atomic<unsigned> joint_messages_{0};
  std::string person_, texture_;
};

TEST_F(GreetSim, TheFaceOfThePersonIsFoundAndCentredAndStopGivesTheHeadBack)
{
  ASSERT_TRUE(ros::service::waitForService("sim/place_object", ros::Duration(30.0)));
  ASSERT_TRUE(ros::service::waitForService("hri/greet", ros::Duration(30.0)));
  // A stand-in for the head controller's mode service (no attractor here): the behaviour must hold the
  // head when it starts and give it back ("explore") when stopped.
  std::string through;
  ros::NodeHandle("~").param<std::string>("through", through, "service");
  std::vector<std::string> modes;
  std::mutex modes_mutex;
  ros::ServiceServer mode_srv =
      nh_.advertiseService<biovision_msgs::SetHeadMode::Request, biovision_msgs::SetHeadMode::Response>(
          "head/set_mode", [&](biovision_msgs::SetHeadMode::Request& req, biovision_msgs::SetHeadMode::Response& res) {
            std::lock_guard<std::mutex> lock(modes_mutex);
            modes.push_back(req.mode);
            res.success = true;
            return true;
          });
  placePerson();
  TopicProbe<biovision_msgs::DetectionArray> faces(nh_, "hri/faces");
  TopicProbe<std_msgs::Float64> pan_cmd(nh_, "head_pan_joint/command");
  TopicProbe<std_msgs::Float64> tilt_cmd(nh_, "head_tilt_joint/command");
  ASSERT_TRUE(waitFor([&] { return joint_messages_ > 5 && faces.count() > 2; }, 30.0)) << "sim and hri running";
  const auto [pan0, tilt0] = joints();
  EXPECT_NEAR(pan0, 0.0, 0.01) << "the head starts straight ahead";

  std_srvs::Trigger trigger;
  std::unique_ptr<TaskClient> tasks;
  if (through == "tasks")
  {
    tasks = std::make_unique<TaskClient>(nh_, "tasks/execute", false);
    ASSERT_TRUE(tasks->waitForServer(ros::Duration(30.0)));
    biovision_msgs::ExecuteTaskGoal greet;
    greet.task = "greet";
    greet.arguments = {"timeout=" + std::to_string(int(kGreetTaskTimeout))};
    tasks->sendGoal(greet);
  }
  else
  {
    ASSERT_TRUE(ros::service::call("hri/greet", trigger));
    ASSERT_TRUE(trigger.response.success) << trigger.response.message;
  }

  // Found and centred: a face on hri/faces whose box centre is within tolerance of the image centre while
  // the head points at the person (pan turned left towards its bearing, tilt up).
  double dx = NAN, dy = NAN, score = NAN;
  const bool centred = waitFor(
      [&] {
        const auto m = faces.last();
        if (!m || m->detections.empty())
          return false;
        const auto& b = m->detections.front().box;  // strongest first
        dx = b.x_offset + b.width / 2.0 - 160.0;
        dy = b.y_offset + b.height / 2.0 - 120.0;
        score = m->detections.front().score;
        const auto [pan, tilt] = joints();
        return std::hypot(dx, dy) < kCentreTolerancePx && pan > 0.08 && tilt < -0.1;
      },
      60.0);
  const auto [pan, tilt] = joints();
  ASSERT_TRUE(centred) << "person '" << person_ << "': last face offset (" << dx << ", " << dy << ") px, score "
                       << score << "; head pan " << pan << " tilt " << tilt << " rad; " << faces.count()
                       << " hri/faces messages, " << pan_cmd.count() << " pan commands";
  std::cout << "greet_sim: person '" << person_ << "': face centred at offset (" << dx << ", " << dy << ") px, score "
            << score << "; head pan " << pan << " tilt " << tilt << " rad" << std::endl;
  // The bearing of the person from the left camera is ≈ 0.19 rad: the pan must have turned by about that,
  // less what "centred" leaves open — 24 px ≈ 0.06 rad here and the behaviour's 0.05 rad dead band — so
  // 0.08, the bound the wait above uses (a run here centred the face at 0.094 rad and failed a 0.1 bound).
  EXPECT_GT(pan, 0.08);
  EXPECT_LT(pan, 0.35);
  EXPECT_GE(pan, kPanMin);
  EXPECT_LE(pan, kPanMax);
  EXPECT_GE(tilt, kTiltMin);
  EXPECT_LE(tilt, kTiltMax);
  EXPECT_GT(pan_cmd.count(), 0u);
  for (const auto& c : pan_cmd.messages())
    EXPECT_TRUE(c->data >= kPanMin && c->data <= kPanMax) << c->data;
  for (const auto& c : tilt_cmd.messages())
    EXPECT_TRUE(c->data >= kTiltMin && c->data <= kTiltMax) << c->data;
  {
    std::lock_guard<std::mutex> lock(modes_mutex);
    ASSERT_FALSE(modes.empty());
    EXPECT_EQ(modes.front(), "hold");
  }

  // Stop: the head is given back to the head controller and hri commands it no more. Through the tasks:
  // the greet fails at its time-out (no gesture) and the task manager calls hri/stop_greet.
  if (tasks)
  {
    ASSERT_TRUE(tasks->waitForResult(ros::Duration(kGreetTaskTimeout + 15.0))) << "the greet task never ended";
    EXPECT_EQ(tasks->getState(), actionlib::SimpleClientGoalState::ABORTED);
    EXPECT_NE(tasks->getResult()->message.find("no gesture read"), std::string::npos) << tasks->getResult()->message;
  }
  else
  {
    ASSERT_TRUE(ros::service::call("hri/stop_greet", trigger));
    EXPECT_TRUE(trigger.response.success) << trigger.response.message;
  }
  EXPECT_TRUE(waitFor(
      [&] {
        std::lock_guard<std::mutex> lock(modes_mutex);
        return modes.size() >= 2 && modes.back() == "explore";
      },
      5.0));
  ros::WallDuration(0.5).sleep();
  const size_t after_stop = pan_cmd.count() + tilt_cmd.count();
  ros::WallDuration(1.5).sleep();
  EXPECT_EQ(pan_cmd.count() + tilt_cmd.count(), after_stop) << "no head commands after hri/stop_greet";
}
}  // namespace

int main(int argc, char** argv)
{
  return biovision_ros_common::RosTestRun(argc, argv, "greet_sim_test", 2).run();
}
