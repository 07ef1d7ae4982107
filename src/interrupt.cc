// fit3dof: aerodynamic coefficients from 3DOF gas-bearing motion.
//
// Stop requests (interrupt.h): SIGINT and SIGTERM set a flag the fits and
// the batch poll.

#include "fit3dof/interrupt.h"

#include <signal.h>

#include <atomic>

namespace fit3dof {
namespace {

std::atomic<bool> stop_requested{false};
static_assert(std::atomic<bool>::is_always_lock_free,
              "the signal handler needs a lock-free flag");

extern "C" void OnStopSignal(int signal_number) {
  stop_requested.store(true);
  // The next one takes the default action: a user can always force it.
  ::signal(signal_number, SIG_DFL);
}

}  // namespace

void InstallStopHandlers() {
  struct sigaction action = {};
  action.sa_handler = OnStopSignal;
  sigemptyset(&action.sa_mask);
  action.sa_flags = 0;
  ::sigaction(SIGINT, &action, nullptr);
  ::sigaction(SIGTERM, &action, nullptr);
}

bool StopRequested() { return stop_requested.load(); }
void RequestStop() { stop_requested.store(true); }
void ClearStopRequest() { stop_requested.store(false); }

}  // namespace fit3dof
