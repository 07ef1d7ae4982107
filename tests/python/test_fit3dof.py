"""The Python module against the command line (pytest, run by ctest).

Environment (set by CMake's python_test): PYTHONPATH holds build/python,
FIT3DOF_BINARY the fit3dof command, FIT3DOF_SOURCE_DIR the checkout.
"""

import csv
import json
import os
import subprocess
import threading
import time

import numpy as np
import pytest
import yaml

import fit3dof

BINARY = os.environ["FIT3DOF_BINARY"]
SOURCE = os.environ["FIT3DOF_SOURCE_DIR"]
REPORT = os.path.join(SOURCE, "configs", "report")

FIT_CONFIGS = ["table6_sigma0.01.yaml", "table6_sigma0.03.yaml",
               "table6_sigma0.05.yaml", "section5_1_fit.yaml",
               "asymmetric_magnus_fit.yaml"]
CHECK_CASES = ["check_case_1.yaml", "check_case_2.yaml",
               "check_case_1_printed.yaml"]


def cli(*args):
    return subprocess.run([BINARY, *args], capture_output=True, text=True)


def comparable(report):
    """report.json without what differs between two runs of the same fit:
    the wall time, and the date and command line of its provenance."""
    report = dict(report)
    report.pop("seconds")
    provenance = dict(report.pop("provenance"))
    provenance.pop("date")
    provenance.pop("command_line")
    report["provenance"] = provenance
    return report


def test_version_matches_the_command():
    out = cli("--version")
    assert out.returncode == 0
    assert out.stdout.strip() == "fit3dof " + fit3dof.__version__


@pytest.mark.parametrize("name", FIT_CONFIGS)
def test_fit_equals_the_command_lines_report(name, tmp_path):
    path = os.path.join(REPORT, name)
    out = cli("fit", path, "--out_dir=" + str(tmp_path))
    assert out.returncode in (0, 1), out.stderr
    with open(tmp_path / "report.json") as f:
        expected = json.load(f)
    result = fit3dof.fit(fit3dof.load_config(path))
    # Every number to the last digit: the same code on the same doubles.
    assert comparable(result.to_dict()) == comparable(expected)
    assert result.converged == expected["converged"]
    for name_, p in result.parameters.items():
        e = expected["parameters"][name_]
        assert p.value == e["value"]
        assert p.free == e["free"]
        assert p.units == e["units"]
        if p.free:
            assert p.standard_error == e["standard_error"]
            assert p.rms_error == e["rms_error"]


def test_fit_data_are_numpy_arrays_matching_fit_csv(tmp_path):
    path = os.path.join(REPORT, "table6_sigma0.01.yaml")
    assert cli("fit", path, "--out_dir=" + str(tmp_path)).returncode == 0
    with open(tmp_path / "fit.csv", newline="") as f:
        rows = list(csv.DictReader(f))
    segment = fit3dof.fit(fit3dof.load_config(path)).segments[0]
    n = len(rows)
    assert segment.times.shape == (n,)
    for array in (segment.measured, segment.computed, segment.residuals):
        assert isinstance(array, np.ndarray) and array.shape == (n, 3)
    columns = ("phi", "theta", "psi")
    for i in (0, n // 2, n - 1):
        # fit.csv holds 10 significant digits.
        assert segment.times[i] == pytest.approx(float(rows[i]["t"]),
                                                 rel=1e-9, abs=1e-12)
        for ch, name in enumerate(columns):
            assert segment.measured[i, ch] == pytest.approx(
                float(rows[i][name]), rel=1e-9, abs=1e-9)
            assert segment.computed[i, ch] == pytest.approx(
                float(rows[i][name + "_fit"]), rel=1e-9, abs=1e-9)
    np.testing.assert_allclose(
        segment.residuals[:, 1:],
        segment.computed[:, 1:] - segment.measured[:, 1:], atol=1e-12)


@pytest.mark.parametrize("name", CHECK_CASES)
def test_simulate_equals_the_command_line(name, tmp_path):
    path = os.path.join(REPORT, name)
    out_csv = tmp_path / "motion.csv"
    assert cli("simulate", path, "--out=" + str(out_csv)).returncode == 0
    expected = np.loadtxt(out_csv, delimiter=",", skiprows=1)
    motion = fit3dof.simulate(fit3dof.load_config(path))
    assert motion.shape == expected.shape
    # The CSV holds 12 significant digits.
    np.testing.assert_allclose(motion, expected, rtol=1e-11, atol=1e-9)
    # At given times: the same motion, no noise.
    at = fit3dof.simulate(fit3dof.load_config(path), list(motion[:50, 0]))
    np.testing.assert_array_equal(at, motion[:50])


def test_case_from_dict_equals_the_yaml_file():
    path = os.path.join(REPORT, "table6_sigma0.01.yaml")
    with open(path) as f:
        config = yaml.safe_load(f)
    from_dict = fit3dof.Case.from_dict(config, base_dir=REPORT)
    assert from_dict == fit3dof.load_config(path)
    assert from_dict.parameters["Cm_alpha"]["free"]
    from_dict.set_parameter("Cm_alpha", value=-0.3, free=False)
    assert from_dict.parameters["Cm_alpha"] == {"value": -0.3, "free": False}


def test_tied_parameters_follow_and_untie_when_set():
    path = os.path.join(REPORT, "table6_sigma0.01.yaml")
    with open(path) as f:
        config = yaml.safe_load(f)
    # Cl_p follows Cm_q; at the truth (-4.0) it is the truth's -0.0081.
    k = 0.002025
    config["parameters"]["Cl_p"] = {"tied": "Cm_q", "factor": k}
    case = fit3dof.Case.from_dict(config, base_dir=REPORT)
    cm_q = case.parameters["Cm_q"]["value"]
    assert case.parameters["Cl_p"] == {"value": k * cm_q, "free": False,
                                       "tied_to": "Cm_q", "tie_factor": k}
    result = fit3dof.fit(case)
    cl_p, fitted = result.parameters["Cl_p"], result.parameters["Cm_q"]
    assert cl_p.tied_to == "Cm_q" and cl_p.value == k * fitted.value
    assert cl_p.standard_error == k * fitted.standard_error
    case.set_parameter("Cl_p", value=-0.008)
    assert case.parameters["Cl_p"] == {"value": -0.008, "free": False}


def test_bad_input_raises_value_error_with_the_command_lines_message(
        tmp_path):
    good = os.path.join(REPORT, "table6_sigma0.01.yaml")
    with open(good) as f:
        text = f.read()
    assert "Cm_alpha:" in text
    bad = tmp_path / "bad.yaml"
    bad.write_text(text.replace("Cm_alpha:", "Cm_alfa:").replace(
        "data/", os.path.join(REPORT, "data") + "/"))
    out = cli("fit", str(bad), "--out_dir=" + str(tmp_path / "out"))
    assert out.returncode == 2
    with pytest.raises(ValueError) as error:
        fit3dof.load_config(str(bad))
    assert isinstance(error.value, fit3dof.InputError)
    assert out.stderr.strip() == "fit3dof: " + str(error.value)
    assert "did you mean Cm_alpha" in str(error.value)
    with open(good) as f:
        config = yaml.safe_load(f)
    config["parameters"]["Cm_alfa"] = config["parameters"].pop("Cm_alpha")
    with pytest.raises(ValueError, match="did you mean Cm_alpha"):
        fit3dof.Case.from_dict(config, base_dir=REPORT)
    with pytest.raises(ValueError, match="did you mean Cm_alpha"):
        fit3dof.load_config(
            os.path.join(REPORT, "table6_sigma0.01.yaml")).set_parameter(
                "Cm_alfa", value=1.0)


def test_a_fit_releases_the_gil():
    """While one thread fits, another runs Python: the fit does not hold
    the interpreter (so fits in two threads run side by side)."""
    case = fit3dof.load_config(os.path.join(REPORT, "section5_1_fit.yaml"))
    done = threading.Event()
    results = []

    def work():
        results.append(fit3dof.fit(case))
        done.set()

    ticks = 0
    worker = threading.Thread(target=work)
    worker.start()
    while not done.is_set():
        ticks += 1
        time.sleep(0.001)
    worker.join()
    # A held GIL lets the main thread run only before and after the fit.
    assert results and ticks >= 10, ticks


def test_two_threads_give_the_same_results():
    case = fit3dof.load_config(os.path.join(REPORT, "table6_sigma0.03.yaml"))
    results = [None, None]

    def work(i):
        results[i] = fit3dof.fit(case)

    threads = [threading.Thread(target=work, args=(i,)) for i in range(2)]
    for t in threads:
        t.start()
    for t in threads:
        t.join()
    assert comparable(results[0].to_dict()) == comparable(
        results[1].to_dict())


def test_diagnose_matches_the_command_line(tmp_path):
    path = os.path.join(REPORT, "table6_sigma0.01.yaml")
    out = cli("diagnose", path, "--out_dir=" + str(tmp_path))
    with open(tmp_path / "diagnosis.json") as f:
        expected = json.load(f)
    case = fit3dof.load_config(path)
    d = fit3dof.diagnose(case)
    assert d.verdict == expected["verdict"]
    assert d.effects_added == expected["effects_added"]
    got = d.to_dict(case)
    assert got["final_parameters"] == expected["final_parameters"]
    assert out.returncode == (0 if d.verdict in ("noise_level", "explained")
                              else 1)


def test_diagnose_takes_effects_known_absent(tmp_path):
    case = fit3dof.load_config(os.path.join(REPORT, "table6_sigma0.01.yaml"))
    d = fit3dof.diagnose(case, absent=["magnus", "tunnel_damping"])
    assert d.to_dict(case)["effects_known_absent"] == ["magnus",
                                                       "tunnel_damping"]
    with pytest.raises(fit3dof.InputError, match="tunnel_buzz"):
        fit3dof.diagnose(case, absent=["tunnel_buzz"])


def test_diagnose_at_the_configs_step_on_request():
    path = os.path.join(REPORT, "table6_sigma0.01.yaml")
    case = fit3dof.load_config(path)
    exact = fit3dof.diagnose(case, exact_step=True).to_dict(case)
    searched = fit3dof.diagnose(case).to_dict(case)
    assert exact["search_step"] == 0.01  # the config's solver.step
    # Table 6 at twice its step: the motion more than 0.01/16 apart.
    assert searched["search_step"] == 0.01
    assert exact["verdict"] == searched["verdict"]
    assert exact["effects_added"] == searched["effects_added"]


def test_batch_writes_the_summary_and_returns_it(tmp_path):
    manifest = tmp_path / "manifest.yaml"
    manifest.write_text(
        "runs:\n"
        f"  - {{name: a, config: {os.path.join(REPORT, 'table6_sigma0.01.yaml')}}}\n"
        f"  - {{name: b, config: {os.path.join(REPORT, 'table6_sigma0.02.yaml')}}}\n")
    summary = fit3dof.batch(str(manifest), str(tmp_path / "out"), jobs=2)
    with open(tmp_path / "out" / "summary.json") as f:
        assert summary == json.load(f)
    assert [r["name"] for r in summary["runs"]] == ["a", "b"]
    with pytest.raises(ValueError):
        fit3dof.batch(str(tmp_path / "missing.yaml"), str(tmp_path / "x"))


def test_batch_fits_runs_together(tmp_path):
    # Two runs of the example campaign at one dynamic pressure, and a run
    # fitting one model to both records (together:): each record keeps its
    # initial conditions, and the two determine Cm_alpha better than either.
    campaign = os.path.join(SOURCE, "configs", "examples", "campaign")
    with open(os.path.join(campaign, "manifest.yaml")) as f:
        manifest = yaml.safe_load(f)
    runs = [r for r in manifest["runs"] if r["name"] in ("q150-a", "q150-c")]
    for r in runs:
        r["data"]["file"] = os.path.join(campaign, r["data"]["file"])
    runs.append({"name": "q150-ac", "together": ["q150-a", "q150-c"]})
    manifest["runs"] = runs
    path = tmp_path / "manifest.yaml"
    path.write_text(yaml.safe_dump(manifest))
    summary = fit3dof.batch(str(path), str(tmp_path / "out"), jobs=2)
    rows = {r["name"]: r for r in summary["runs"]}
    assert [r["status"] for r in rows.values()] == ["converged"] * 3
    joint = rows["q150-ac"]["parameters"]
    assert "q150-c.phidot0" in joint
    for alone in ("q150-a", "q150-c"):
        assert (joint["Cm_alpha"]["standard_error"] <
                rows[alone]["parameters"]["Cm_alpha"]["standard_error"])
    with open(tmp_path / "out" / "q150-ac" / "report.json") as f:
        report = json.load(f)
    assert [s["name"] for s in report["segments"]] == ["q150-a", "q150-c"]


def test_the_example_script_fits_the_campaign(tmp_path):
    script = os.path.join(SOURCE, "examples", "campaign.py")
    out = subprocess.run(["/usr/bin/python3", script, str(tmp_path)],
                         capture_output=True, text=True)
    assert out.returncode == 0, out.stderr
    assert "12 runs" in out.stdout
    assert out.stdout.count(" True ") == 12, out.stdout
    assert (tmp_path / "campaign_from_python.png").stat().st_size > 20000


def test_report_records_its_provenance(tmp_path):
    path = os.path.join(REPORT, "table6_sigma0.01.yaml")
    assert cli("fit", path, "--out_dir=" + str(tmp_path)).returncode == 0
    with open(tmp_path / "report.json") as f:
        provenance = json.load(f)["provenance"]
    assert provenance["fit3dof_version"] == fit3dof.__version__
    assert provenance["config"] == path
    assert provenance["command_line"].endswith(
        f"fit {path} --out_dir={tmp_path}")
    import hashlib
    [data] = provenance["data"]
    with open(data["path"], "rb") as f:
        content = f.read()
    assert data["sha256"] == hashlib.sha256(content).hexdigest()
    assert data["bytes"] == len(content)
    assert provenance["date"].endswith("Z") and provenance["date"][:2] == "20"


def test_filter_error_fit_equals_the_command_lines(tmp_path):
    with open(os.path.join(REPORT, "table6_sigma0.01.yaml")) as f:
        config = yaml.safe_load(f)
    config["data"]["file"] = os.path.join(REPORT, config["data"]["file"])
    config["solver"]["method"] = "filter_error"
    config["process_noise"] = {"roll": "auto", "pitch": "auto", "yaw": 0.05}
    path = tmp_path / "filter.yaml"
    with open(path, "w") as f:
        yaml.safe_dump(config, f)
    out = cli("fit", str(path), "--out_dir=" + str(tmp_path / "out"))
    assert out.returncode in (0, 1), out.stderr
    with open(tmp_path / "out" / "report.json") as f:
        expected = json.load(f)
    result = fit3dof.fit(fit3dof.load_config(str(path)))
    assert comparable(result.to_dict()) == comparable(expected)
    noise = result.process_noise
    assert set(noise) == {"roll", "pitch", "yaw"}
    assert noise["yaw"] == {"intensity": 0.05,
                            "standard_error": noise["yaw"]["standard_error"],
                            "estimated": False}
    assert noise["pitch"]["estimated"]
    assert expected["process_noise"]["yaw"]["intensity"] == 0.05
