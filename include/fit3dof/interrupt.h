// fit3dof: aerodynamic coefficients from 3DOF gas-bearing motion.
//
// Ctrl-C and SIGTERM as a request to stop, for long jobs (a batch): the
// first signal sets a flag that the batch scheduler and the fit's iteration
// callback poll; they stop starting work and abandon what runs, so the batch
// can write the summary of what finished. A second signal ends the process
// at once (the default action).

#ifndef FIT3DOF_INTERRUPT_H_
#define FIT3DOF_INTERRUPT_H_

#include <stdexcept>

namespace fit3dof {

// Installs the SIGINT and SIGTERM handlers.
void InstallStopHandlers();

// True once a stop was requested (by a signal or RequestStop).
bool StopRequested();

void RequestStop();
void ClearStopRequest();

// Thrown by a fit abandoned because a stop was requested.
class Interrupted : public std::runtime_error {
 public:
  Interrupted() : std::runtime_error("interrupted") {}
};

}  // namespace fit3dof

#endif  // FIT3DOF_INTERRUPT_H_
