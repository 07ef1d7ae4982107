// Fits a config through the installed library and prints Cm_alpha.
//
//   consumer CONFIG

#include <cstdio>
#include <exception>

#include "fit3dof/config.h"
#include "fit3dof/fit.h"
#include "fit3dof/version.h"

int main(int argc, char** argv) {
  if (argc != 2) {
    std::fprintf(stderr, "usage: consumer CONFIG\n");
    return 2;
  }
  try {
    const fit3dof::FitResult result =
        fit3dof::Fit(fit3dof::LoadConfig(argv[1]));
    for (const fit3dof::ParameterEstimate& e : result.parameters) {
      if (e.name == "Cm_alpha") {
        std::printf("fit3dof %s: %s Cm_alpha = %.17g +- %.3g (%s)\n",
                    FIT3DOF_VERSION,
                    result.name.c_str(),
                    e.value,
                    e.standard_error,
                    result.converged ? "converged" : "not converged");
      }
    }
    return result.converged ? 0 : 1;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "consumer: %s\n", e.what());
    return 2;
  }
}
