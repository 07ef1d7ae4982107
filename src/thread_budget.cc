// fit3dof: aerodynamic coefficients from 3DOF gas-bearing motion.
//
// One budget of threads for the process (thread_budget.h), shared by the
// batch, multi-start and basin studies.

#include "fit3dof/thread_budget.h"

#include <algorithm>
#include <atomic>
#include <thread>
#include <vector>

#include "glog/logging.h"

namespace fit3dof {
namespace {

int DefaultBudget() {
  return std::max(1, static_cast<int>(std::thread::hardware_concurrency()));
}

std::atomic<int> budget{DefaultBudget()};
// Threads that may still be lent: the budget less one for the thread that
// started the work (it always computes) and less those lent out.
std::atomic<int> lendable{DefaultBudget() - 1};

// Takes up to `wanted` threads from the budget; returns how many.
int Borrow(int wanted) {
  int free = lendable.load();
  while (free > 0 && wanted > 0) {
    const int take = std::min(free, wanted);
    if (lendable.compare_exchange_weak(free, free - take)) return take;
  }
  return 0;
}

}  // namespace

void SetThreadBudget(int threads) {
  CHECK_GE(threads, 1);
  const int change = threads - budget.exchange(threads);
  lendable += change;
}

int ThreadBudget() { return budget.load(); }

int FreeThreads() { return std::max(0, lendable.load()); }

void ParallelFor(int n, const std::function<void(int)>& task) {
  if (n <= 0) return;
  std::atomic<int> next{0};
  auto work = [&] {
    for (int i = next++; i < n; i = next++) task(i);
  };
  const int extra = Borrow(n - 1);
  std::vector<std::thread> threads;
  threads.reserve(extra);
  for (int t = 0; t < extra; ++t) {
    threads.emplace_back([&] {
      work();
      ++lendable;  // back to the budget as soon as nothing is left to do
    });
  }
  work();
  for (std::thread& t : threads) t.join();
}

ThreadLease::ThreadLease(int wanted) : count_(Borrow(wanted)) {}

ThreadLease::~ThreadLease() { lendable += count_; }

}  // namespace fit3dof
