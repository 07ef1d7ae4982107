// fit3dof: aerodynamic coefficients from 3DOF gas-bearing motion.
//
// InputError is thrown for anything wrong with what the user gave us: a
// config key, a data file, a NAMELIST deck. Its message names the file and
// the key or line and says what was expected. The command line maps it to
// exit status 2.

#ifndef FIT3DOF_INPUT_ERROR_H_
#define FIT3DOF_INPUT_ERROR_H_

#include <stdexcept>
#include <string>

namespace fit3dof {

class InputError : public std::runtime_error {
 public:
  explicit InputError(const std::string& message)
      : std::runtime_error(message) {}
};

}  // namespace fit3dof

#endif  // FIT3DOF_INPUT_ERROR_H_
