// fit3dof: aerodynamic coefficients from 3DOF gas-bearing motion.
//
// The status line: it counts the fit's iterations, draws only after its
// delay, and erases itself at the end.

#include "fit3dof/progress.h"

#include <fcntl.h>
#include <unistd.h>

#include <string>

#include "fit3dof/config.h"
#include "fit3dof/fit.h"
#include "gtest/gtest.h"
#include "test_util.h"

namespace fit3dof {
namespace {

std::string Drain(int fd) {
  std::string text;
  char buffer[4096];
  for (ssize_t n; (n = ::read(fd, buffer, sizeof(buffer))) > 0;) {
    text.append(buffer, static_cast<size_t>(n));
  }
  return text;
}

TEST(Progress, FitsCountTheirIterations) {
  const long before = CurrentProgress().iterations;
  const FitResult r = Fit(
      LoadConfig(testing::SourcePath("configs/report/table6_sigma0.01.yaml")));
  const ProgressSnapshot after = CurrentProgress();
  EXPECT_GE(after.iterations - before, r.iterations);
  EXPECT_GT(after.probable_error, 0.0);
}

TEST(Progress, DrawsWhileTheWorkRunsAndErasesAtTheEnd) {
  int pipe_fds[2];
  ASSERT_EQ(::pipe(pipe_fds), 0);
  ::fcntl(pipe_fds[0], F_SETFL, O_NONBLOCK);
  {
    ProgressLine line("fit table6", pipe_fds[1], 0.0, 0.05);
    Fit(LoadConfig(
        testing::SourcePath("configs/report/table6_sigma0.01.yaml")));
    ::usleep(120000);
  }
  const std::string text = Drain(pipe_fds[0]);
  EXPECT_NE(text.find("\r\033[Kfit table6: "), std::string::npos) << text;
  EXPECT_NE(text.find(" iterations, probable error "), std::string::npos);
  EXPECT_EQ(text.substr(text.size() - 4), "\r\033[K");
  ::close(pipe_fds[0]);
  ::close(pipe_fds[1]);
}

TEST(Progress, SilentBeforeItsDelay) {
  int pipe_fds[2];
  ASSERT_EQ(::pipe(pipe_fds), 0);
  ::fcntl(pipe_fds[0], F_SETFL, O_NONBLOCK);
  { ProgressLine line("quick", pipe_fds[1], 30.0, 1.0); }
  EXPECT_EQ(Drain(pipe_fds[0]), "");
  ::close(pipe_fds[0]);
  ::close(pipe_fds[1]);
}

}  // namespace
}  // namespace fit3dof
