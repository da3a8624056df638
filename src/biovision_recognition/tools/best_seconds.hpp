#pragma once

#include <algorithm>
#include <chrono>

namespace biovision_recognition
{
/// The shortest wall time of `repeats` runs of f [s]: the benchmarks' timing (the best run is the one
/// least disturbed by other load on the machine).
template <typename F>
double bestSeconds(int repeats, F&& f)
{
  double best = 1e30;
  for (int r = 0; r < repeats; ++r)
  {
    const auto t0 = std::chrono::steady_clock::now();
    f();
    best = std::min(best, std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count());
  }
  return best;
}
}  // namespace biovision_recognition
