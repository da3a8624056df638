// Integration with a real roscore: a held-out face (test part of the Caltech WebFaces crops, never
// trained on) pasted into a held-out scene (test part of the negatives) is found by the node and sent on
// hri/faces; the subscription is lazy; bad input gives an ERROR diagnostic and no output, and the node
// keeps working; hri/greet looks up and turns the head towards the face, inside the joint limits.

#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>

#include <biovision_msgs/DetectionArray.h>
#include <biovision_msgs/GestureArray.h>
#include <biovision_msgs/SetHeadMode.h>
#include <cv_bridge/cv_bridge.h>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>
#include <ros/ros.h>
#include <sensor_msgs/JointState.h>
#include <std_msgs/Float64.h>
#include <std_srvs/Trigger.h>

#include "biovision_ros_common/rostest_helpers.hpp"

namespace fs = std::filesystem;
using biovision_ros_common::DiagnosticsWatch;
using biovision_ros_common::TopicProbe;
using biovision_ros_common::waitFor;

namespace
{
std::string hri(const std::string& rest)
{
  const char* env = std::getenv("BIOVISION_SHARED");
  return std::string(env ? env : BIOVISION_DEFAULT_SHARED) + "/data/hri/" + rest;
}

/// The n-th file of a folder in name order counted from the end: the test part (last 30%) of the
/// contiguous splits the tools use.
std::string fromTestPart(const std::string& folder, size_t from_end)
{
  std::vector<std::string> files;
  for (const auto& e : fs::directory_iterator(hri(folder)))
    files.push_back(e.path().string());
  std::sort(files.begin(), files.end());
  EXPECT_GT(files.size(), 10 * from_end) << hri(folder);
  return files.empty() ? "" : files[files.size() - 1 - from_end];
}

/// A 320x240 scene of the test part with a test-part face crop pasted at `where`.
cv::Mat faceScene(const cv::Rect& where)
{
  const cv::Mat scene = cv::imread(fromTestPart("negatives/scenes", 2), cv::IMREAD_COLOR);
  const cv::Mat face = cv::imread(fromTestPart("faces/caltech-webfaces-36x36/Caltech_CropFaces", 5), cv::IMREAD_COLOR);
  EXPECT_FALSE(scene.empty());
  EXPECT_FALSE(face.empty());
  cv::Mat out, resized;
  cv::resize(scene, out, cv::Size(320, 240), 0, 0, cv::INTER_AREA);
  cv::resize(face, resized, where.size(), 0, 0, cv::INTER_LINEAR);
  resized.copyTo(out(where));
  return out;
}

double iou(const sensor_msgs::RegionOfInterest& r, const cv::Rect& b)
{
  const cv::Rect a(r.x_offset, r.y_offset, r.width, r.height);
  const double inter = (a & b).area();
  return inter / (a.area() + b.area() - inter);
}

class HriNode : public testing::Test
{
protected:
  void SetUp() override
  {
    image_pub_ = nh_.advertise<sensor_msgs::Image>("camera/image", 2);
    joints_pub_ = nh_.advertise<sensor_msgs::JointState>("joint_states", 2);
  }

  sensor_msgs::ImagePtr message(const cv::Mat& image, const std::string& encoding = "bgr8")
  {
    std_msgs::Header header;
    header.stamp = ros::Time::now();
    header.frame_id = "left_camera_optical_frame";
    return cv_bridge::CvImage(header, encoding, image).toImageMsg();
  }

  /// Publishes until the probe has one more message than before (or the time is up).
  bool showUntil(const sensor_msgs::ImagePtr& msg, TopicProbe<biovision_msgs::DetectionArray>& probe, double seconds)
  {
    const size_t before = probe.count();
    return waitFor(
        [&] {
          msg->header.stamp = ros::Time::now();
          image_pub_.publish(msg);
          ros::WallDuration(0.2).sleep();
          return probe.count() > before;
        },
        seconds);
  }

  ros::NodeHandle nh_;
  ros::Publisher image_pub_, joints_pub_;
};

TEST_F(HriNode, FindsAHeldOutFaceAndSendsItOnHriFaces)
{
  ASSERT_TRUE(waitFor([&] { return image_pub_.getNumSubscribers() == 0; }, 5.0));
  TopicProbe<biovision_msgs::DetectionArray> faces(nh_, "hri/faces");
  TopicProbe<biovision_msgs::DetectionArray> hands(nh_, "hri/hands");
  ASSERT_TRUE(waitFor([&] { return image_pub_.getNumSubscribers() > 0; }, 20.0)) << "lazy: subscribes on demand";

  const cv::Rect where(150, 60, 84, 84);
  ASSERT_TRUE(showUntil(message(faceScene(where)), faces, 30.0));
  const auto msg = faces.last();
  ASSERT_FALSE(msg->detections.empty()) << "no face found";
  double best = 0;
  for (const auto& d : msg->detections)
  {
    EXPECT_EQ(d.kind, "face");
    best = std::max(best, iou(d.box, where));
  }
  EXPECT_GT(best, 0.4) << "best overlap with the pasted face";
  EXPECT_TRUE(hands.waitForCount(1, 5.0)) << "hri/hands is published for the same image";
}

TEST_F(HriNode, BadInputGivesAnErrorAndNoOutputAndTheNodeKeepsWorking)
{
  TopicProbe<biovision_msgs::DetectionArray> faces(nh_, "hri/faces");
  DiagnosticsWatch diagnostics(nh_, "HRI");
  ASSERT_TRUE(waitFor([&] { return image_pub_.getNumSubscribers() > 0; }, 20.0));
  ASSERT_TRUE(showUntil(message(faceScene(cv::Rect(150, 60, 84, 84))), faces, 30.0));

  // Outputs carry their image's stamp: an answer to a bad image is told apart by it, since good images
  // showUntil() left queued or in progress may still be answered meanwhile.
  const ros::Time bad_from = ros::Time::now();
  cv::Mat wrong(240, 320, CV_32SC1, cv::Scalar(7));
  for (int i = 0; i < 5; ++i)
  {
    image_pub_.publish(message(wrong, "32SC1"));
    ros::WallDuration(0.1).sleep();
  }
  EXPECT_TRUE(waitFor([&] { return diagnostics.sawError(); }, 5.0)) << "an ERROR diagnostic";
  ros::WallDuration(1.0).sleep();  // an answer still in progress would come out now
  for (const auto& m : faces.messages())
    EXPECT_LT(m->header.stamp, bad_from) << "nothing published for bad input";
  EXPECT_TRUE(showUntil(message(faceScene(cv::Rect(150, 60, 84, 84))), faces, 30.0)) << "still working";
}

TEST_F(HriNode, GreetLooksUpAndTurnsTowardsTheFaceWithinTheLimits)
{
  TopicProbe<biovision_msgs::DetectionArray> faces(nh_, "hri/faces");
  TopicProbe<std_msgs::Float64> pan(nh_, "head_pan_joint/command");
  TopicProbe<std_msgs::Float64> tilt(nh_, "head_tilt_joint/command");
  // A stand-in for the head controller's mode service: the behaviour holds it, then gives it back.
  std::vector<std::string> modes;
  ros::ServiceServer mode_srv =
      nh_.advertiseService<biovision_msgs::SetHeadMode::Request, biovision_msgs::SetHeadMode::Response>(
          "head/set_mode", [&](biovision_msgs::SetHeadMode::Request& req, biovision_msgs::SetHeadMode::Response& res) {
            modes.push_back(req.mode);
            res.success = true;
            return true;
          });
  ASSERT_TRUE(waitFor([&] { return image_pub_.getNumSubscribers() > 0; }, 20.0));
  sensor_msgs::JointState js;
  js.name = {"head_pan_joint", "head_tilt_joint"};
  js.position = {0.0, 0.3};
  joints_pub_.publish(js);
  ros::WallDuration(0.3).sleep();
  joints_pub_.publish(js);

  std_srvs::Trigger trigger;
  ASSERT_TRUE(ros::service::call("hri/greet", trigger));
  EXPECT_TRUE(trigger.response.success);
  // The face right of the centre: the head must turn right (pan command below the current 0).
  const cv::Rect where(210, 80, 84, 84);
  ASSERT_TRUE(showUntil(message(faceScene(where)), faces, 30.0));
  ASSERT_TRUE(pan.waitForCount(1, 10.0)) << "no pan command";
  ASSERT_TRUE(tilt.waitForCount(1, 10.0));
  EXPECT_LT(pan.last()->data, 0.0) << "turns right towards the face";
  EXPECT_GE(pan.last()->data, -1.5708);
  EXPECT_GE(tilt.last()->data, -0.7854);
  EXPECT_LE(tilt.last()->data, 0.7854);
  EXPECT_TRUE(waitFor([&] { return !modes.empty(); }, 5.0));
  EXPECT_EQ(modes.front(), "hold");
  ASSERT_TRUE(ros::service::call("hri/stop_greet", trigger));
  EXPECT_TRUE(waitFor([&] { return modes.size() >= 2; }, 5.0));
  EXPECT_EQ(modes.back(), "explore");
}

TEST_F(HriNode, AGreetingSubscribesTheImageThoughNobodyListensAndLetsItGoWhenStopped)
{
  ASSERT_TRUE(waitFor([&] { return image_pub_.getNumSubscribers() == 0; }, 5.0)) << "lazy: nobody listens";
  TopicProbe<std_msgs::Float64> tilt(nh_, "head_tilt_joint/command");  // not a lazy output
  std_srvs::Trigger trigger;
  ASSERT_TRUE(ros::service::call("hri/greet", trigger));
  EXPECT_TRUE(trigger.response.success) << trigger.response.message;
  ASSERT_TRUE(waitFor([&] { return image_pub_.getNumSubscribers() > 0; }, 5.0))
      << "the greeting needs the images: " << trigger.response.message;
  sensor_msgs::JointState js;
  js.name = {"head_pan_joint", "head_tilt_joint"};
  js.position = {0.0, 0.3};
  const auto image = message(faceScene(cv::Rect(120, 80, 84, 84)));
  // The behaviour runs on the images alone: it looks up (tilt commands) with no hri/* subscriber.
  EXPECT_TRUE(waitFor(
      [&] {
        joints_pub_.publish(js);
        image->header.stamp = ros::Time::now();
        image_pub_.publish(image);
        ros::WallDuration(0.2).sleep();
        return tilt.count() > 0;
      },
      20.0))
      << "no tilt command while greeting";
  ASSERT_TRUE(ros::service::call("hri/stop_greet", trigger));
  EXPECT_TRUE(waitFor([&] { return image_pub_.getNumSubscribers() == 0; }, 5.0)) << "the images are let go";
}

TEST_F(HriNode, AGreetingOnImagesWhoseStampsStandStillIsGivenUp)
{
  // Stamps that never advance (0 from some drivers): the behaviour runs on image time, so it would hold
  // the head and keep the lazy node's images for good; it gives up after search_timeout (8 s) of wall time.
  ASSERT_TRUE(waitFor([&] { return image_pub_.getNumSubscribers() == 0; }, 5.0));
  std_srvs::Trigger trigger;
  ASSERT_TRUE(ros::service::call("hri/greet", trigger));
  ASSERT_TRUE(waitFor([&] { return image_pub_.getNumSubscribers() > 0; }, 5.0));
  const auto image = message(faceScene(cv::Rect(120, 80, 84, 84)));
  image->header.stamp = ros::Time(0);
  const ros::WallTime start = ros::WallTime::now();
  const bool let_go = waitFor(
      [&] {
        image_pub_.publish(image);
        ros::WallDuration(0.2).sleep();
        return image_pub_.getNumSubscribers() == 0;
      },
      15.0);
  EXPECT_TRUE(let_go) << "the greeting never ended";
  EXPECT_GT((ros::WallTime::now() - start).toSec(), 6.0) << "not before search_timeout";
}
}  // namespace

int main(int argc, char** argv)
{
  return biovision_ros_common::RosTestRun(argc, argv, "hri_node_test", 2).run();
}
