#include "biovision_ros_common/processing_times.hpp"

#include <utility>

namespace biovision_ros_common
{
namespace
{
double seconds(const timespec& t)
{
  return double(t.tv_sec) + 1e-9 * double(t.tv_nsec);
}
}  // namespace

ProcessingTimes& ProcessingTimes::instance()
{
  static ProcessingTimes times;
  return times;
}

void ProcessingTimes::record(const std::string& stage, double cpu_seconds, double wall_seconds)
{
  std::lock_guard<std::mutex> lock(mutex_);
  Totals& t = totals_[stage];
  ++t.inputs;
  t.cpu_seconds += cpu_seconds;
  t.wall_seconds += wall_seconds;
}

std::map<std::string, ProcessingTimes::Totals> ProcessingTimes::snapshot() const
{
  std::lock_guard<std::mutex> lock(mutex_);
  return totals_;
}

ScopedProcessingTimer::ScopedProcessingTimer(std::string stage) : stage_(std::move(stage))
{
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &cpu_start_);
  clock_gettime(CLOCK_MONOTONIC, &wall_start_);
}

ScopedProcessingTimer::~ScopedProcessingTimer()
{
  timespec cpu{}, wall{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &cpu);
  clock_gettime(CLOCK_MONOTONIC, &wall);
  ProcessingTimes::instance().record(stage_, seconds(cpu) - seconds(cpu_start_) + extra_cpu_seconds_,
                                     seconds(wall) - seconds(wall_start_));
}
}  // namespace biovision_ros_common
