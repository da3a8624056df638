// The monitoring view in rviz under Xvfb during a simulator run: rviz with biovision.rviz subscribes to the
// eight monitor/<plot> views, each view delivers a non-empty picture, the screenshot's image views are not
// the empty-display colour, and monitor/panel has eight tiles with data (none saying "no data on").
// With ~screenshot_dir set, the screenshot (rviz.png) and the last panel (panel.png) are written there.
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cstdlib>
#include <string>
#include <vector>

#include <XmlRpcValue.h>
#include <cv_bridge/cv_bridge.h>
#include <gtest/gtest.h>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>
#include <ros/master.h>
#include <ros/ros.h>
#include <sensor_msgs/Image.h>

#include "biovision_ros_common/rostest_helpers.hpp"

// Xlib last: its macros (None, Bool, Status) would break the headers above.
#include <X11/Xlib.h>
#include <X11/Xutil.h>
#undef None
#undef Bool
#undef Status

using biovision_ros_common::TopicProbe;
using biovision_ros_common::waitFor;

namespace
{
const std::vector<std::string> kPlots = {"left_image",     "saliency_map", "disparity",      "thresholded_saliency",
                                         "base_attractor", "ltm",          "head_attractor", "stm"};
constexpr int kWidth = 1600, kHeight = 1000;

pid_t spawn(const std::vector<std::string>& args, const std::string& display)
{
  const pid_t pid = fork();
  if (pid == 0)
  {
    if (!display.empty())
      setenv("DISPLAY", display.c_str(), 1);
    std::vector<char*> argv;
    for (const auto& a : args)
      argv.push_back(const_cast<char*>(a.c_str()));
    argv.push_back(nullptr);
    execvp(argv[0], argv.data());
    _exit(127);
  }
  return pid;
}

void stop(pid_t pid)
{
  if (pid <= 0)
    return;
  kill(pid, SIGTERM);
  for (int i = 0; i < 50; ++i)
  {
    if (waitpid(pid, nullptr, WNOHANG) == pid)
      return;
    usleep(100000);
  }
  kill(pid, SIGKILL);
  waitpid(pid, nullptr, 0);
}

// The nodes subscribed to `topic` (from the master's system state).
std::vector<std::string> subscribersOf(const std::string& topic)
{
  XmlRpc::XmlRpcValue args, result, payload;
  args[0] = ros::this_node::getName();
  std::vector<std::string> nodes;
  if (!ros::master::execute("getSystemState", args, result, payload, false))
    return nodes;
  XmlRpc::XmlRpcValue& subscribers = payload[1];
  for (int i = 0; i < subscribers.size(); ++i)
    if (std::string(subscribers[i][0]) == topic)
      for (int k = 0; k < subscribers[i][1].size(); ++k)
        nodes.push_back(std::string(subscribers[i][1][k]));
  return nodes;
}

cv::Mat screenshot(Display* display)
{
  const Window root = DefaultRootWindow(display);
  XImage* image = XGetImage(display, root, 0, 0, kWidth, kHeight, AllPlanes, ZPixmap);
  if (!image)
    return {};
  cv::Mat out(kHeight, kWidth, CV_8UC3);
  for (int y = 0; y < kHeight; ++y)
    for (int x = 0; x < kWidth; ++x)
    {
      const unsigned long p = XGetPixel(image, x, y);
      out.at<cv::Vec3b>(y, x) = cv::Vec3b(p & 0xff, (p >> 8) & 0xff, (p >> 16) & 0xff);
    }
  XDestroyImage(image);
  return out;
}

// rviz's Image displays sit in the left dock column, each a black area with the picture scaled into its
// middle: the row ranges where column 5 is black, at least 20 rows tall, and in each the bounding box of
// the picture (non-black pixels) within the column's `width` px.
std::vector<cv::Rect> imageViews(const cv::Mat& shot, int width)
{
  std::vector<cv::Rect> views;
  int start = -1;
  for (int y = 0; y <= shot.rows; ++y)
  {
    const bool black = y < shot.rows && shot.at<cv::Vec3b>(y, 5) == cv::Vec3b(0, 0, 0);
    if (black && start < 0)
      start = y;
    if (!black && start >= 0)
    {
      if (y - start >= 20)
      {
        cv::Mat grey;
        cv::cvtColor(shot(cv::Rect(0, start, width, y - start)), grey, cv::COLOR_BGR2GRAY);
        std::vector<cv::Point> lit;
        cv::findNonZero(grey, lit);
        if (!lit.empty())
          views.push_back(cv::boundingRect(lit) + cv::Point(0, start));
      }
      start = -1;
    }
  }
  return views;
}

// Share of the panel tile's pixels that are the "no data" grey (60, 60, 60).
double noDataShare(const cv::Mat& panel, int index)
{
  const int w = 320, h = 240, gap = 2;
  const cv::Mat tile = panel(cv::Rect((index % 4) * (w + gap), (index / 4) * (h + gap) + 18, w, h - 18));
  return double(cv::countNonZero(cv::Mat(tile == cv::Scalar(60, 60, 60)).reshape(1) > 0)) / (tile.total() * 3);
}
}  // namespace

TEST(MonitorRviz, EveryViewHasContentAndThePanelHasEightTiles)
{
  ros::NodeHandle nh, pnh("~");
  std::string config, out_dir;
  pnh.getParam("rviz_config", config);
  pnh.param("screenshot_dir", out_dir, std::string());
  ASSERT_FALSE(config.empty());

  int number = 0;
  for (int n = 91; n < 200 && !number; ++n)
    if (access(("/tmp/.X" + std::to_string(n) + "-lock").c_str(), F_OK) != 0)
      number = n;
  ASSERT_GT(number, 0) << "no free X display number";
  const std::string display_name = ":" + std::to_string(number);
  const pid_t xvfb = spawn({"Xvfb", display_name, "-screen", "0",
                            std::to_string(kWidth) + "x" + std::to_string(kHeight) + "x24", "-nolisten", "tcp"},
                           "");
  Display* display = nullptr;
  waitFor([&] { return (display = XOpenDisplay(display_name.c_str())) != nullptr; }, 15.0);
  ASSERT_NE(display, nullptr) << "Xvfb did not start on " << display_name;
  const pid_t rviz = spawn({"rviz", "-d", config, "__name:=rviz_under_test"}, display_name);

  std::vector<std::unique_ptr<TopicProbe<sensor_msgs::Image>>> probes;
  for (const auto& p : kPlots)
    probes.push_back(std::make_unique<TopicProbe<sensor_msgs::Image>>(nh, "monitor/" + p, 10));
  TopicProbe<sensor_msgs::Image> panel(nh, "monitor/panel", 2);

  // rviz subscribes to every view.
  for (const auto& p : kPlots)
  {
    const std::string topic = "/monitor/" + p;
    EXPECT_TRUE(waitFor(
        [&] {
          for (const auto& n : subscribersOf(topic))
            if (n == "/rviz_under_test")
              return true;
          return false;
        },
        60.0))
        << "rviz does not show " << topic;
  }
  // Every view delivers a picture with content, and the panel has eight tiles with data.
  for (size_t i = 0; i < kPlots.size(); ++i)
  {
    EXPECT_TRUE(probes[i]->waitForCount(1, 60.0)) << "nothing on monitor/" << kPlots[i];
    if (const auto m = probes[i]->last())
    {
      const cv::Mat image = cv_bridge::toCvShare(m, "bgr8")->image;
      cv::Scalar mean, dev;
      cv::meanStdDev(image, mean, dev);
      EXPECT_GT(dev[0] + dev[1] + dev[2], 10.0) << "monitor/" << kPlots[i] << " is uniform";
    }
  }
  cv::Mat last_panel;
  EXPECT_TRUE(waitFor(
      [&] {
        const auto m = panel.last();
        if (!m)
          return false;
        last_panel = cv_bridge::toCvCopy(m, "bgr8")->image;
        for (int i = 0; i < 8; ++i)
          if (noDataShare(last_panel, i) > 0.5)
            return false;
        return true;
      },
      60.0))
      << "the panel still has a tile without data";
  ASSERT_FALSE(last_panel.empty());
  for (int i = 0; i < 8; ++i)
    EXPECT_LT(noDataShare(last_panel, i), 0.5) << "panel tile " << i << " (" << kPlots[i] << ") says no data";

  ros::WallDuration(8.0).sleep();  // rviz draws the latest pictures
  const cv::Mat shot = screenshot(display);
  ASSERT_FALSE(shot.empty());
  EXPECT_EQ(waitpid(rviz, nullptr, WNOHANG), 0) << "rviz exited";
  if (!out_dir.empty())
  {
    cv::imwrite(out_dir + "/rviz.png", shot);
    cv::imwrite(out_dir + "/panel.png", last_panel);
  }
  // The screenshot is not one colour: rviz drew its window with the 3-D view and the image views.
  cv::Scalar mean, dev;
  cv::meanStdDev(shot, mean, dev);
  EXPECT_GT(dev[0] + dev[1] + dev[2], 30.0);
  // Every view shows its picture, not the empty display ("No Image"): for each picture rviz drew, the view
  // whose last ten images (rviz draws what it received a frame or two ago), scaled to the drawn box,
  // correlate best with it (normalised); every view must be the best match of some drawn box, at > 0.3.
  const std::vector<cv::Rect> views = imageViews(shot, kWidth / 5);
  EXPECT_GE(views.size(), kPlots.size()) << "image views found in the screenshot's dock column";
  std::vector<double> matched(kPlots.size(), -1.0);
  for (const cv::Rect& v : views)
  {
    if (v.width < 8 || v.height < 8)
      continue;
    int best_plot = -1;
    double best = -1;
    for (size_t i = 0; i < kPlots.size(); ++i)
      for (const auto& m : probes[i]->messages())
      {
        cv::Mat scaled, score;
        cv::resize(cv_bridge::toCvShare(m, "bgr8")->image, scaled, v.size(), 0, 0, cv::INTER_AREA);
        cv::matchTemplate(shot(v), scaled, score, cv::TM_CCOEFF_NORMED);
        if (score.at<float>(0, 0) > best)
          best = score.at<float>(0, 0), best_plot = int(i);
      }
    if (best_plot >= 0)
      matched[best_plot] = std::max(matched[best_plot], best);
  }
  for (size_t i = 0; i < kPlots.size(); ++i)
  {
    ROS_INFO("monitor/%s: drawn by rviz, correlation %.2f", kPlots[i].c_str(), matched[i]);
    EXPECT_GT(matched[i], 0.3) << "no view in rviz shows monitor/" << kPlots[i] << "'s picture";
  }
  XCloseDisplay(display);
  stop(rviz);
  stop(xvfb);
}

int main(int argc, char** argv)
{
  testing::InitGoogleTest(&argc, argv);
  ros::init(argc, argv, "test_monitor_rviz");
  ros::AsyncSpinner spinner(2);
  spinner.start();
  return RUN_ALL_TESTS();
}
