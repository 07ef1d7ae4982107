// fit3dof: aerodynamic coefficients from 3DOF gas-bearing motion.
//
// libFuzzer harness: a CSV data file (tools/fuzz). Any input must end in a
// record or an InputError.

#include <cstddef>
#include <cstdint>
#include <string>

#include "fit3dof/input_error.h"
#include "fit3dof/time_history.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  try {
    fit3dof::ParseTimeHistory(text, "fuzz.csv");
  } catch (const fit3dof::InputError&) {
  }
  return 0;
}
