// fit3dof: aerodynamic coefficients from 3DOF gas-bearing motion.
//
// The status line of a long fit, diagnosis or basin study (progress.h).

#include "fit3dof/progress.h"

#include <unistd.h>

#include <chrono>
#include <cstdio>

namespace fit3dof {
namespace {

std::atomic<long> iterations{0};
std::atomic<double> latest_probable_error{0.0};

void WriteAll(int fd, const std::string& text) {
  size_t done = 0;
  while (done < text.size()) {
    const ssize_t n = ::write(fd, text.data() + done, text.size() - done);
    if (n <= 0) return;  // a closed terminal is no reason to fail a fit
    done += static_cast<size_t>(n);
  }
}

}  // namespace

void CountIteration(double probable_error) {
  iterations.fetch_add(1, std::memory_order_relaxed);
  latest_probable_error.store(probable_error, std::memory_order_relaxed);
}

ProgressSnapshot CurrentProgress() {
  return {iterations.load(std::memory_order_relaxed),
          latest_probable_error.load(std::memory_order_relaxed)};
}

ProgressLine::ProgressLine(std::string name, double delay)
    : ProgressLine(std::move(name),
                   ::isatty(STDERR_FILENO) ? STDERR_FILENO : -1,
                   delay,
                   1.0) {}

ProgressLine::ProgressLine(std::string name,
                           int fd,
                           double delay,
                           double interval)
    : name_(std::move(name)),
      fd_(fd),
      delay_(delay),
      interval_(interval),
      first_iterations_(CurrentProgress().iterations) {
  if (fd_ >= 0) thread_ = std::thread([this] { Run(); });
}

ProgressLine::~ProgressLine() {
  if (!thread_.joinable()) return;
  {
    std::lock_guard<std::mutex> lock(mutex_);
    done_ = true;
  }
  wake_.notify_all();
  thread_.join();
  if (drawn_) WriteAll(fd_, "\r\033[K");
}

void ProgressLine::Run() {
  const auto start = std::chrono::steady_clock::now();
  std::unique_lock<std::mutex> lock(mutex_);
  auto next = start + std::chrono::duration<double>(delay_);
  while (!wake_.wait_until(lock, next, [this] { return done_; })) {
    const double elapsed =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start)
            .count();
    Draw(elapsed);
    next += std::chrono::duration_cast<std::chrono::steady_clock::duration>(
        std::chrono::duration<double>(interval_));
  }
}

void ProgressLine::Draw(double elapsed) {
  const ProgressSnapshot now = CurrentProgress();
  char line[256];
  std::snprintf(line,
                sizeof(line),
                "\r\033[K%s: %.0f s, %ld iterations, probable error %.4g",
                name_.c_str(),
                elapsed,
                now.iterations - first_iterations_,
                now.probable_error);
  WriteAll(fd_, line);
  drawn_ = true;
}

}  // namespace fit3dof
