// fit3dof: aerodynamic coefficients from 3DOF gas-bearing motion.
//
// libFuzzer harness: a YAML config (tools/fuzz). Any input must end in a
// Case or an InputError; anything else (a crash, another exception, a
// sanitizer report, a leak, a slow or huge input) is a finding.

#include <cstddef>
#include <cstdint>
#include <string>

#include "fit3dof/config.h"
#include "fit3dof/input_error.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  try {
    fit3dof::ParseConfig(text, "fuzz.yaml", "/nonexistent");
  } catch (const fit3dof::InputError&) {
  }
  return 0;
}
