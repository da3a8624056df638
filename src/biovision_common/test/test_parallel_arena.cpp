#include <gtest/gtest.h>

#include <atomic>
#include <chrono>
#include <mutex>
#include <set>
#include <stdexcept>
#include <thread>
#include <vector>

#include "biovision_common/parallel_arena.hpp"

using biovision_common::ParallelArena;
using biovision_common::parallelFor;

namespace
{
// How often each index of [start, end) was visited by one parallelFor, for each nstripes.
void expectEachIndexOnce(int start, int end)
{
  for (double stripes : {-1.0, 0.0, 1.0, 3.0, 7.5, 1000.0})
  {
    std::vector<std::atomic<int>> visits(end - start);
    parallelFor(
        cv::Range(start, end),
        [&](const cv::Range& r) {
          ASSERT_LE(start, r.start);
          ASSERT_LE(r.end, end);
          for (int i = r.start; i < r.end; ++i)
            ++visits[i - start];
        },
        stripes);
    for (int i = 0; i < end - start; ++i)
      EXPECT_EQ(visits[i], 1) << "index " << start + i << ", nstripes " << stripes;
  }
}

// Burns about `n` iterations of CPU so that a helper thread has time to join.
double spin(int n)
{
  volatile double x = 0.0;
  for (int i = 0; i < n; ++i)
    x = x + 1e-9 * i;
  return x;
}
}  // namespace

TEST(ParallelArena, CoversTheRangeOnceInsideAndOutside)
{
  expectEachIndexOnce(3, 250);  // outside: cv::parallel_for_
  ParallelArena arena(2);
  arena.run([] { expectEachIndexOnce(3, 250); });
  arena.run([] { expectEachIndexOnce(-5, -4); });
  ParallelArena single(1);
  single.run([] { expectEachIndexOnce(0, 17); });
}

TEST(ParallelArena, ThreadsAreClampedToTheCpusAndRefuseNegative)
{
  const int cpus = ParallelArena(0).threads();
  EXPECT_GE(cpus, 1);
  EXPECT_LE(cpus, std::max(1, static_cast<int>(std::thread::hardware_concurrency())));
  EXPECT_EQ(ParallelArena(1).threads(), 1);
  EXPECT_EQ(ParallelArena(1000).threads(), cpus);  // TBB's pool never grows beyond them
  EXPECT_THROW(ParallelArena(-1), std::invalid_argument);
}

TEST(ParallelArena, AnInvertedRangeGoesToTheBodyOnce)
{
  ParallelArena arena(2);
  for (bool inside : {false, true})
  {
    int calls = 0;
    cv::Range seen;
    const auto loop = [&] {
      parallelFor(
          cv::Range(5, 2),
          [&](const cv::Range& r) {
            ++calls;
            seen = r;
          },
          3.0);
    };
    if (inside)
      arena.run(loop);
    else
      loop();
    EXPECT_EQ(calls, 1) << (inside ? "inside" : "outside");
    EXPECT_EQ(seen, cv::Range(5, 2));
  }
}

TEST(ParallelArena, CallersFromSeveralThreadsTakeTurns)
{
  ParallelArena arena(2);
  std::atomic<int> inside{0}, most{0}, failures{0};
  std::vector<std::thread> callers;
  for (int c = 0; c < 3; ++c)
    callers.emplace_back([&] {
      for (int round = 0; round < 20; ++round)
        arena.run([&] {
          const int now = ++inside;
          most = std::max(most.load(), now);
          std::this_thread::sleep_for(std::chrono::microseconds(300));  // time for another caller to come in
          std::vector<std::atomic<int>> visits(97);
          parallelFor(cv::Range(0, 97), [&](const cv::Range& r) {
            for (int i = r.start; i < r.end; ++i)
              ++visits[i];
          });
          for (auto& v : visits)
            failures += v != 1;
          --inside;
        });
    });
  for (auto& t : callers)
    t.join();
  EXPECT_EQ(failures, 0);
  EXPECT_EQ(most, 1);  // one run() at a time
}

TEST(ParallelArena, RunInsideALoopBodyJustCallsF)
{
  ParallelArena arena(2);
  std::atomic<int> inner_calls{0};
  arena.run([&] {
    parallelFor(cv::Range(0, 4), [&](const cv::Range& outer) {
      for (int i = outer.start; i < outer.end; ++i)
        arena.run([&] { parallelFor(cv::Range(0, 10), [&](const cv::Range&) { ++inner_calls; }); });
    });
  });
  EXPECT_EQ(inner_calls, 4);  // each inner loop one serial call, and no deadlock on the run() lock
}

TEST(ParallelArena, NestedLoopsRunSeriallyOnTheirThread)
{
  ParallelArena arena(2);
  std::atomic<int> inner_calls{0}, visited{0};
  std::atomic<bool> other_thread{false};
  arena.run([&] {
    parallelFor(cv::Range(0, 8), [&](const cv::Range& outer) {
      const std::thread::id me = std::this_thread::get_id();
      for (int i = outer.start; i < outer.end; ++i)
        parallelFor(cv::Range(0, 10), [&](const cv::Range& inner) {
          ++inner_calls;  // one call with the whole range: serial
          visited += inner.size();
          if (std::this_thread::get_id() != me)
            other_thread = true;
        });
    });
  });
  EXPECT_EQ(inner_calls, 8);
  EXPECT_EQ(visited, 80);
  EXPECT_FALSE(other_thread);
}

TEST(ParallelArena, ExceptionsReachTheCaller)
{
  ParallelArena arena(2);
  EXPECT_THROW(arena.run([] {
    parallelFor(cv::Range(0, 100), [](const cv::Range& r) {
      if (r.start <= 50 && 50 < r.end)
        throw std::runtime_error("element 50");
    });
  }),
               std::runtime_error);
  EXPECT_THROW(arena.run([] { throw std::logic_error("in run"); }), std::logic_error);
  // The arena is still usable, and a loop outside it no longer uses it.
  arena.run([] { expectEachIndexOnce(0, 64); });
  expectEachIndexOnce(0, 64);
}

TEST(ParallelArena, HelperCpuIsOnlyOtherThreads)
{
  ParallelArena single(1);
  single.run([] { parallelFor(cv::Range(0, 64), [](const cv::Range& r) { spin(20000 * r.size()); }); });
  EXPECT_EQ(single.helperCpuSeconds(), 0.0);  // no arena: everything ran on the caller (or OpenCV's pool)

  ParallelArena arena(2);
  std::mutex mutex;
  std::set<std::thread::id> threads;
  for (int round = 0; round < 20 && threads.size() < 2; ++round)
    arena.run([&] {
      parallelFor(cv::Range(0, 64), [&](const cv::Range& r) {
        spin(200000 * r.size());
        std::lock_guard<std::mutex> lock(mutex);
        threads.insert(std::this_thread::get_id());
      });
    });
  ASSERT_LE(threads.size(), 2u);  // never more threads than the arena's concurrency
  if (threads.size() == 2)
    EXPECT_GT(arena.helperCpuSeconds(), 0.0);
  else
    EXPECT_EQ(arena.helperCpuSeconds(), 0.0);  // the machine never let the helper join: nothing to count
}

int main(int argc, char** argv)
{
  testing::InitGoogleTest(&argc, argv);
  return RUN_ALL_TESTS();
}
