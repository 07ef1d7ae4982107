"""tools/diagnose_suite's simulator (pytest, run by ctest): a motion that
diverges is reported as such, and the sizing shrinks the effect that drove
it instead of leaving the case unrun.

Environment as test_fit3dof.py: FIT3DOF_BINARY the fit3dof command,
FIT3DOF_SOURCE_DIR the checkout.
"""

import importlib.machinery
import importlib.util
import math
import os

import pytest

SOURCE = os.environ["FIT3DOF_SOURCE_DIR"]


def load_suite():
    path = os.path.join(SOURCE, "tools", "diagnose_suite")
    loader = importlib.machinery.SourceFileLoader("diagnose_suite", path)
    spec = importlib.util.spec_from_loader("diagnose_suite", loader)
    module = importlib.util.module_from_spec(spec)
    loader.exec_module(module)
    return module


suite = load_suite()
# A nonlinear damping of the sign that undamps the short run (Cm_q -5.5):
# Cm_q + Cm_q_delta2 delta^2 > 0 past 1.3 deg, and the motion runs away
# within half a second.
UNDAMPING = {"Cm_q_delta2": 10000.0}


def test_a_diverging_motion_raises_rather_than_returning_nan():
    cond = suite.CONDITIONS["short"]
    times = suite.sample_times(cond)
    with pytest.raises(OverflowError, match="diverged"):
        suite.simulate(cond, UNDAMPING, times)
    # The same effect with the damping's sign: bounded, finite.
    motion = suite.simulate(cond, {"Cm_q_delta2": -10000.0}, times)
    assert all(math.isfinite(v) for v in motion.flatten())


def test_the_sizing_shrinks_an_effect_that_drove_the_motion_away(tmp_path):
    cond = suite.CONDITIONS["short"]
    times = suite.sample_times(cond)
    assert suite.nominal_level(str(tmp_path), "short", times, UNDAMPING,
                               1) == math.inf
    terms, reached = suite.sized(str(tmp_path), "short", times, UNDAMPING,
                                 1.5, 1)
    assert abs(terms["Cm_q_delta2"]) < UNDAMPING["Cm_q_delta2"]
    assert math.isfinite(reached) and abs(reached - 1.5) < 0.15
