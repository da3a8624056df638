#include "biovision_common/parallel_arena.hpp"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <ctime>
#include <mutex>
#include <stdexcept>
#include <string>
#include <thread>

#include <tbb/blocked_range.h>
#include <tbb/info.h>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

namespace biovision_common
{
struct ParallelArena::Impl
{
  int threads = 1;
  std::unique_ptr<tbb::task_arena> arena;  // null when threads == 1
  // One run() at a time: a second caller of task_arena::execute without a free slot has its functor queued
  // and run by whichever thread of the arena takes it, possibly inside the first caller's loop.
  std::mutex run_mutex;
  std::atomic<long long> helper_cpu_ns{0};
};

namespace
{
thread_local ParallelArena::Impl* current_arena = nullptr;  // the arena whose run() this thread is inside
thread_local int loop_depth = 0;                            // > 0 inside a parallelFor() body on this thread

long long threadCpuNanoseconds()
{
  timespec t{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &t);
  return static_cast<long long>(t.tv_sec) * 1000000000LL + t.tv_nsec;
}

// Sets a thread-local for a scope and restores it when the scope ends, exceptions included.
template <typename T>
class ScopedValue
{
public:
  ScopedValue(T& variable, T value) : variable_(variable), previous_(variable) { variable_ = value; }
  ~ScopedValue() { variable_ = previous_; }
  ScopedValue(const ScopedValue&) = delete;
  ScopedValue& operator=(const ScopedValue&) = delete;

private:
  T& variable_;
  T previous_;
};
}  // namespace

ParallelArena::ParallelArena(int threads) : impl_(std::make_unique<Impl>())
{
  if (threads < 0)
    throw std::invalid_argument("ParallelArena: threads " + std::to_string(threads) + " must be >= 0");
  // TBB's default concurrency respects the process's CPU affinity; its worker pool never grows beyond it,
  // so more threads than that would only be asked for, never given.
  const int available = std::max(1, tbb::info::default_concurrency());
  impl_->threads = threads > 0 ? std::min(threads, available) : available;
  if (impl_->threads > 1)
  {
    impl_->arena = std::make_unique<tbb::task_arena>(impl_->threads);
    impl_->arena->initialize();  // allocation errors here, not at the first frame
  }
}

ParallelArena::~ParallelArena() = default;

int ParallelArena::threads() const
{
  return impl_->threads;
}

void ParallelArena::run(const std::function<void()>& f)
{
  if (!impl_->arena || loop_depth > 0)
  {
    f();  // no arena, or inside a loop body: loops in f stay what they would be here (serial if nested)
    return;
  }
  const std::lock_guard<std::mutex> lock(impl_->run_mutex);
  // The thread-locals are set inside execute(), on the thread that runs f (the caller: its slot is free).
  impl_->arena->execute([&] {
    const ScopedValue<Impl*> arena(current_arena, impl_.get());
    const ScopedValue<int> depth(loop_depth, 0);
    f();
  });
}

double ParallelArena::helperCpuSeconds() const
{
  return 1e-9 * static_cast<double>(impl_->helper_cpu_ns.load(std::memory_order_relaxed));
}

void parallelFor(const cv::Range& range, const std::function<void(const cv::Range&)>& body, double nstripes)
{
  const long long length = static_cast<long long>(range.end) - range.start;
  if (length == 0)
    return;
  if (length < 0 || loop_depth > 0)
  {
    body(range);  // an inverted range once, as OpenCV does; nested: serially, as OpenCV does
    return;
  }
  ParallelArena::Impl* arena = current_arena;
  if (arena == nullptr)
  {
    cv::parallel_for_(range, body, nstripes);
    return;
  }
  // OpenCV's stripe count: <= 0 (or NaN) one per element, else clamped to [1, length] before rounding.
  const unsigned long long stripes = !(nstripes > 0.0)
                                         ? static_cast<unsigned long long>(length)
                                         : static_cast<unsigned long long>(std::max(
                                               1.0, std::round(std::min(nstripes, static_cast<double>(length)))));
  const unsigned long long span = static_cast<unsigned long long>(length);
  const auto offset = [&](unsigned long long stripe) {
    // stripe * span / stripes without overflow: both are below 2^32 for int ranges.
    return static_cast<int>(static_cast<long long>(range.start) + static_cast<long long>(stripe * span / stripes));
  };
  const std::thread::id caller = std::this_thread::get_id();
  tbb::parallel_for(tbb::blocked_range<unsigned long long>(0, stripes),
                    [&](const tbb::blocked_range<unsigned long long>& part) {
                      const cv::Range r(offset(part.begin()), part.end() >= stripes ? range.end : offset(part.end()));
                      if (r.empty())
                        return;
                      const bool helper = std::this_thread::get_id() != caller;
                      const long long start = helper ? threadCpuNanoseconds() : 0;
                      {
                        const ScopedValue<int> depth(loop_depth, loop_depth + 1);
                        body(r);
                      }
                      if (helper)
                        arena->helper_cpu_ns.fetch_add(threadCpuNanoseconds() - start, std::memory_order_relaxed);
                    });
}
}  // namespace biovision_common
