// bag_to_video: renders a bag through the monitoring panel (the thesis's eight panels) into a video.
#include <chrono>
#include <iostream>
#include <map>
#include <string>

#include <nlohmann/json.hpp>
#include <opencv2/videoio.hpp>
#include <rosbag/bag.h>
#include <rosbag/view.h>

#include "biovision_common/tool_options.hpp"
#include "biovision_monitor/ros/panel_renderer.hpp"

using biovision_monitor::MonitorParameters;
using biovision_monitor::PanelRenderer;

namespace
{
// Whether the bag's `topic` is `name`, both read as global names ("/stereo/disparity" is "stereo/disparity").
bool matches(const std::string& topic, const std::string& name)
{
  auto strip = [](const std::string& t) { return t.rfind('/', 0) == 0 ? t.substr(1) : t; };
  return strip(topic) == strip(name);
}
}  // namespace

int main(int argc, char** argv)
{
  biovision_common::ToolOptions options("bag_to_video",
                                        "Renders a bag through monitor_panel's eight panels (thesis Fig. 5.1) into a "
                                        "video with OpenCV's VideoWriter (MP4 'mp4v' for .mp4, MJPG for .avi).");
  std::string bag_path, output, json;
  double fps = 5.0, speed = 1.0;
  MonitorParameters p;
  options.app().add_option("bag", bag_path, "input bag")->required()->check(CLI::ExistingFile);
  options.app().add_option("output", output, "output video (.mp4 or .avi)")->required();
  options.app().add_option("--fps", fps, "panel frames per second of bag time")->check(biovision_common::kPositive);
  options.app().add_option("--speed", speed, "video time = bag time / speed")->check(biovision_common::kPositive);
  options.app().add_option("--columns", p.columns, "panel tiles per row")->check(CLI::Range(1, 8));
  options.app().add_option("--tile-width", p.tile_width, "tile width [px]")->check(CLI::Range(64, 1920));
  options.app().add_option("--tile-height", p.tile_height, "tile height [px]")->check(CLI::Range(48, 1080));
  std::string left_topic = PanelRenderer::defaultTopic(PanelRenderer::kLeftImage);
  std::string disparity_topic = PanelRenderer::defaultTopic(PanelRenderer::kDisparity);
  options.app().add_option("--left", left_topic, "left image topic (e.g. stereo/left/image_raw for a raw bag)");
  options.app().add_option("--disparity", disparity_topic,
                           "disparity topic (e.g. stereo/ground_truth/disparity for a simulator bag)");
  options.app().add_option("--json", json, "write frames, duration and timing here");
  options.parse(argc, argv);

  try
  {
    PanelRenderer renderer(p);
    rosbag::Bag bag(bag_path, rosbag::bagmode::Read);
    rosbag::View view(bag);
    if (view.size() == 0)
      throw std::runtime_error(bag_path + " holds no messages");
    std::array<std::string, PanelRenderer::kPanels> topics;
    for (int i = 0; i < PanelRenderer::kPanels; ++i)
      topics[i] = PanelRenderer::defaultTopic(PanelRenderer::Panel(i));
    topics[PanelRenderer::kLeftImage] = left_topic;
    topics[PanelRenderer::kDisparity] = disparity_topic;
    const bool avi = output.size() > 4 && output.substr(output.size() - 4) == ".avi";
    const int fourcc = avi ? cv::VideoWriter::fourcc('M', 'J', 'P', 'G') : cv::VideoWriter::fourcc('m', 'p', '4', 'v');
    cv::VideoWriter writer;
    PanelRenderer::Inputs in;
    const ros::Time begin = view.getBeginTime(), end = view.getEndTime();
    ros::Time next = begin;
    const ros::Duration step(1.0 / fps);
    size_t frames = 0, messages = 0;
    std::map<std::string, size_t> used;  // messages per topic
    const auto start = std::chrono::steady_clock::now();
    ros::Time last_frame;
    auto frame = [&](const ros::Time& at) {
      last_frame = at;
      const cv::Mat panel = renderer.renderPanel(in, topics, at);
      if (!writer.isOpened())
      {
        writer.open(output, fourcc, fps * speed, panel.size());
        if (!writer.isOpened())
          throw std::runtime_error("cannot open " + output + " for writing (OpenCV VideoWriter)");
      }
      writer.write(panel);
      ++frames;
    };
    for (const rosbag::MessageInstance& m : view)
    {
      while (m.getTime() >= next)
      {
        frame(next);
        next += step;
      }
      const std::string& topic = m.getTopic();
      const ros::Time t = m.getTime();
      using P = PanelRenderer;
      if (matches(topic, left_topic) && (in.left = m.instantiate<sensor_msgs::Image>()))
        in.received[P::kLeftImage] = t;
      else if (matches(topic, "objects"))
        in.objects = m.instantiate<biovision_msgs::RecognizedObjectArray>();
      else if (matches(topic, P::defaultTopic(P::kSaliencyMap)) && (in.saliency = m.instantiate<sensor_msgs::Image>()))
        in.received[P::kSaliencyMap] = in.received[P::kThresholdedSaliency] = t;
      else if (matches(topic, "saliency/regions"))
        in.regions = m.instantiate<biovision_msgs::SalientRegionArray>();
      else if (matches(topic, disparity_topic) && (in.disparity = m.instantiate<stereo_msgs::DisparityImage>()))
        in.received[P::kDisparity] = t;
      else if (matches(topic, P::defaultTopic(P::kBaseAttractor)) &&
               (in.base = m.instantiate<biovision_msgs::AttractorState>()))
        in.received[P::kBaseAttractor] = t;
      else if (matches(topic, P::defaultTopic(P::kHeadAttractor)) &&
               (in.head = m.instantiate<biovision_msgs::AttractorState>()))
        in.received[P::kHeadAttractor] = t;
      else if (matches(topic, P::defaultTopic(P::kLtm)) && (in.ltm = m.instantiate<nav_msgs::OccupancyGrid>()))
        in.received[P::kLtm] = t;
      else if (matches(topic, P::defaultTopic(P::kStm)) && (in.stm = m.instantiate<biovision_msgs::EgoMap>()))
        in.received[P::kStm] = t;
      else
        continue;
      ++messages;
      ++used[topic];
      if (frames % 50 == 0 && frames > 0)
        std::cerr << "\rbag_to_video: " << frames << " frames, " << (t - begin).toSec() << " of "
                  << (end - begin).toSec() << " s" << std::flush;
    }
    if (frames == 0 || last_frame < end)  // the bag's last state
      frame(end);
    writer.release();
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    std::cerr << "\rbag_to_video: wrote " << output << ": " << frames << " frames from " << messages << " messages in "
              << seconds << " s\n";
    if (!json.empty())
      biovision_common::writeJsonFile(json, nlohmann::json{{"command", options.command()},
                                                           {"bag", bag_path},
                                                           {"output", output},
                                                           {"frames", frames},
                                                           {"messages_used", messages},
                                                           {"messages_per_topic", used},
                                                           {"bag_duration_s", (end - begin).toSec()},
                                                           {"wall_s", seconds}});
  }
  catch (const std::exception& e)
  {
    std::cerr << "bag_to_video: " << e.what() << "\n";
    return 1;
  }
  return 0;
}
