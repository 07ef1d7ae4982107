// fit3dof: aerodynamic coefficients from 3DOF gas-bearing motion.
//
// Output files are written atomically: the text goes to a temporary file in
// the same directory, which is renamed over the target only when complete.
// A crash or a full disk never leaves a half-written report behind.

#ifndef FIT3DOF_ATOMIC_FILE_H_
#define FIT3DOF_ATOMIC_FILE_H_

#include <string>

namespace fit3dof {

// Writes `content` to `path` atomically; creates missing parent
// directories. Throws std::runtime_error naming the path on failure.
void WriteFileAtomically(const std::string& path, const std::string& content);

}  // namespace fit3dof

#endif  // FIT3DOF_ATOMIC_FILE_H_
