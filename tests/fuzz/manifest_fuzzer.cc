// fit3dof: aerodynamic coefficients from 3DOF gas-bearing motion.
//
// libFuzzer harness: a batch manifest (tools/fuzz). The loader reads a
// path, so each input goes to a file of this process first; it must end in
// runs or an InputError, and each run's merged config must end in a Case
// or an InputError too.

#include <unistd.h>

#include <cstddef>
#include <cstdint>
#include <fstream>
#include <string>

#include "config_node.h"
#include "fit3dof/input_error.h"
#include "manifest.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  static const std::string path =
      "/tmp/fit3dof_manifest_fuzz_" + std::to_string(::getpid()) + ".yaml";
  {
    std::ofstream out(path, std::ios::binary | std::ios::trunc);
    out.write(reinterpret_cast<const char*>(data), size);
  }
  try {
    for (const fit3dof::RunSpec& run : fit3dof::LoadManifest(path)) {
      try {
        fit3dof::ParseConfigNode(
            run.config, run.source, run.base_dir, run.node_lines);
      } catch (const fit3dof::InputError&) {
      }
    }
  } catch (const fit3dof::InputError&) {
  }
  return 0;
}
