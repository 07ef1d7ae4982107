// fit3dof: aerodynamic coefficients from 3DOF gas-bearing motion.
//
// The thread budget: nested parallel loops never compute on more threads
// than the budget, every index runs once, and borrowed threads come back.

#include "fit3dof/thread_budget.h"

#include <atomic>
#include <chrono>
#include <thread>
#include <vector>

#include "gtest/gtest.h"

namespace fit3dof {
namespace {

// Counts tasks running at once and the most seen.
struct Gauge {
  std::atomic<int> now{0}, most{0};
  void Enter() {
    const int n = ++now;
    for (int m = most.load(); n > m && !most.compare_exchange_weak(m, n);) {
    }
  }
  void Leave() { --now; }
};

void Busy() { std::this_thread::sleep_for(std::chrono::milliseconds(2)); }

TEST(ThreadBudget, NestedLoopsShareOneBudget) {
  for (int threads : {1, 2, 3, 8}) {
    SetThreadBudget(threads);
    Gauge gauge;
    std::vector<std::atomic<int>> ran(6 * 10);
    // A batch of 6 runs, each a multi-start of 10: 60 pieces of work.
    ParallelFor(6, [&](int run) {
      ParallelFor(10, [&](int start) {
        gauge.Enter();
        Busy();
        ++ran[10 * run + start];
        gauge.Leave();
      });
    });
    for (const auto& r : ran) EXPECT_EQ(r.load(), 1);
    EXPECT_LE(gauge.most.load(), threads) << "budget " << threads;
    EXPECT_EQ(FreeThreads(), threads - 1) << "budget " << threads;
  }
}

// A loop started while the budget is lent out still finishes, on its own
// thread.
TEST(ThreadBudget, AnExhaustedBudgetRunsOnTheCallingThread) {
  SetThreadBudget(2);
  std::atomic<int> sum{0}, arrived{0}, finished{0};
  ParallelFor(2, [&](int outer) {
    // Both outer tasks are running (the budget is all lent) before either
    // starts its inner loop, and neither ends before both inner loops have:
    // a borrowed thread goes back as soon as its outer task ends, and the
    // other inner loop, started later, could take it.
    ++arrived;
    while (arrived.load() < 2) std::this_thread::yield();
    const std::thread::id caller = std::this_thread::get_id();
    ParallelFor(5, [&](int i) {
      EXPECT_EQ(std::this_thread::get_id(), caller);
      sum += 10 * outer + i;
    });
    ++finished;
    while (finished.load() < 2) std::this_thread::yield();
  });
  EXPECT_EQ(sum.load(), 2 * (0 + 1 + 2 + 3 + 4) + 5 * 10);
}

// A lease takes what is free, at most what it asks for, and gives it
// back when it ends; a loop started meanwhile gets only the rest.
TEST(ThreadBudget, ALeaseHoldsThreadsUntilItEnds) {
  SetThreadBudget(3);
  {
    const ThreadLease lease(1);
    EXPECT_EQ(lease.count(), 1);
    EXPECT_EQ(FreeThreads(), 1);
    const ThreadLease more(5);
    EXPECT_EQ(more.count(), 1);
    EXPECT_EQ(FreeThreads(), 0);
    const ThreadLease none(1);
    EXPECT_EQ(none.count(), 0);
    const std::thread::id caller = std::this_thread::get_id();
    ParallelFor(4, [&](int) { EXPECT_EQ(std::this_thread::get_id(), caller); });
  }
  EXPECT_EQ(FreeThreads(), 2);
}

}  // namespace
}  // namespace fit3dof
