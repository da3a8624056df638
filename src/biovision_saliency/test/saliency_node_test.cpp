// Integration test of the saliency node: image + disparity in, regions out at the input rate; the
// near object wins; IoR reset service; bad input is reported and survived.
#include <atomic>
#include <mutex>

#include <biovision_msgs/SalientRegionArray.h>
#include <biovision_ros_common/rostest_helpers.hpp>
#include <cv_bridge/cv_bridge.h>
#include <diagnostic_msgs/DiagnosticArray.h>
#include <gtest/gtest.h>
#include <opencv2/imgproc.hpp>
#include <ros/ros.h>
#include <std_srvs/Trigger.h>
#include <stereo_msgs/DisparityImage.h>

namespace
{
class SaliencyNodeTest : public ::testing::Test
{
public:
  SaliencyNodeTest()
  {
    image_pub_ = nh_.advertise<sensor_msgs::Image>("camera/image", 5);
    disparity_pub_ = nh_.advertise<stereo_msgs::DisparityImage>("disparity", 5);
  }
  void onRegions(const biovision_msgs::SalientRegionArrayConstPtr& m)
  {
    std::lock_guard<std::mutex> lock(mutex_);
    last_ = m;
    ++received_;
  }
  void onDiagnostics(const diagnostic_msgs::DiagnosticArrayConstPtr& m)
  {
    for (const auto& s : m->status)
      if (s.name.find("Saliency") != std::string::npos && s.level == diagnostic_msgs::DiagnosticStatus::ERROR)
        saw_error_ = true;
  }

  // Two identical grey boxes; the disparity says the right one is near.
  void publishFrame(const ros::Time& stamp)
  {
    cv::Mat img(240, 320, CV_8UC3, cv::Scalar(120, 120, 120));
    cv::rectangle(img, cv::Rect(40, 80, 60, 60), cv::Scalar(90, 90, 90), cv::FILLED);
    cv::rectangle(img, cv::Rect(220, 80, 60, 60), cv::Scalar(90, 90, 90), cv::FILLED);
    std_msgs::Header h;
    h.stamp = stamp;
    h.frame_id = "stereo_left_optical";
    image_pub_.publish(cv_bridge::CvImage(h, "bgr8", img).toImageMsg());
    cv::Mat d(240, 320, CV_32F, cv::Scalar(3.f));
    d(cv::Rect(40, 80, 60, 60)).setTo(6.f);
    d(cv::Rect(220, 80, 60, 60)).setTo(30.f);
    stereo_msgs::DisparityImage dm;
    dm.header = h;
    dm.f = 300;
    dm.T = 0.12f;
    dm.min_disparity = 0;
    dm.max_disparity = 64;
    cv_bridge::CvImage(h, "32FC1", d).toImageMsg(dm.image);
    disparity_pub_.publish(dm);
  }

  ros::NodeHandle nh_;
  ros::Publisher image_pub_, disparity_pub_;
  std::mutex mutex_;
  biovision_msgs::SalientRegionArrayConstPtr last_;
  std::atomic<int> received_{0};
  std::atomic<bool> saw_error_{false};
};

TEST_F(SaliencyNodeTest, RegionsAtTheInputRateNearObjectFirst)
{
  ros::Subscriber sub = nh_.subscribe("saliency/regions", 10, &SaliencyNodeTest::onRegions,
                                      static_cast<SaliencyNodeTest*>(this));
  ros::Subscriber diag = nh_.subscribe("/diagnostics", 20, &SaliencyNodeTest::onDiagnostics,
                                       static_cast<SaliencyNodeTest*>(this));
  const ros::WallTime deadline = ros::WallTime::now() + ros::WallDuration(30);
  while (received_ == 0 && ros::WallTime::now() < deadline)
  {
    publishFrame(ros::Time::now());
    ros::WallDuration(0.1).sleep();
  }
  ASSERT_GT(received_.load(), 0) << "no saliency/regions";
  // Rate: 20 frames at 10 Hz must give (nearly) 20 region messages.
  const int before = received_;
  const ros::WallTime start = ros::WallTime::now();
  ros::Rate rate(10);
  for (int i = 0; i < 20; ++i)
  {
    publishFrame(ros::Time::now());
    rate.sleep();
  }
  ros::WallDuration(0.5).sleep();
  const double hz = (received_ - before) / (ros::WallTime::now() - start).toSec();
  EXPECT_GE(received_ - before, 18);
  EXPECT_GT(hz, 7.0);
  {
    std::lock_guard<std::mutex> lock(mutex_);
    ASSERT_FALSE(last_->regions.empty());
    EXPECT_EQ(last_->image_width, 320u);
    bool near_seen = false;
    for (const auto& r : last_->regions)
      near_seen |= r.box.x_offset <= 250 && r.box.x_offset + r.box.width >= 250;
    EXPECT_TRUE(near_seen) << "the near box is not among the regions";
  }
  // IoR reset service answers.
  std_srvs::Trigger srv;
  ASSERT_TRUE(ros::service::waitForService("saliency/reset_inhibition", ros::Duration(5)));
  EXPECT_TRUE(ros::service::call("saliency/reset_inhibition", srv));
  EXPECT_TRUE(srv.response.success);
  // Bad input: a frame whose data is shorter than step x height -> ERROR diagnostic; the node keeps
  // producing regions afterwards.
  std_msgs::Header h;
  h.stamp = ros::Time::now();
  sensor_msgs::ImagePtr truncated =
      cv_bridge::CvImage(h, "mono8", cv::Mat(240, 320, CV_8U, cv::Scalar(100))).toImageMsg();
  truncated->data.resize(truncated->data.size() / 2);
  image_pub_.publish(truncated);
  const ros::WallTime diag_deadline = ros::WallTime::now() + ros::WallDuration(15);
  while (!saw_error_ && ros::WallTime::now() < diag_deadline)
    ros::WallDuration(0.1).sleep();
  EXPECT_TRUE(saw_error_.load());
  const int after_bad = received_;
  for (int i = 0; i < 5; ++i)
  {
    publishFrame(ros::Time::now());
    ros::WallDuration(0.1).sleep();
  }
  ros::WallDuration(0.5).sleep();
  EXPECT_GT(received_.load(), after_bad);
}
}  // namespace

int main(int argc, char** argv)
{
  return biovision_ros_common::RosTestRun(argc, argv, "saliency_node_test", 2).run();
}
