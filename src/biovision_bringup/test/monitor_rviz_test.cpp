// The monitoring view in rviz under Xvfb during a simulator run with every panel's real producer
// (monitor_sim.launch: perception with biovision_memory, the base controller, which this test drives
// around the table): rviz with biovision.rviz subscribes to the eight monitor/<plot> views and the memory's
// topics, each view delivers a non-empty picture, the screenshot's image views show them, the memory
// publishes a map with obstacles, an STM with an obstacle and labelled objects, the base controller's
// attractor state has repellers, monitor/panel has eight tiles with data (none saying "no data on"), and
// no rviz display is in error (rviz's own per-display status, published by biovision_monitor's
// DisplayStatus panel). With ~screenshot_dir set, rviz.png and panel.png are written there.
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <mutex>
#include <regex>
#include <string>
#include <vector>

#include <XmlRpcValue.h>
#include <biovision_msgs/AttractorState.h>
#include <biovision_msgs/EgoMap.h>
#include <cv_bridge/cv_bridge.h>
#include <diagnostic_msgs/DiagnosticArray.h>
#include <geometry_msgs/PoseStamped.h>
#include <nav_msgs/OccupancyGrid.h>
#include <gtest/gtest.h>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>
#include <ros/master.h>
#include <ros/ros.h>
#include <sensor_msgs/Image.h>
#include <visualization_msgs/MarkerArray.h>

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
// middle: the row ranges where column 5 is black, at least 20 rows tall, and in each two guesses of where
// the picture is: the bounding box of what is not black within the column's `width` px, and the 4:3 box
// (every plot is 320 x 240) as tall as the black area, centred in it (its right end: the first pixel
// right of the picture that is not black) — rviz fits the picture to the widget's height.
struct ImageView
{
  cv::Rect lit, fitted;
};

std::vector<ImageView> imageViews(const cv::Mat& shot, int width)
{
  std::vector<ImageView> views;
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
        {
          ImageView v;
          v.lit = cv::boundingRect(lit) + cv::Point(0, start);
          const int mid = (start + y) / 2, h = y - start;
          int right = v.lit.br().x;
          while (right < shot.cols && shot.at<cv::Vec3b>(mid, right) == cv::Vec3b(0, 0, 0))
            ++right;
          const int w = h * 4 / 3;
          v.fitted = cv::Rect(right / 2 - w / 2, start, w, h) & cv::Rect(0, 0, shot.cols, shot.rows);
          views.push_back(v);
        }
      }
      start = -1;
    }
  }
  return views;
}

// The names of the displays in an rviz config: in the list under "Displays:" (not the panels' list), each
// "- Class:" item's "Name:"; the list ends at the next key indented no deeper than "Displays:".
std::vector<std::string> displayNames(const std::string& config)
{
  std::ifstream in(config);
  std::vector<std::string> names;
  std::string line;
  long indent = -1;  // of "Displays:", -1 before it
  bool display = false;
  const std::regex list(R"(^(\s+)Displays:\s*$)"), key(R"(^(\s*)[A-Za-z].*:.*$)"), klass(R"(^\s+- Class: .*)"),
      name(R"(^\s+Name: (.*)$)");
  std::smatch m;
  while (std::getline(in, line))
  {
    if (indent < 0)
    {
      if (std::regex_match(line, m, list))
        indent = m[1].length();
      continue;
    }
    if (std::regex_match(line, m, key) && long(m[1].length()) <= indent)
      break;
    if (std::regex_match(line, klass))
      display = true;
    else if (display && std::regex_match(line, m, name))
    {
      names.push_back(m[1]);
      display = false;
    }
  }
  return names;
}

// The base's goals, in odom (the robot starts at its origin facing +x, the table 0.7-1.4 m ahead, 1.6 m
// wide, walls 2.4 m to each side): 1.4 m to the left, then 1.4 m to the right, and again, each sent when the
// last is reached — along the table's front, which the STM sees as an obstacle (a goal behind the table
// had the base push against its corner).
class GoalPatrol
{
public:
  explicit GoalPatrol(ros::NodeHandle& nh) : pub_(nh.advertise<geometry_msgs::PoseStamped>("goal", 1, true))
  {
    // Subscribed once every member exists; sub_ is the last member, so it also goes first.
    sub_ = nh.subscribe("attractor/base", 20, &GoalPatrol::onState, this);
  }
  void start() { send(); }
  int sent() const { return sent_; }
  int withRepellers() const { return with_repellers_; }
  std::string behaviours() const
  {
    std::lock_guard<std::mutex> lock(mutex_);
    return behaviours_;
  }

private:
  void send()
  {
    static const double goals[][2] = {{0.0, 1.4}, {0.0, -1.4}};
    geometry_msgs::PoseStamped g;
    g.header.frame_id = "odom";
    g.header.stamp = ros::Time(0);
    g.pose.position.x = goals[sent_ % 2][0];
    g.pose.position.y = goals[sent_ % 2][1];
    g.pose.orientation.w = 1.0;
    pub_.publish(g);
    ++sent_;
    last_sent_ = ros::WallTime::now();
  }
  void onState(const biovision_msgs::AttractorStateConstPtr& s)
  {
    {
      std::lock_guard<std::mutex> lock(mutex_);
      if (behaviours_.find(s->behaviour) == std::string::npos)
        behaviours_ += (behaviours_.empty() ? "" : ", ") + s->behaviour;
    }
    bool repeller = false;
    for (float r : s->repulsion)
      repeller = repeller || r > 0.0f;
    if (s->forcelet.size() == 9 && repeller)
      ++with_repellers_;
    if (sent_ > 0 && s->behaviour == "reached" && (ros::WallTime::now() - last_sent_).toSec() > 3.0)
      send();
  }
  ros::Publisher pub_;
  std::atomic<int> sent_{0}, with_repellers_{0};
  ros::WallTime last_sent_;
  mutable std::mutex mutex_;
  std::string behaviours_;
  ros::Subscriber sub_;
};

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
  biovision_ros_common::ChildProcess xvfb({"Xvfb", display_name, "-screen", "0",
                                           std::to_string(kWidth) + "x" + std::to_string(kHeight) + "x24", "-nolisten",
                                           "tcp"});
  Display* display = nullptr;
  waitFor([&] { return (display = XOpenDisplay(display_name.c_str())) != nullptr; }, 15.0);
  ASSERT_NE(display, nullptr) << "Xvfb did not start on " << display_name;
  biovision_ros_common::ChildProcess rviz({"rviz", "-d", config, "__name:=rviz_under_test"}, display_name);

  std::vector<std::unique_ptr<TopicProbe<sensor_msgs::Image>>> probes;
  for (const auto& p : kPlots)
    probes.push_back(std::make_unique<TopicProbe<sensor_msgs::Image>>(nh, "monitor/" + p, 10));
  TopicProbe<sensor_msgs::Image> panel(nh, "monitor/panel", 2);
  TopicProbe<nav_msgs::OccupancyGrid> ltm(nh, "memory/ltm", 2);
  TopicProbe<visualization_msgs::MarkerArray> ltm_markers(nh, "memory/ltm_markers", 2);
  TopicProbe<biovision_msgs::EgoMap> stm(nh, "memory/stm", 50);
  TopicProbe<diagnostic_msgs::DiagnosticArray> display_status(nh, "/rviz_under_test/display_status", 2);
  GoalPatrol patrol(nh);

  // rviz subscribes to every view and to the memory's topics.
  std::vector<std::string> topics = {"/memory/ltm", "/memory/ltm_markers", "/memory/stm_markers", "/sim/objects"};
  for (const auto& p : kPlots)
    topics.push_back("/monitor/" + p);
  for (const auto& topic : topics)
  {
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
  // The memory places what recognition finds (the teacher shows it the table's objects): a labelled object
  // in memory/ltm_markers, while the base stands facing the table; then the base starts driving.
  std::string labels;
  EXPECT_TRUE(waitFor(
      [&] {
        const auto a = ltm_markers.last();
        labels.clear();
        if (a)
          for (const auto& m : a->markers)
            if (m.ns == "ltm_labels" && !m.text.empty())
              labels += m.text + "; ";
        return !labels.empty();
      },
      90.0))
      << "memory/ltm_markers has no labelled object";
  ROS_INFO("memory/ltm_markers: %s", labels.c_str());
  patrol.start();
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

  // The real producers: the memory's map has obstacle cells, its STM an obstacle; the base controller's
  // attractor state has repellers while it drives along the table.
  EXPECT_TRUE(waitFor(
      [&] {
        const auto g = ltm.last();
        return g && std::count_if(g->data.begin(), g->data.end(), [](int8_t v) { return v > 0; }) >= 10;
      },
      60.0))
      << "memory/ltm has fewer than 10 occupied cells";
  EXPECT_TRUE(waitFor(
      [&] {
        for (const auto& m : stm.messages())
          for (size_t i = 0; i < m->obstacle_distance.size() && i < m->confidence.size(); ++i)
            if (std::isfinite(m->obstacle_distance[i]) && m->confidence[i] > 0.0f)
              return true;
        return false;
      },
      30.0))
      << "memory/stm never had an obstacle";
  EXPECT_TRUE(waitFor([&] { return patrol.withRepellers() > 0; }, 60.0))
      << "attractor/base never had a repeller (behaviours seen: " << patrol.behaviours() << ")";
  ROS_INFO("base: %d goals sent, %d states with repellers, behaviours: %s", patrol.sent(), patrol.withRepellers(),
           patrol.behaviours().c_str());

  ros::WallDuration(8.0).sleep();  // rviz draws the latest pictures
  // The pictures sent before the screenshot (rviz draws what it received a frame or two ago).
  std::vector<std::vector<sensor_msgs::ImageConstPtr>> sent;
  for (const auto& probe : probes)
    sent.push_back(probe->messages());
  const cv::Mat shot = screenshot(display);
  ASSERT_FALSE(shot.empty());
  EXPECT_TRUE(rviz.running()) << "rviz exited";
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
  const std::vector<ImageView> views = imageViews(shot, kWidth / 5);
  EXPECT_GE(views.size(), kPlots.size()) << "image views found in the screenshot's dock column";
  // score[v][i]: the best correlation of view v (either box) with plot i's recent pictures (as sent, and
  // without their black margins). Each plot's picture must be found (> 0.3) in a view of its own: the
  // plots' best views are all different.
  std::vector<std::vector<double>> score(views.size(), std::vector<double>(kPlots.size(), -1.0));
  for (size_t k = 0; k < views.size(); ++k)
    for (const cv::Rect& v : {views[k].lit, views[k].fitted})
    {
      if (v.width < 8 || v.height < 8)
        continue;
      for (size_t i = 0; i < kPlots.size(); ++i)
        for (const auto& m : sent[i])
        {
          const cv::Mat image = cv_bridge::toCvShare(m, "bgr8")->image;
          cv::Mat grey;
          cv::cvtColor(image, grey, cv::COLOR_BGR2GRAY);
          std::vector<cv::Point> lit;
          cv::findNonZero(grey, lit);
          if (lit.empty())
            continue;
          for (const cv::Mat& candidate : {image, image(cv::boundingRect(lit))})
          {
            cv::Mat scaled, result;
            cv::resize(candidate, scaled, v.size(), 0, 0, cv::INTER_AREA);
            cv::matchTemplate(shot(v), scaled, result, cv::TM_CCOEFF_NORMED);
            score[k][i] = std::max(score[k][i], double(result.at<float>(0, 0)));
          }
        }
    }
  std::vector<int> best_view(kPlots.size(), -1);
  for (size_t i = 0; i < kPlots.size(); ++i)
  {
    double best = -1.0;
    for (size_t k = 0; k < views.size(); ++k)
      if (score[k][i] > best)
        best = score[k][i], best_view[i] = int(k);
    ROS_INFO("monitor/%s: drawn by rviz in box %d (y %d), correlation %.2f", kPlots[i].c_str(), best_view[i],
             best_view[i] >= 0 ? views[best_view[i]].lit.y : -1, best);
    EXPECT_GT(best, 0.3) << "no view in rviz shows monitor/" << kPlots[i] << "'s picture";
    for (size_t j = 0; j < i; ++j)
      EXPECT_NE(best_view[i], best_view[j])
          << "monitor/" << kPlots[i] << " and monitor/" << kPlots[j] << " are found in the same box of the screenshot";
  }
  // No display is in error, none even warns: rviz's own status of every display of the config and its
  // Global Status (fixed frame), as the DisplayStatus panel reports it once a second. With every producer
  // running each display should be Ok (an Image display warns "No Image received", a Map "No map
  // received"; a display whose class is missing is in error): waits up to 20 s for such a report.
  const std::vector<std::string> names = displayNames(config);
  EXPECT_GE(names.size(), 8u) << "displays read from " << config;
  auto allOk = [&](const diagnostic_msgs::DiagnosticArray& a) {
    for (const auto& s : a.status)
      if (s.level != diagnostic_msgs::DiagnosticStatus::OK)
        return false;
    for (const auto& name : names)
      if (std::none_of(a.status.begin(), a.status.end(), [&](const auto& s) { return s.name == name; }))
        return false;
    return true;
  };
  waitFor(
      [&] {
        const auto a = display_status.last();
        return a && allOk(*a);
      },
      20.0);
  const auto statuses = display_status.last();
  ASSERT_TRUE(statuses) << "no display status from rviz (DisplayStatus panel not loaded?)";
  for (const auto& name : names)
    EXPECT_TRUE(std::any_of(statuses->status.begin(), statuses->status.end(),
                            [&](const diagnostic_msgs::DiagnosticStatus& s) { return s.name == name; }))
        << "rviz reports no status for display '" << name << "'";
  for (const auto& s : statuses->status)
  {
    std::string lines;
    for (const auto& v : s.values)
      lines += " [" + v.key + ": " + v.value + "]";
    ROS_INFO("rviz display '%s' (%s): %s%s", s.name.c_str(), s.hardware_id.c_str(), s.message.c_str(), lines.c_str());
    EXPECT_LT(s.level, diagnostic_msgs::DiagnosticStatus::ERROR)
        << "rviz display '" << s.name << "' is in error:" << lines;
    EXPECT_EQ(s.level, diagnostic_msgs::DiagnosticStatus::OK) << "rviz display '" << s.name << "' warns:" << lines;
  }
  XCloseDisplay(display);
}

int main(int argc, char** argv)
{
  return biovision_ros_common::RosTestRun(argc, argv, "test_monitor_rviz", 2).run();
}
