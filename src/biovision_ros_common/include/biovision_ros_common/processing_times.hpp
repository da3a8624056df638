#pragma once

#include <map>
#include <mutex>
#include <string>

#include <time.h>

namespace biovision_ros_common
{
/// Per-stage processing totals of every nodelet in this process (one nodelet manager), for benchmarks
/// that run the graph in their own process (biovision_bringup's loop_bench): each nodelet times the
/// callback that does its work with a ScopedProcessingTimer, the benchmark reads snapshot() before and
/// after a run. CPU time is the calling thread's (CLOCK_THREAD_CPUTIME_ID), so work a stage hands to
/// other threads (OpenCV's parallel_for_ pool) is counted only when that pool runs on the calling thread
/// (cv::setNumThreads(1), as loop_bench does), plus what the stage adds with addCpuSeconds (its own
/// ParallelArena's helper threads). Thread-safe; costs one mutex per processed input.
class ProcessingTimes
{
public:
  struct Totals
  {
    unsigned long inputs = 0;   ///< inputs processed
    double cpu_seconds = 0.0;   ///< [s] thread CPU time
    double wall_seconds = 0.0;  ///< [s] wall time in the callback
  };

  /// The process's registry.
  static ProcessingTimes& instance();

  /// Adds one processed input of `stage` (a nodelet's name).
  void record(const std::string& stage, double cpu_seconds, double wall_seconds);
  /// Totals per stage since start.
  std::map<std::string, Totals> snapshot() const;

private:
  mutable std::mutex mutex_;
  std::map<std::string, Totals> totals_;
};

/// Times its scope (CPU of the calling thread and wall) and records it under `stage` when it ends.
class ScopedProcessingTimer
{
public:
  explicit ScopedProcessingTimer(std::string stage);
  ~ScopedProcessingTimer();
  /// Adds CPU the stage spent on other threads in this scope ([s], e.g. its ParallelArena's helpers).
  void addCpuSeconds(double seconds) { extra_cpu_seconds_ += seconds; }
  ScopedProcessingTimer(const ScopedProcessingTimer&) = delete;
  ScopedProcessingTimer& operator=(const ScopedProcessingTimer&) = delete;

private:
  std::string stage_;
  timespec cpu_start_{}, wall_start_{};
  double extra_cpu_seconds_ = 0.0;
};
}  // namespace biovision_ros_common
