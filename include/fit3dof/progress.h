// fit3dof: aerodynamic coefficients from 3DOF gas-bearing motion.
//
// A status line for fits that take more than a few seconds (a long record,
// a multi-start from poor guesses): elapsed time, Levenberg-Marquardt
// iterations taken so far and the latest probable error, redrawn once a
// second on a terminal and erased when the work ends. The fit's iteration
// callback counts iterations here (from every thread of a multi-start);
// the command that runs the fit owns the line.
//
// Example Usage:
//
//   {
//     ProgressLine line("run12");  // silent unless stderr is a terminal
//     result = Fit(c);
//   }                              // line erased

#ifndef FIT3DOF_PROGRESS_H_
#define FIT3DOF_PROGRESS_H_

#include <atomic>
#include <condition_variable>
#include <mutex>
#include <string>
#include <thread>

namespace fit3dof {

// Called by the fit once per Levenberg-Marquardt iteration. Thread-safe.
void CountIteration(double probable_error);

struct ProgressSnapshot {
  long iterations = 0;
  double probable_error = 0.0;  // of the latest iteration counted
};
ProgressSnapshot CurrentProgress();

class ProgressLine {
 public:
  // Draws on stderr if it is a terminal, after `delay` seconds.
  explicit ProgressLine(std::string name, double delay = 3.0);
  // Draws on `fd` whether or not it is a terminal (for tests).
  ProgressLine(std::string name, int fd, double delay, double interval);
  ~ProgressLine();

  ProgressLine(const ProgressLine&) = delete;
  ProgressLine& operator=(const ProgressLine&) = delete;

 private:
  void Run();
  void Draw(double elapsed);

  std::string name_;
  int fd_ = -1;  // -1: nothing to draw on
  double delay_;
  double interval_;
  long first_iterations_;
  bool drawn_ = false;
  bool done_ = false;
  std::mutex mutex_;
  std::condition_variable wake_;
  std::thread thread_;
};

}  // namespace fit3dof

#endif  // FIT3DOF_PROGRESS_H_
