"""fit3dof: aerodynamic coefficients from 3DOF gas-bearing motion.

    import fit3dof
    case = fit3dof.load_config("configs/table6.yaml")
    result = fit3dof.fit(case)            # releases the GIL: thread it
    p = result.parameters["Cm_alpha"]     # value, standard_error, units ...
    seg = result.segments[0]              # times, measured, computed,
                                          # residuals: numpy arrays
    report = result.to_dict()             # report.json as a dict

    fit3dof.Case.from_dict({...})         # the config's YAML keys as a dict
    fit3dof.simulate(case, times)         # (n, 3) phi, theta, psi, deg
    fit3dof.diagnose(case)                # verdict, effects_added, ...
    fit3dof.batch("manifest.yaml", "out", jobs=2)   # summary.json as a dict

Bad input raises fit3dof.InputError, a ValueError whose message is the one
the command line prints. Plots: fit3dof.plot (python3 -m fit3dof.plot DIR).
"""

try:
    from ._fit3dof import (Case, Diagnosis, FitResult, InputError, Parameter,
                           Segment, __version__, batch, diagnose, fit,
                           load_config, simulate)
except ImportError as _error:  # the plots need only matplotlib
    _missing = _error

    def __getattr__(name):
        raise ImportError(
            f"fit3dof.{name}: the compiled core fit3dof._fit3dof is not "
            f"built or not loadable ({_missing}); run tools/run") from None

__all__ = ["Case", "Diagnosis", "FitResult", "InputError", "Parameter",
           "Segment", "__version__", "batch", "diagnose", "fit",
           "load_config", "simulate"]
