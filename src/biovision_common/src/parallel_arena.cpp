#include "biovision_common/parallel_arena.hpp"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <ctime>
#include <stdexcept>
#include <string>
#include <thread>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

namespace biovision_common
{
struct ParallelArena::Impl
{
  int threads = 1;
  std::unique_ptr<tbb::task_arena> arena;  // null when threads == 1
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
  impl_->threads = threads > 0 ? threads : std::max(1, static_cast<int>(std::thread::hardware_concurrency()));
  if (impl_->threads > 1)
    impl_->arena = std::make_unique<tbb::task_arena>(impl_->threads);
}

ParallelArena::~ParallelArena() = default;

int ParallelArena::threads() const
{
  return impl_->threads;
}

void ParallelArena::run(const std::function<void()>& f)
{
  if (!impl_->arena)
  {
    f();
    return;
  }
  // The thread-locals are set inside execute(): f runs on whichever thread the arena gives it.
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
  if (range.empty())
    return;
  if (loop_depth > 0)
  {
    body(range);  // nested: serially, as OpenCV does
    return;
  }
  ParallelArena::Impl* arena = current_arena;
  if (arena == nullptr)
  {
    cv::parallel_for_(range, body, nstripes);
    return;
  }
  const long long length = range.end - range.start;
  const long long stripes = nstripes <= 0.0 ? length : std::clamp<long long>(std::llround(nstripes), 1LL, length);
  const std::thread::id caller = std::this_thread::get_id();
  tbb::parallel_for(tbb::blocked_range<long long>(0, stripes), [&](const tbb::blocked_range<long long>& part) {
    const cv::Range r(range.start + static_cast<int>(part.begin() * length / stripes),
                      part.end() >= stripes ? range.end
                                            : range.start + static_cast<int>(part.end() * length / stripes));
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
