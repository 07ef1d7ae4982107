// fit3dof: aerodynamic coefficients from 3DOF gas-bearing motion.
//
// Built only with FIT3DOF_AVX2=ON, and without AVX itself: before main and
// before the other units' static initializers, refuse a CPU that lacks the
// instructions the rest of the program was compiled for, instead of dying
// later with SIGILL.

#include <unistd.h>

#include <cstdlib>
#include <cstring>

namespace {

__attribute__((constructor(101))) void RefuseACpuWithoutAvx2() {
  __builtin_cpu_init();
  // FIT3DOF_PRETEND_NO_AVX2=1 takes this path on any CPU (for the test).
  const char* pretend = std::getenv("FIT3DOF_PRETEND_NO_AVX2");
  const bool refuse = pretend != nullptr && std::strcmp(pretend, "1") == 0;
  if (!refuse && __builtin_cpu_supports("avx2") &&
      __builtin_cpu_supports("fma")) {
    return;
  }
  static const char kMessage[] =
      "fit3dof: this build uses AVX2 and FMA (cmake -DFIT3DOF_AVX2=ON) and "
      "this CPU has not got them; build with -DFIT3DOF_AVX2=OFF (the "
      "default) to run here\n";
  // write(2): nothing of the C++ runtime is needed, or initialized yet.
  if (::write(STDERR_FILENO, kMessage, std::strlen(kMessage)) < 0) {
  }
  std::_Exit(2);
}

}  // namespace
