// loop_bench: the whole perception loop on a committed bag, in this process as its one nodelet manager,
// as fast as the graph keeps up, against a peer pipeline from Debian parts on the same frames (issue 21).
// Run by launch/loop_bench.launch, which loads the nodelets into this process (/loop_bench).
#include <algorithm>
#include <cmath>
#include <limits>
#include <atomic>
#include <chrono>
#include <condition_variable>
#include <filesystem>
#include <iomanip>
#include <iostream>
#include <map>
#include <mutex>
#include <sstream>
#include <thread>

#include <sys/resource.h>

#include <biovision_msgs/KeypointArray.h>
#include <biovision_msgs/RecognizedObjectArray.h>
#include <biovision_msgs/SalientRegionArray.h>
#include <nodelet/loader.h>
#include <opencv2/core.hpp>
#include <ros/ros.h>
#include <rosbag/bag.h>
#include <rosbag/view.h>
#include <rosgraph_msgs/Clock.h>
#include <sensor_msgs/CameraInfo.h>
#include <sensor_msgs/Image.h>
#include <sensor_msgs/JointState.h>
#include <stereo_msgs/DisparityImage.h>
#include <tf2_msgs/TFMessage.h>
#include <topic_tools/shape_shifter.h>

#include "biovision_common/cpu_features.hpp"
#include "biovision_common/hamming_distance.hpp"
#include "biovision_common/tool_options.hpp"
#include "biovision_recognition/packed_projection.hpp"
#include "biovision_ros_common/processing_times.hpp"
#include "biovision_stereo/cost_simd.hpp"
#include "biovision_stereo/hamming.hpp"
#include "biovision_stereo/semi_global_aggregation.hpp"
#include "biovision_v1/fourier_transform.hpp"

namespace
{
using Clock = std::chrono::steady_clock;

const char* kDescription =
    "Replays a bag's stereo frames through the perception nodelets loaded into this process (one nodelet\n"
    "manager: launch/loop_bench.launch loads them) as fast as the graph keeps up — a frame is published once\n"
    "fewer than --in-flight frames are unfinished — without the simulator, and measures end-to-end frames/s,\n"
    "per-stage latency (p50/p95) and CPU per stage. Phases on the same frames: 'frontend' (Debian's debayer +\n"
    "rectify only), 'ours' (BioBin, saliency, recognition, V1 keypoints, memory) and 'peer' (stereo_image_proc\n"
    "SGBM + OpenCV spectral-residual saliency + ORB/BFMatcher in the salient regions).";

double seconds(Clock::duration d)
{
  return std::chrono::duration<double>(d).count();
}

double processCpuSeconds()
{
  rusage u{};
  getrusage(RUSAGE_SELF, &u);
  return u.ru_utime.tv_sec + u.ru_stime.tv_sec + 1e-6 * (u.ru_utime.tv_usec + u.ru_stime.tv_usec);
}

double percentile(std::vector<double> v, double p)
{
  if (v.empty())
    return -1.0;
  std::sort(v.begin(), v.end());
  const double pos = p * (v.size() - 1);
  const size_t i = static_cast<size_t>(pos);
  const double f = pos - i;
  return i + 1 < v.size() ? v[i] * (1 - f) + v[i + 1] * f : v[i];
}

/// One stereo frame of the bag, restamped for its replay loop.
struct Frame
{
  ros::Time stamp;
  sensor_msgs::ImageConstPtr left, right;
  sensor_msgs::CameraInfoConstPtr left_info, right_info;
  std::vector<tf2_msgs::TFMessageConstPtr> tf;  ///< recorded since the previous frame
  std::vector<sensor_msgs::JointStateConstPtr> joints;
};

template <typename M>
boost::shared_ptr<std::remove_const_t<M>> restamped(const boost::shared_ptr<M>& m, ros::Duration offset)
{
  auto c = boost::make_shared<std::remove_const_t<M>>(*m);
  c->header.stamp += offset;
  return c;
}

/// An output watched by the benchmark: its arrival time per frame stamp.
struct Sink
{
  std::string topic;
  std::string stage;      ///< the name in the report
  std::string after;      ///< the sink whose arrival starts this stage ("" = the frame's publication)
  bool completes = true;  ///< a frame is finished when every completing sink has given it (or a later one)
  std::string nodelet;    ///< the nodelet (getName()) whose ScopedProcessingTimer gives this stage's CPU
};

struct Phase
{
  std::string name;
  std::vector<Sink> sinks;
  std::vector<std::string> activate;  ///< outputs subscribed only to switch their producer on (lazy nodelets)
};

class LoopBench
{
public:
  LoopBench(ros::NodeHandle& nh, std::vector<Frame> frames, int in_flight, int warmup, double timeout)
    : nh_(nh), frames_(std::move(frames)), in_flight_(in_flight), warmup_(warmup), timeout_(timeout)
  {
    for (const Frame& f : frames_)
      stamps_.push_back(f.stamp);
    clock_pub_ = nh_.advertise<rosgraph_msgs::Clock>("/clock", 1);
    tf_pub_ = nh_.advertise<tf2_msgs::TFMessage>("/tf", 100);
    joints_pub_ = nh_.advertise<sensor_msgs::JointState>("/joint_states", 100);
    left_pub_ = nh_.advertise<sensor_msgs::Image>("stereo/left/image_raw", 5);
    right_pub_ = nh_.advertise<sensor_msgs::Image>("stereo/right/image_raw", 5);
    left_info_pub_ = nh_.advertise<sensor_msgs::CameraInfo>("stereo/left/camera_info", 5);
    right_info_pub_ = nh_.advertise<sensor_msgs::CameraInfo>("stereo/right/camera_info", 5);
  }

  void publishStatic(const std::vector<tf2_msgs::TFMessageConstPtr>& statics)
  {
    tf_static_pub_ = nh_.advertise<tf2_msgs::TFMessage>("/tf_static", 10, true);
    auto all = boost::make_shared<tf2_msgs::TFMessage>();
    for (const auto& m : statics)
      all->transforms.insert(all->transforms.end(), m->transforms.begin(), m->transforms.end());
    tf_static_pub_.publish(all);
    publishClock(frames_.front().stamp - ros::Duration(0.5));
  }

  nlohmann::ordered_json run(const Phase& phase)
  {
    std::cout << "loop_bench: phase " << phase.name << ": waiting for its nodelets" << std::endl;
    {
      std::lock_guard<std::mutex> lock(mutex_);
      arrivals_.clear();
      latest_.clear();
      sinks_ = phase.sinks;
      for (const Sink& s : sinks_)
      {
        arrivals_[s.topic];
        if (s.completes)
          latest_[s.topic] = -1;
      }
    }
    waitForPublishers(phase);
    std::vector<ros::Subscriber> subs;
    for (const Sink& s : phase.sinks)
      subs.push_back(subscribe(s.topic));
    for (const std::string& t : phase.activate)
      subs.push_back(subscribe(t));
    // The lazy chain subscribes upstream as listeners connect: wait until the raw images are watched.
    const auto t_wait = Clock::now();
    while (ros::ok() && (left_pub_.getNumSubscribers() == 0 || right_pub_.getNumSubscribers() == 0) &&
           seconds(Clock::now() - t_wait) < 30)
      std::this_thread::sleep_for(std::chrono::milliseconds(50));
    std::this_thread::sleep_for(std::chrono::seconds(2));  // the remaining links of the chain

    // Stage CPU is counted from the same frame as the process's: the warm-up's DFT plan measuring (seconds
    // of it) counted in the stages alone made them add up to more than the process.
    std::map<std::string, biovision_ros_common::ProcessingTimes::Totals> stages_before;
    published_.assign(frames_.size(), Clock::time_point());
    double cpu_start = 0.0, cpu_end = 0.0;
    Clock::time_point t_start, t_end;
    size_t timeouts = 0;
    for (size_t k = 0; k < frames_.size() && ros::ok(); ++k)
    {
      // Keep at most in_flight_ frames unfinished: sleep until an arrival finishes one (no polling, which
      // took ~5% of the process's CPU samples under perf, competing with the graph it measures).
      if (!waitUntil([&] { return unfinishedLocked(k) < static_cast<size_t>(in_flight_); }))
        ++timeouts;
      if (static_cast<int>(k) == warmup_)
      {
        cpu_start = processCpuSeconds();
        stages_before = biovision_ros_common::ProcessingTimes::instance().snapshot();
        t_start = Clock::now();
      }
      publish(k);
    }
    waitAllFinished();
    t_end = lastCompletion();
    cpu_end = processCpuSeconds();
    const auto stages_after = biovision_ros_common::ProcessingTimes::instance().snapshot();
    subs.clear();
    std::this_thread::sleep_for(std::chrono::seconds(1));
    return report(phase, t_start, t_end, cpu_end - cpu_start, stages_before, stages_after, timeouts);
  }

private:
  ros::Subscriber subscribe(const std::string& topic)
  {
    // Typed subscriptions: intra-process messages arrive as the publisher's pointer, never serialised.
    if (topic.find("disparity") != std::string::npos)
      return nh_.subscribe<stereo_msgs::DisparityImage>(
          topic, 10, [this, topic](const stereo_msgs::DisparityImageConstPtr& m) { arrived(topic, m->header.stamp); });
    if (topic.find("regions") != std::string::npos)
      return nh_.subscribe<biovision_msgs::SalientRegionArray>(
          topic, 10,
          [this, topic](const biovision_msgs::SalientRegionArrayConstPtr& m) { arrived(topic, m->header.stamp); });
    if (topic.find("objects") != std::string::npos)
      return nh_.subscribe<biovision_msgs::RecognizedObjectArray>(
          topic, 10,
          [this, topic](const biovision_msgs::RecognizedObjectArrayConstPtr& m) { arrived(topic, m->header.stamp); });
    if (topic.find("keypoints") != std::string::npos)
      return nh_.subscribe<biovision_msgs::KeypointArray>(
          topic, 10,
          [this, topic](const biovision_msgs::KeypointArrayConstPtr& m) { arrived(topic, m->header.stamp); });
    if (topic.find("image") != std::string::npos)
      return nh_.subscribe<sensor_msgs::Image>(topic, 10, [this, topic](const sensor_msgs::ImageConstPtr& m) {
        arrived(topic, m->header.stamp);
      });
    // Anything else (memory/stm ...): only switched on.
    const boost::function<void(const topic_tools::ShapeShifter::ConstPtr&)> ignore =
        [](const topic_tools::ShapeShifter::ConstPtr&) {};
    return nh_.subscribe<topic_tools::ShapeShifter>(topic, 1, ignore);
  }

  void waitForPublishers(const Phase& phase)
  {
    const auto t0 = Clock::now();
    while (ros::ok())
    {
      ros::master::V_TopicInfo topics;
      ros::master::getTopics(topics);
      size_t found = 0;
      for (const Sink& s : phase.sinks)
        for (const auto& t : topics)
          if (t.name == nh_.resolveName(s.topic))
          {
            ++found;
            break;
          }
      if (found == phase.sinks.size())
        return;
      if (seconds(Clock::now() - t0) > 60)
        throw std::runtime_error("phase " + phase.name + ": only " + std::to_string(found) + " of " +
                                 std::to_string(phase.sinks.size()) + " outputs advertised after 60 s");
      std::this_thread::sleep_for(std::chrono::milliseconds(200));
    }
  }

  void publishClock(ros::Time t)
  {
    rosgraph_msgs::Clock c;
    c.clock = t;
    clock_pub_.publish(c);
  }

  void publish(size_t k)
  {
    const Frame& f = frames_[k];
    publishClock(f.stamp);
    for (const auto& m : f.tf)
      tf_pub_.publish(m);
    for (const auto& m : f.joints)
      joints_pub_.publish(m);
    {
      std::lock_guard<std::mutex> lock(mutex_);
      published_[k] = Clock::now();
      index_[f.stamp] = k;
    }
    left_info_pub_.publish(f.left_info);
    right_info_pub_.publish(f.right_info);
    left_pub_.publish(f.left);
    right_pub_.publish(f.right);
  }

  void arrived(const std::string& topic, ros::Time stamp)
  {
    const auto now = Clock::now();
    {
      std::lock_guard<std::mutex> lock(mutex_);
      arrivals_[topic][stamp] = now;
      // The topic now covers every frame up to this stamp (a frame it dropped is covered by a later one).
      const auto latest = latest_.find(topic);
      if (latest != latest_.end())
      {
        const long k = static_cast<long>(std::upper_bound(stamps_.begin(), stamps_.end(), stamp) - stamps_.begin()) - 1;
        latest->second = std::max(latest->second, k);
      }
    }
    changed_.notify_all();
  }

  /// Waits (mutex_ not held by the caller) until done() holds or timeout_ passes; false on timeout.
  template <typename Done>
  bool waitUntil(Done done)
  {
    const auto deadline = Clock::now() +
                          std::chrono::duration_cast<Clock::duration>(std::chrono::duration<double>(timeout_));
    std::unique_lock<std::mutex> lock(mutex_);
    while (!done())
    {
      if (!ros::ok() || Clock::now() >= deadline)
        return false;
      changed_.wait_for(lock, std::chrono::milliseconds(100));  // wakes on each arrival; 100 ms to see ros::ok()
    }
    return true;
  }

  /// Frames before `next` not yet given (or covered by a later frame) by every completing sink; mutex_ held.
  size_t unfinishedLocked(size_t next) const
  {
    long covered = static_cast<long>(next) - 1;
    for (const auto& [topic, k] : latest_)
      covered = std::min(covered, k);
    return next - static_cast<size_t>(covered + 1);
  }

  void waitAllFinished()
  {
    waitUntil([&] { return unfinishedLocked(frames_.size()) == 0; });
  }

  Clock::time_point lastCompletion() const
  {
    std::lock_guard<std::mutex> lock(mutex_);
    Clock::time_point last = published_.back();
    for (const Sink& s : sinks_)
      if (s.completes)
        for (const auto& [stamp, t] : arrivals_.at(s.topic))
          last = std::max(last, t);
    return last;
  }

  nlohmann::ordered_json report(const Phase& phase, Clock::time_point t_start, Clock::time_point t_end,
                                double cpu_seconds,
                                const std::map<std::string, biovision_ros_common::ProcessingTimes::Totals>& before,
                                const std::map<std::string, biovision_ros_common::ProcessingTimes::Totals>& after,
                                size_t timeouts)
  {
    std::lock_guard<std::mutex> lock(mutex_);
    const size_t measured = frames_.size() - std::min<size_t>(frames_.size(), warmup_);
    const double wall = seconds(t_end - t_start);
    nlohmann::ordered_json out;
    out["frames"] = measured;
    out["warmup_frames"] = warmup_;
    out["frames_per_s"] = measured / wall;
    out["process_cpu_cores"] = cpu_seconds / wall;
    out["process_cpu_ms_per_frame"] = 1e3 * cpu_seconds / measured;
    out["timeouts"] = timeouts;
    // Arrival of each sink per measured frame, relative to the frame's publication [ms].
    std::map<std::string, std::vector<double>> stage_ms;
    std::map<std::string, size_t> given;
    std::vector<double> end_to_end;
    for (size_t k = warmup_; k < frames_.size(); ++k)
    {
      const ros::Time stamp = frames_[k].stamp;
      double last = 0.0;
      bool complete = true;
      std::map<std::string, double> at;
      for (const Sink& s : phase.sinks)
      {
        const auto& a = arrivals_.at(s.topic);
        const auto it = a.find(stamp);
        if (it == a.end())
        {
          if (s.completes)
            complete = false;
          continue;
        }
        ++given[s.topic];
        at[s.topic] = 1e3 * seconds(it->second - published_[k]);
        if (s.completes)
          last = std::max(last, at[s.topic]);
      }
      for (const Sink& s : phase.sinks)
      {
        if (!at.count(s.topic))
          continue;
        const double start = s.after.empty() ? 0.0 : (at.count(s.after) ? at[s.after] : -1.0);
        if (start >= 0.0)
          stage_ms[s.stage].push_back(at[s.topic] - start);
      }
      if (complete)
        end_to_end.push_back(last);
    }
    out["end_to_end_latency_p50_ms"] = percentile(end_to_end, 0.5);
    out["end_to_end_latency_p95_ms"] = percentile(end_to_end, 0.95);
    out["frames_complete"] = end_to_end.size();
    // Frames with every output (the others were dropped by a stage's queue and covered by a later frame).
    out["complete_frames_per_s"] = (wall > 0 ? end_to_end.size() / wall : 0.0);
    // CPU per nodelet (ScopedProcessingTimer: its callback thread's CPU), over the whole phase.
    std::map<std::string, std::pair<unsigned long, double>> cpu;  // nodelet -> inputs, CPU [s]
    double attributed = 0.0;
    for (const auto& [name, t] : after)
    {
      const auto b = before.count(name) ? before.at(name) : biovision_ros_common::ProcessingTimes::Totals();
      if (t.inputs == b.inputs)
        continue;
      cpu[name] = {t.inputs - b.inputs, t.cpu_seconds - b.cpu_seconds};
      attributed += t.cpu_seconds - b.cpu_seconds;
    }
    // One row per stage: bench_report.py makes the rows of equal columns one table.
    auto row = [&](const std::string& stage, const std::vector<double>& ms, size_t frames_given,
                   const std::string& nodelet) {
      nlohmann::ordered_json r;
      r["latency_p50_ms"] = percentile(ms, 0.5);
      r["latency_p95_ms"] = percentile(ms, 0.95);
      r["frames_given"] = frames_given;
      if (cpu.count(nodelet))
      {
        r["cpu_ms_per_input"] = 1e3 * cpu[nodelet].second / cpu[nodelet].first;
        r["cpu_share"] = cpu[nodelet].second / (cpu_total_ + 1e-12);
        cpu.erase(nodelet);
      }
      else
      {
        r["cpu_ms_per_input"] = "-";
        r["cpu_share"] = "-";
      }
      stage_rows_[phase.name + ": " + stage] = r;
    };
    cpu_total_ = 0.0;
    for (const auto& [name, c] : cpu)
      cpu_total_ += c.second;
    cpu_total_ = std::max(cpu_total_, cpu_seconds);
    for (const Sink& s : phase.sinks)
      row(s.stage, stage_ms[s.stage], given[s.topic], s.nodelet);
    const auto leftover = cpu;
    for (const auto& [name, c] : leftover)  // nodelets without a watched output (memory)
      row(name, {}, 0, name);
    out["attributed_cpu_ms_per_frame"] = 1e3 * attributed / std::max<size_t>(1, measured);
    out["unattributed_cpu_ms_per_frame"] = out["process_cpu_ms_per_frame"].get<double>() -
                                           out["attributed_cpu_ms_per_frame"].get<double>();
    row("end to end", end_to_end, end_to_end.size(), "");
    return out;
  }

  ros::NodeHandle& nh_;
  std::vector<Frame> frames_;
  int in_flight_, warmup_;
  double timeout_;
  ros::Publisher clock_pub_, tf_pub_, tf_static_pub_, joints_pub_, left_pub_, right_pub_, left_info_pub_,
      right_info_pub_;
  mutable std::mutex mutex_;
  std::condition_variable changed_;     ///< notified at each arrival
  std::vector<ros::Time> stamps_;       ///< frames_' stamps, ascending
  std::map<std::string, long> latest_;  ///< completing sink -> last frame index it covers (-1: none)
  std::vector<Sink> sinks_;
  std::map<std::string, std::map<ros::Time, Clock::time_point>> arrivals_;
  std::vector<Clock::time_point> published_;
  std::map<ros::Time, size_t> index_;
  double cpu_total_ = 0.0;

public:
  /// "<phase>: <stage>" -> latency p50/p95 [ms], frames given, CPU per input [ms] and share of the phase's CPU.
  nlohmann::ordered_json stage_rows_;
};

/// The bag's stereo frames (left/right image_raw + camera_info with equal stamps), `loops` times, each loop
/// shifted past the previous one so that time never goes backwards; the tf and joint states between frames.
std::vector<Frame> readFrames(const std::string& path, int loops, std::vector<tf2_msgs::TFMessageConstPtr>& statics)
{
  rosbag::Bag bag(path, rosbag::bagmode::Read);
  rosbag::View view(bag);
  std::map<ros::Time, Frame> by_stamp;
  std::vector<std::pair<ros::Time, tf2_msgs::TFMessageConstPtr>> tf;
  std::vector<std::pair<ros::Time, sensor_msgs::JointStateConstPtr>> joints;
  for (const rosbag::MessageInstance& m : view)
  {
    const std::string& t = m.getTopic();
    if (t == "/stereo/left/image_raw" || t == "/stereo/right/image_raw")
    {
      auto img = m.instantiate<sensor_msgs::Image>();
      Frame& f = by_stamp[img->header.stamp];
      f.stamp = img->header.stamp;
      (t == "/stereo/left/image_raw" ? f.left : f.right) = img;
    }
    else if (t == "/stereo/left/camera_info" || t == "/stereo/right/camera_info")
    {
      auto info = m.instantiate<sensor_msgs::CameraInfo>();
      Frame& f = by_stamp[info->header.stamp];
      f.stamp = info->header.stamp;
      (t == "/stereo/left/camera_info" ? f.left_info : f.right_info) = info;
    }
    else if (t == "/tf")
      tf.emplace_back(m.getTime(), m.instantiate<tf2_msgs::TFMessage>());
    else if (t == "/tf_static")
      statics.push_back(m.instantiate<tf2_msgs::TFMessage>());
    else if (t == "/joint_states")
      joints.emplace_back(m.getTime(), m.instantiate<sensor_msgs::JointState>());
  }
  std::vector<Frame> base;
  for (auto& [stamp, f] : by_stamp)
    if (f.left && f.right && f.left_info && f.right_info)
      base.push_back(f);
  if (base.size() < 2)
    throw std::runtime_error(path +
                             ": fewer than 2 complete stereo frames (/stereo/{left,right}/image_raw + camera_info)");
  const ros::Duration span = base.back().stamp - base.front().stamp + ros::Duration(1.0);
  std::vector<Frame> frames;
  for (int loop = 0; loop < loops; ++loop)
  {
    const ros::Duration offset = span * loop;
    size_t ti = 0, ji = 0;
    for (const Frame& b : base)
    {
      Frame f;
      f.stamp = b.stamp + offset;
      f.left = restamped(b.left, offset);
      f.right = restamped(b.right, offset);
      f.left_info = restamped(b.left_info, offset);
      f.right_info = restamped(b.right_info, offset);
      for (; ti < tf.size() && tf[ti].first <= b.stamp; ++ti)
      {
        auto c = boost::make_shared<tf2_msgs::TFMessage>(*tf[ti].second);
        for (auto& tr : c->transforms)
          tr.header.stamp += offset;
        f.tf.push_back(c);
      }
      for (; ji < joints.size() && joints[ji].first <= b.stamp; ++ji)
        f.joints.push_back(restamped(joints[ji].second, offset));
      frames.push_back(f);
    }
  }
  return frames;
}
}  // namespace

int main(int argc, char** argv)
{
  std::string bag_path, json_path, phases_list = "frontend,ours,peer";
  int loops = 3, in_flight = 2, opencv_threads = 1, rounds = 9;  // single rounds spread 1.24-2.09 on one EPYC evening
  int warmup = 20;  // DFT plans are measured on a size's 16th run (biovision_v1::FourierTransform)
  int fft_measure_after = biovision_v1::FourierTransform::kMeasureAfter;
  double timeout = 20.0;
  biovision_common::ToolOptions options("loop_bench", kDescription);
  CLI::App& app = options.app();
  app.add_option("--bag", bag_path, "the bag (stereo/{left,right}/image_raw + camera_info, tf)")->required();
  app.add_option("--loops", loops, "times the bag's frames are replayed")->check(biovision_common::kPositive);
  app.add_option("--in-flight", in_flight, "unfinished frames allowed at once")->check(biovision_common::kPositive);
  app.add_option("--warmup", warmup, "first frames left out of the figures")->check(biovision_common::kNonNegative);
  app.add_option("--opencv-threads", opencv_threads,
                 "OpenCV's parallel_for_ threads (1: stages run in parallel on the manager's workers, and each "
                 "stage's CPU is its callback thread's)")
      ->check(biovision_common::kPositive);
  app.add_option("--phases", phases_list, "comma list of frontend, ours, peer");
  app.add_option("--rounds", rounds,
                 "times the phase list runs; ours_vs_peer_time is the median of the rounds' ratios, and the "
                 "figures are that round's (the machine's speed drifts between minutes: one pair of phases "
                 "varied 1.35-2.1)")
      ->check(biovision_common::kPositive);
  app.add_option("--fft-measure-after", fft_measure_after,
                 "runs of a DFT size after which its plan is measured (0: estimated plans only)");
  app.add_option("--timeout", timeout, "[s] longest wait for a frame")->check(biovision_common::kPositive);
  app.add_option("--json", json_path, "write the figures to this file");
  options.parse(argc, argv);

  biovision_v1::FourierTransform::setMeasurePolicy(fft_measure_after);
  ros::init(argc, argv, "loop_bench");
  cv::setNumThreads(opencv_threads);
  ros::NodeHandle nh;
  // This process is the nodelet manager: loop_bench.launch's `nodelet load ... /loop_bench` lands here.
  // The bag is read before the spinner serves the launch file's `nodelet load` calls: rosbag::Bag's
  // constructor loads its encryptor plugin through class_loader, which is not thread-safe against the
  // nodelet loads (1 in 3 starts here died in class_loader::impl::unloadLibrary with SIGSEGV).
  std::vector<tf2_msgs::TFMessageConstPtr> statics;
  std::vector<Frame> frames = readFrames(bag_path, loops, statics);
  nodelet::Loader manager(ros::NodeHandle("~"));
  ros::AsyncSpinner spinner(2);
  spinner.start();
  if (static_cast<int>(frames.size()) <= warmup)
  {
    std::cerr << "loop_bench: " << frames.size() << " frames, not more than --warmup " << warmup << "\n";
    return 2;
  }
  std::cout << "loop_bench: " << frames.size() << " stereo frames (" << loops << " loops of " << bag_path << ")"
            << std::endl;
  LoopBench bench(nh, frames, in_flight, warmup, timeout);
  bench.publishStatic(statics);

  const Sink rect_left{"stereo/left/image_rect_color", "rectification (debayer + rectify, left)", "", true, ""};
  const Sink rect_right{"stereo/right/image_rect_color", "rectification (debayer + rectify, right)", "", true, ""};
  std::map<std::string, Phase> phases;
  phases["frontend"] = {"frontend", {rect_left, rect_right}, {}};
  phases["ours"] = {"ours",
                    {rect_left,
                     rect_right,
                     {"stereo/disparity", "stereo: BioBin multi-scale", "stereo/right/image_rect_color", true,
                      "/stereo/biobin_disparity"},
                     {"saliency/regions", "saliency", "stereo/left/image_rect_color", true, "/saliency"},
                     {"objects", "recognition", "stereo/left/image_rect_color", true, "/recognition"},
                     {"keypoints", "V1 keypoints", "stereo/left/image_rect_color", true, "/v1_cells"}},
                    {"memory/stm"}};
  phases["peer"] = {"peer",
                    {rect_left,
                     rect_right,
                     {"peer/disparity", "stereo: stereo_image_proc SGBM", "stereo/right/image_rect_color", true, ""},
                     {"peer/saliency/regions", "saliency: spectral residual", "stereo/left/image_rect_color", true, ""},
                     {"peer/objects", "saliency + recognition: spectral residual, ORB + BFMatcher",
                      "stereo/left/image_rect_color", true, "/peer_recognition"}},
                    {}};

  nlohmann::ordered_json figures;
  figures["command"] = "roslaunch biovision_bringup loop_bench.launch (loop_bench " + options.command() + ")";
  figures["bag"] = std::filesystem::weakly_canonical(bag_path).string();  // no launch-file "../.."
  figures["hardware_threads"] = std::thread::hardware_concurrency();
  figures["opencv_threads"] = opencv_threads;
  figures["fft_measure_after"] = fft_measure_after;
  int manager_threads = 0;
  ros::param::get("~num_worker_threads", manager_threads);  // nodelet::Loader's own parameter (0: one per core)
  figures["manager_threads"] = manager_threads > 0 ? manager_threads
                                                   : static_cast<int>(std::thread::hardware_concurrency());
  // Which instruction set each SIMD stage of ours ran (the same libraries are loaded into this process).
  figures["simd"] = {
      {"cpu", biovision_common::CpuFeatures::host().describe()},
      {"biobin_cost_volume", biovision_stereo::costSimdName(biovision_stereo::bestCostSimd())},
      {"biobin_hamming", "byte windows (" + biovision_stereo::costSimdName(biovision_stereo::bestCostSimd()) + ")"},
      {"biobin_semi_global_aggregation",
       biovision_stereo::SemiGlobalAggregation::name(biovision_stereo::SemiGlobalAggregation::bestSimd())},
      {"recognition_projection", biovision_recognition::toString(biovision_recognition::bestProjectionPath())},
      {"recognition_matcher", biovision_common::toString(biovision_common::bestHammingPath())}};
  figures["in_flight"] = in_flight;
  int status = 0;
  std::vector<std::string> names;
  std::stringstream list(phases_list);
  for (std::string name; std::getline(list, name, ',');)
  {
    if (!phases.count(name))
    {
      std::cerr << "loop_bench: unknown phase '" << name << "'\n";
      return 2;
    }
    names.push_back(name);
  }
  // Every round runs the phases one after the other; a ratio compares phases of the same round only.
  struct Round
  {
    nlohmann::ordered_json phases, stage_rows;
    double ratio = std::numeric_limits<double>::quiet_NaN();  // peer / ours frames per second
  };
  std::vector<Round> results;
  for (int r = 0; r < rounds && ros::ok(); ++r)
  {
    Round round;
    for (const std::string& name : names)
    {
      try
      {
        round.phases[name] = bench.run(phases[name]);
        std::cout << "round " << r + 1 << "/" << rounds << ", " << name << ": " << round.phases[name].dump(2)
                  << std::endl;
      }
      catch (const std::exception& e)
      {
        std::cerr << "loop_bench: " << e.what() << "\n";
        round.phases[name] = {{"error", e.what()}};
        status = 1;
      }
    }
    round.stage_rows = bench.stage_rows_;
    const auto& ph = round.phases;
    if (ph.contains("ours") && ph.contains("peer") && ph["ours"].contains("frames_per_s") &&
        ph["peer"].contains("frames_per_s") && ph["ours"]["frames_per_s"].get<double>() > 0)
      round.ratio = ph["peer"]["frames_per_s"].get<double>() / ph["ours"]["frames_per_s"].get<double>();
    results.push_back(std::move(round));
  }
  // The reported round: the median ratio's (the last round when no round has a ratio).
  size_t chosen = results.empty() ? 0 : results.size() - 1;
  std::vector<size_t> with_ratio;
  for (size_t i = 0; i < results.size(); ++i)
    if (std::isfinite(results[i].ratio))
      with_ratio.push_back(i);
  if (!with_ratio.empty())
  {
    std::sort(with_ratio.begin(), with_ratio.end(),
              [&](size_t a, size_t b) { return results[a].ratio < results[b].ratio; });
    chosen = with_ratio[(with_ratio.size() - 1) / 2];
  }
  figures["fft_plans_measured"] = biovision_v1::FourierTransform::plansMeasured();  // by every phase
  figures["rounds"] = results.size();
  if (!results.empty())
  {
    for (const auto& [name, phase] : results[chosen].phases.items())
      figures[name] = phase;
    if (std::isfinite(results[chosen].ratio))
    {
      nlohmann::json ratios = nlohmann::json::array();
      for (const Round& round : results)
        ratios.push_back(std::isfinite(round.ratio) ? nlohmann::json(std::round(round.ratio * 1000) / 1000)
                                                    : nlohmann::json());  // 3 digits: a list prints whole
      figures["ours_vs_peer_time_rounds"] = ratios;
      figures["ours_vs_peer_time"] = results[chosen].ratio;
      figures["goal"] = ">= 15 frames/s end to end on 2 cores, and ours_vs_peer_time <= 1.5";
    }
    for (const auto& [k, v] : results[chosen].stage_rows.items())
      figures[k] = v;
  }
  figures["notes"] =
      "Phases on the same frames of the bag, one after the other, in one nodelet manager (this process), in "
      "`rounds` rounds: ours_vs_peer_time is the median of the rounds' ratios (ours_vs_peer_time_rounds), and "
      "every other figure is that round's. "
      "frames_per_s: frames published per wall second while at most in_flight were unfinished (a stage that drops "
      "a frame covers it with a later one); complete_frames_per_s: frames that got every output. Per stage: "
      "latency from the arrival of the stage's input (the rectified image; for the end to end row, the frame's "
      "publication) [ms]; cpu_ms_per_input: CPU of the nodelet's callback thread per input, plus its own worker "
      "threads' (BioBin's ParallelArena) (ScopedProcessingTimer; OpenCV's parallel_for_ on that thread with "
      "opencv_threads 1); '-' = Debian's "
      "nodelets (debayer, rectify, SGBM), not instrumented: their CPU is in unattributed_cpu_ms_per_frame. "
      "simd: the instruction set each of our SIMD stages ran on this CPU.";
  if (!json_path.empty())
    biovision_common::writeJsonFile(json_path, figures);
  spinner.stop();
  ros::shutdown();
  return status;
}
