// fit3dof: aerodynamic coefficients from 3DOF gas-bearing motion.
//
// One number in a message, printf-style: FormatNumber("%.3g", e).

#ifndef FIT3DOF_SRC_FORMAT_H_
#define FIT3DOF_SRC_FORMAT_H_

#include <cstdio>
#include <string>

namespace fit3dof {

inline std::string FormatNumber(const char* format, double value) {
  char buffer[64];
  std::snprintf(buffer, sizeof(buffer), format, value);
  return buffer;
}

}  // namespace fit3dof

#endif  // FIT3DOF_SRC_FORMAT_H_
