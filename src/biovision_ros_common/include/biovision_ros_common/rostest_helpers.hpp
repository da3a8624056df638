#pragma once

// What the rostest gtests of BioVision nodes share: the test binary's main (RosTestRun), waiting on a
// condition in wall time (sim time may be paused), watching a node's diagnostics, collecting messages,
// and child processes.

#include <atomic>
#include <cmath>
#include <condition_variable>
#include <csignal>
#include <cstdlib>
#include <memory>
#include <mutex>
#include <string>
#include <vector>

#include <fcntl.h>
#include <sys/wait.h>
#include <unistd.h>

#include <diagnostic_msgs/DiagnosticArray.h>
#include <gtest/gtest.h>
#include <ros/callback_queue.h>
#include <ros/ros.h>
#include <sensor_msgs/JointState.h>

namespace biovision_ros_common
{
/// The main of a rostest gtest binary: initialises gtest and roscpp, keeps roscpp started for the whole
/// run and spins the global callback queue on `spinner_threads` threads (0 when the fixtures run their own
/// spinners). Without the run's own NodeHandle, the last NodeHandle of a fixture going away calls
/// ros::shutdown() — under the spinner's threads — and the next test restarts roscpp; a crash in that
/// rarely used path kills the binary before gtest writes its results (CI saw such deaths, rostest
/// reporting only "did not generate test results").
///
///   int main(int argc, char** argv) { return biovision_ros_common::RosTestRun(argc, argv, "my_test", 2).run(); }
class RosTestRun
{
public:
  RosTestRun(int& argc, char** argv, const std::string& node_name, unsigned spinner_threads)
  {
    testing::InitGoogleTest(&argc, argv);
    ros::init(argc, argv, node_name);
    nh_ = std::make_unique<ros::NodeHandle>();
    if (spinner_threads > 0)
    {
      spinner_ = std::make_unique<ros::AsyncSpinner>(spinner_threads);
      spinner_->start();
    }
  }
  RosTestRun(const RosTestRun&) = delete;
  RosTestRun& operator=(const RosTestRun&) = delete;
  /// Stops the spinner first, then shuts roscpp down (the NodeHandle was the last one).
  ~RosTestRun()
  {
    if (spinner_)
      spinner_->stop();
    spinner_.reset();
    nh_.reset();
    ros::shutdown();
  }
  ros::NodeHandle& nodeHandle() { return *nh_; }
  /// RUN_ALL_TESTS(); its result is main's exit code.
  int run() { return RUN_ALL_TESTS(); }

private:
  std::unique_ptr<ros::NodeHandle> nh_;
  std::unique_ptr<ros::AsyncSpinner> spinner_;
};

/// The position [rad or m] of joint `name` in `js`; NaN when there is no message, the joint is not named
/// or it has no position.
inline double jointPosition(const sensor_msgs::JointStateConstPtr& js, const std::string& name)
{
  if (js)
    for (size_t i = 0; i < js->name.size() && i < js->position.size(); ++i)
      if (js->name[i] == name)
        return js->position[i];
  return NAN;
}

/// Polls `condition` every 20 ms for up to `seconds` of wall time; true as soon as it holds.
template <typename Condition>
bool waitFor(Condition condition, double seconds)
{
  const ros::WallTime end = ros::WallTime::now() + ros::WallDuration(seconds);
  while (ros::ok() && ros::WallTime::now() < end)
  {
    if (condition())
      return true;
    ros::WallDuration(0.02).sleep();
  }
  return condition();
}

/// Watches /diagnostics for the statuses whose name contains `status_name`: how many arrived and the
/// highest level seen since the last clear(). Needs a spinner (ros::AsyncSpinner) running.
class DiagnosticsWatch
{
public:
  DiagnosticsWatch(ros::NodeHandle& nh, const std::string& status_name) : name_(status_name)
  {
    sub_ = nh.subscribe("/diagnostics", 50, &DiagnosticsWatch::onDiagnostics, this);
  }
  unsigned received() const { return received_; }
  bool sawError() const { return max_level_ >= diagnostic_msgs::DiagnosticStatus::ERROR; }
  std::string lastMessage() const
  {
    std::lock_guard<std::mutex> lock(mutex_);
    return last_message_;
  }
  /// The value of `key` in the last matching status ("" when it had none).
  std::string lastValue(const std::string& key) const
  {
    std::lock_guard<std::mutex> lock(mutex_);
    for (const auto& kv : last_values_)
      if (kv.key == key)
        return kv.value;
    return "";
  }
  void clear()
  {
    received_ = 0;
    max_level_ = 0;
  }

private:
  void onDiagnostics(const diagnostic_msgs::DiagnosticArrayConstPtr& msg)
  {
    for (const auto& s : msg->status)
      if (s.name.find(name_) != std::string::npos)
      {
        ++received_;
        if (s.level > max_level_)
          max_level_ = s.level;
        std::lock_guard<std::mutex> lock(mutex_);
        last_message_ = s.message;
        last_values_ = s.values;
      }
  }

  std::string name_;
  std::atomic<unsigned> received_{0};
  std::atomic<int> max_level_{0};
  mutable std::mutex mutex_;
  std::string last_message_;
  std::vector<diagnostic_msgs::KeyValue> last_values_;
  // Last: destroyed first, so a spinner thread's callback never writes into members already gone
  // (unsubscribing waits for a callback in progress).
  ros::Subscriber sub_;
};

/// A service server whose callback holds every call until release() (a node that accepted the call and
/// hangs), on a callback queue and two threads of its own so that the test's spinner stays free.
template <typename Service>
class HangingServiceServer
{
public:
  explicit HangingServiceServer(const std::string& name) : spinner_(2, &queue_)
  {
    ros::NodeHandle nh;
    nh.setCallbackQueue(&queue_);
    server_ = nh.advertiseService(name, &HangingServiceServer::serve, this);
    spinner_.start();
  }
  ~HangingServiceServer()
  {
    release();
    spinner_.stop();
  }
  HangingServiceServer(const HangingServiceServer&) = delete;
  HangingServiceServer& operator=(const HangingServiceServer&) = delete;
  /// Lets every held call and every later one return (with a default response).
  void release()
  {
    std::lock_guard<std::mutex> lock(mutex_);
    released_ = true;
    released_cv_.notify_all();
  }
  /// Calls that reached the callback.
  int entered() const { return entered_; }

private:
  bool serve(typename Service::Request&, typename Service::Response&)
  {
    ++entered_;
    std::unique_lock<std::mutex> lock(mutex_);
    released_cv_.wait(lock, [this] { return released_; });
    return true;
  }
  ros::CallbackQueue queue_;
  ros::AsyncSpinner spinner_;
  std::mutex mutex_;
  std::condition_variable released_cv_;
  bool released_ = false;
  std::atomic<int> entered_{0};
  ros::ServiceServer server_;  // last: shut down before what serve() uses
};

/// Keeps every message of one topic (bounded by `capacity`, oldest dropped).
template <typename Message>
class TopicProbe
{
public:
  TopicProbe(ros::NodeHandle& nh, const std::string& topic, size_t capacity = 1000) : capacity_(capacity)
  {
    sub_ = nh.subscribe<Message>(topic, 20, [this](const typename Message::ConstPtr& m) {
      std::lock_guard<std::mutex> lock(mutex_);
      if (messages_.size() == capacity_)
        messages_.erase(messages_.begin());
      messages_.push_back(m);
      ++count_;
    });
  }
  /// Messages received since start (not bounded by capacity).
  size_t count() const { return count_; }
  std::vector<typename Message::ConstPtr> messages() const
  {
    std::lock_guard<std::mutex> lock(mutex_);
    return messages_;
  }
  typename Message::ConstPtr last() const
  {
    std::lock_guard<std::mutex> lock(mutex_);
    return messages_.empty() ? nullptr : messages_.back();
  }
  /// Waits until `n` messages have arrived since start.
  bool waitForCount(size_t n, double seconds)
  {
    return waitFor([&] { return count_ >= n; }, seconds);
  }
  const ros::Subscriber& subscriber() const { return sub_; }

private:
  size_t capacity_;
  mutable std::mutex mutex_;
  std::vector<typename Message::ConstPtr> messages_;
  std::atomic<size_t> count_{0};
  ros::Subscriber sub_;  // last: destroyed before what its callback writes (see DiagnosticsWatch)
};
/// Starts `args` (argv[0] looked up on PATH) as a child process, with DISPLAY set to `display` unless empty
/// (an Xvfb for rviz) and its stdout and stderr in the file `log` unless empty. Returns its pid; the child
/// exits 127 when the program cannot be run.
inline pid_t spawnProcess(const std::vector<std::string>& args, const std::string& display, const std::string& log = "")
{
  // Everything allocated before fork(): the test is multi-threaded (spinners), and the child of a
  // multi-threaded process may only make async-signal-safe calls until it execs.
  std::vector<char*> argv;
  for (const auto& a : args)
    argv.push_back(const_cast<char*>(a.c_str()));
  argv.push_back(nullptr);
  const std::string display_variable = "DISPLAY=" + display;
  std::vector<char*> env;
  for (char** e = environ; *e; ++e)
    if (display.empty() || std::string(*e).rfind("DISPLAY=", 0) != 0)
      env.push_back(*e);
  if (!display.empty())
    env.push_back(const_cast<char*>(display_variable.c_str()));
  env.push_back(nullptr);
  const int fd = log.empty() ? -1 : ::open(log.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0644);
  const pid_t pid = fork();
  if (pid == 0)
  {
    if (fd >= 0)
    {
      dup2(fd, 1);
      dup2(fd, 2);
    }
    execvpe(argv[0], argv.data(), env.data());
    _exit(127);
  }
  if (fd >= 0)
    close(fd);
  return pid;
}

/// SIGTERM, up to 5 s to exit, then SIGKILL; reaps the child. A pid <= 0 is ignored.
inline void stopProcess(pid_t pid)
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

/// A child process of the test (spawnProcess), stopped (stopProcess) when it goes out of scope: a failed
/// ASSERT returns from the test early, and an rviz or Xvfb left running would load the next tests' CPU.
/// Declare the X server before its clients, so they are stopped first.
class ChildProcess
{
public:
  ChildProcess(const std::vector<std::string>& args, const std::string& display = "")
    : pid_(spawnProcess(args, display))
  {
  }
  ~ChildProcess() { stop(); }
  ChildProcess(const ChildProcess&) = delete;
  ChildProcess& operator=(const ChildProcess&) = delete;

  /// Whether it has not exited yet (an exited child is reaped here and not signalled later).
  bool running()
  {
    if (pid_ > 0 && waitpid(pid_, nullptr, WNOHANG) == pid_)
      pid_ = -1;
    return pid_ > 0;
  }
  void stop()
  {
    stopProcess(pid_);
    pid_ = -1;
  }

private:
  pid_t pid_;
};
}  // namespace biovision_ros_common
