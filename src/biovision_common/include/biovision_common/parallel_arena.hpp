#pragma once

#include <functional>
#include <memory>

#include <opencv2/core.hpp>

namespace biovision_common
{
/// A pipeline stage's own share of the process's worker threads (a oneTBB task arena): the stage on the
/// critical path of a frame (BioBin stereo in the perception loop) can use every core while the process's
/// OpenCV parallel_for_ stays at its own setting. cv::setNumThreads is process-wide, and OpenCV runs every
/// parallel_for_ serially while another thread is inside one, so in one nodelet manager the stage that
/// needs the cores cannot get them from OpenCV (issue #21's loop: BioBin 40 ms on one thread, the second
/// core about a third busy). The workers are TBB's process-wide pool, which Debian's OpenCV also uses.
///
/// Loops written with parallelFor() run on the arena whose run() the calling thread is inside; anywhere
/// else they are cv::parallel_for_. A parallelFor() inside another one's body runs serially on its thread,
/// as OpenCV's nested parallel_for_ does. OpenCV calls inside a body are not nested for OpenCV: with an
/// OpenCV thread count above 1 they may run on OpenCV's own pool (CPU the helper count misses). As for
/// cv::parallel_for_, a loop's result must not depend on how its range is split.
/// run() takes one caller at a time (others wait); loops go through parallelFor(), not cv::parallel_for_,
/// whose body would see this arena only on the calling thread.
class ParallelArena
{
public:
  /// threads: the arena's concurrency, the calling thread included (0: all TBB offers, i.e. the CPUs this
  /// process may run on; more is clamped to that, since TBB's pool never grows beyond it; 1: no arena,
  /// run() calls f directly and parallelFor() is cv::parallel_for_). Throws std::invalid_argument if
  /// negative.
  explicit ParallelArena(int threads);
  ~ParallelArena();
  ParallelArena(const ParallelArena&) = delete;
  ParallelArena& operator=(const ParallelArena&) = delete;

  /// The arena's concurrency after clamping (>= 1).
  int threads() const;

  /// Runs f on the calling thread with this arena current, after any other caller's run() has ended;
  /// inside a parallelFor() body it just calls f. Exceptions from f (or from a loop body inside it)
  /// propagate.
  void run(const std::function<void()>& f);

  /// [s] CPU time that loop bodies of this arena spent on threads other than the one inside run(), since
  /// construction: what a per-thread CPU clock around run() misses (CLOCK_THREAD_CPUTIME_ID per chunk).
  double helperCpuSeconds() const;

  struct Impl;

private:
  std::unique_ptr<Impl> impl_;
};

/// cv::parallel_for_'s contract: body is called on disjoint sub-ranges that cover `range` once, the range
/// split into about `nstripes` stripes (<= 0: as many as elements; an inverted range goes to body once).
/// On the current ParallelArena when the calling thread is inside one's run(), serially inside another
/// parallelFor()'s body, otherwise cv::parallel_for_ itself. Exceptions from body propagate to the caller.
void parallelFor(const cv::Range& range, const std::function<void(const cv::Range&)>& body, double nstripes = -1.0);
}  // namespace biovision_common
