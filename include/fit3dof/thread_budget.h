// fit3dof: aerodynamic coefficients from 3DOF gas-bearing motion.
//
// One budget of computing threads for the whole process. A batch runs fits
// in parallel, a fit runs its multi-start in parallel, a basin study runs
// starts in parallel; nested, each with its own pool, a 16-core batch could
// run 16 x 8 threads. Instead every parallel loop borrows extra threads from
// this budget, as many as are free when it starts, and the calling thread
// always works too: a fit inside a busy batch runs its starts one after the
// other, the same fit alone on the machine spreads them over every core.
//
// Example Usage:
//
//   SetThreadBudget(8);              // --jobs=8; default: every core
//   ParallelFor(starts.size(), [&](int i) { outcomes[i] = Solve(i); });

#ifndef FIT3DOF_THREAD_BUDGET_H_
#define FIT3DOF_THREAD_BUDGET_H_

#include <functional>

namespace fit3dof {

// The most threads that compute at once, the calling threads included
// (at least 1). Set before starting parallel work.
void SetThreadBudget(int threads);
int ThreadBudget();

// Threads of the budget not lent out now (for tests and logs).
int FreeThreads();

// Runs task(i) for every i in [0, n), each exactly once, on the calling
// thread plus up to n - 1 threads borrowed from the budget; returns when
// all are done. A borrowed thread goes back to the budget as soon as no
// index is left for it. The task must not throw.
void ParallelFor(int n, const std::function<void(int)>& task);

// Threads of the budget held for work that starts threads of its own
// (Ceres' evaluation of a problem's residual blocks): up to `wanted`
// beyond the calling thread, as many as are free now (perhaps none),
// given back when the lease ends.
//
//   ThreadLease lease(1);
//   options.num_threads = 1 + lease.count();
class ThreadLease {
 public:
  explicit ThreadLease(int wanted);
  ~ThreadLease();
  ThreadLease(const ThreadLease&) = delete;
  ThreadLease& operator=(const ThreadLease&) = delete;

  int count() const { return count_; }

 private:
  int count_;
};

}  // namespace fit3dof

#endif  // FIT3DOF_THREAD_BUDGET_H_
