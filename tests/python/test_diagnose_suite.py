"""tools/diagnose_suite's simulator (pytest, run by ctest): a motion that
diverges is reported as such, and the sizing shrinks the effect that drove
it instead of leaving the case unrun.

Environment as test_fit3dof.py: FIT3DOF_BINARY the fit3dof command,
FIT3DOF_SOURCE_DIR the checkout.
"""

import math

import pytest

from tool_module import load_tool

suite = load_tool("diagnose_suite")
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


def test_varied_conditions_are_drawn_per_draw_and_leave_table6(monkeypatch):
    import copy
    base = copy.deepcopy(suite.CONDITIONS)
    drawn = []
    for draw in (77, 77, 78):
        monkeypatch.setattr(suite, "CONDITIONS", copy.deepcopy(base))
        suite.varied_conditions(draw)
        drawn.append(copy.deepcopy(suite.CONDITIONS))
    # The same draw, the same conditions; another draw, others.
    assert drawn[0] == drawn[1]
    assert drawn[0]["short"] != drawn[2]["short"]
    for conditions in drawn:
        # The report's Table 6 motion stays as it is.
        assert conditions["table6"] == base["table6"]
        for name in ("short", "coning", "pair"):
            c = conditions[name]
            assert -0.40 <= c["coef"]["Cm_alpha"] <= -0.12
            assert -10.0 <= c["coef"]["Cm_q"] <= -1.5
            assert 0.08 <= c["body"]["Ix"] / c["body"]["Iy"] <= 0.201
            assert 8 <= c["points_per_cycle"] <= 12
            assert 20.0 <= c["initial"][1] <= 40.0
            assert 6.0 <= c["initial"][2] <= 10.0
        # Circular coning: the pitch plane turns at the pitch frequency.
        coning = conditions["coning"]
        rate = 2.0 * math.pi * suite.natural_hz(coning) * coning["initial"][2]
        assert coning["initial"][5] == pytest.approx(rate)
        # The pair's second run: twice the spin, half the amplitude.
        first, second = conditions["pair"]["runs"]
        assert second[1] == pytest.approx(2.0 * first[1])
        assert second[2] == pytest.approx(first[2] / 2.0)


def record(case, kind, ok, oracle_off=None):
    return {"case": case, "kind": kind, "ok": ok, "why": "", "seconds": 0.5,
            "oracle_off": oracle_off}


def test_tally_sums_draws_and_counts_the_truths_own_floor(tmp_path, capsys):
    import json
    first = [record("short/magnus", "inside", True, 0.4),
             record("short/roll_interaction", "inside", False, 3.6),
             record("clean/0", "clean", True)]
    second = [record("short/magnus", "inside", True, 3.2),
              record("clean/0", "clean", True)]
    paths = []
    for i, rows in enumerate((first, second)):
        paths.append(str(tmp_path / f"d{i}.json"))
        with open(paths[-1], "w") as f:
            json.dump(rows, f)
    assert suite.tally(paths) == 1  # a failure among them
    out = capsys.readouterr().out
    assert "2 draws, 5 records" in out
    assert "inside: 2/3 ok" in out
    assert "1 failing where the true model's own fit is over 3 SE off" in out
    # The floor counts the passes too: 3.6 and 3.2, not 0.4.
    assert "over 3 SE off on 2 of 3" in out
    assert "clean: 2/2 ok" in out
    assert suite.tally(paths[1:]) == 0


def test_tally_refuses_what_is_not_the_suites_json(tmp_path, capsys):
    bad = tmp_path / "bad.json"
    bad.write_text('{"case": "short/magnus"}')
    assert suite.tally([str(bad)]) == 2
    err = capsys.readouterr().err
    assert "bad.json" in err and "not a list of the suite's records" in err
    assert suite.tally([str(tmp_path / "missing.json")]) == 2


def test_again_counts_a_case_drawn_again_as_its_first_run_did(tmp_path,
                                                               monkeypatch):
    import json
    kept = {"case": "short/magnus", "terms": {}, "sized_to": 1.0,
            "redrawn": 2, "data": "data.csv"}
    work = tmp_path / "short_magnus"
    work.mkdir()
    (work / "case.json").write_text(json.dumps(kept))
    # No diagnosis run: the row as judged, without `redrawn`.
    monkeypatch.setattr(suite, "diagnosed",
                        lambda work, name: ({}, {}, 0.1, None))
    monkeypatch.setattr(suite, "judged",
                        lambda *args: {"case": "short/magnus", "ok": True})
    assert suite.again(("short/magnus", "short"), str(tmp_path))[
        "redrawn"] == 2
    # A record kept before case.json carried it: not drawn again.
    del kept["redrawn"]
    (work / "case.json").write_text(json.dumps(kept))
    assert suite.again(("short/magnus", "short"), str(tmp_path))[
        "redrawn"] == 0
