#!/usr/bin/python3
"""The example campaign reduced from Python, notebook style.

    PYTHONPATH=build/python /usr/bin/python3 examples/campaign.py [OUT_DIR]

Loads configs/examples/campaign/manifest.yaml, builds each run's case from
its keys (the defaults merged in, as `fit3dof batch` does), fits every run
in a pool of threads (a fit releases the GIL), prints a table of the
coefficients with their standard errors, and plots each coefficient
against dynamic pressure (OUT_DIR/campaign_from_python.png).
"""

import copy
import os
import sys
from concurrent.futures import ThreadPoolExecutor

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import yaml  # noqa: E402

import fit3dof  # noqa: E402

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
MANIFEST = os.path.join(ROOT, "configs", "examples", "campaign",
                        "manifest.yaml")
COEFFICIENTS = ["Cm_alpha", "Cm_alpha_delta2", "Cm_q", "Cl_p"]


def merged(defaults, run):
    """run's keys over the defaults, dictionaries merged key by key."""
    out = copy.deepcopy(defaults)
    for key, value in run.items():
        if isinstance(value, dict) and isinstance(out.get(key), dict):
            out[key] = merged(out[key], value)
        else:
            out[key] = copy.deepcopy(value)
    return out


def cases():
    with open(MANIFEST) as f:
        manifest = yaml.safe_load(f)
    base_dir = os.path.dirname(MANIFEST)
    for run in manifest["runs"]:
        config = merged(manifest.get("defaults", {}), run)
        config.pop("start_from", None)  # a batch feature; every run alone
        yield fit3dof.Case.from_dict(config, base_dir=base_dir)


def main():
    out_dir = sys.argv[1] if len(sys.argv) > 1 else "out"
    os.makedirs(out_dir, exist_ok=True)
    runs = list(cases())
    with ThreadPoolExecutor(max_workers=os.cpu_count()) as pool:
        results = list(pool.map(fit3dof.fit, runs))

    print(f"fit3dof {fit3dof.__version__}: {len(results)} runs")
    print(f"{'run':8s} {'q':>6s} {'conv':5s} {'E':>6s}  " +
          "  ".join(f"{name:>24s}" for name in COEFFICIENTS))
    rows = []
    for case, result in zip(runs, results):
        q = float(yaml.safe_load(case.to_yaml())["flow"]["dynamic_pressure"])
        cells = []
        for name in COEFFICIENTS:
            p = result.parameters[name]
            cells.append(f"{p.value:12.6g} +- {p.standard_error:8.2g}")
        print(f"{result.name:8s} {q:6.0f} {str(result.converged):5s} "
              f"{result.probable_error:6.3f}  " + "  ".join(cells))
        rows.append((q, result))

    fig, axes = plt.subplots(len(COEFFICIENTS), 1, sharex=True,
                             figsize=(8, 2.2 * len(COEFFICIENTS)))
    for ax, name in zip(axes, COEFFICIENTS):
        qs = [q for q, _ in rows]
        values = [r.parameters[name].value for _, r in rows]
        errors = [r.parameters[name].standard_error for _, r in rows]
        ax.errorbar(qs, values, yerr=errors, fmt="o", capsize=3)
        ax.set_ylabel(f"{name} ({rows[0][1].parameters[name].units})")
        ax.ticklabel_format(axis="y", useOffset=False)
        ax.grid(alpha=0.3)
    axes[-1].set_xlabel("dynamic pressure (lbf/ft^2)")
    fig.suptitle("example campaign, fitted from Python (+-1 standard error)")
    fig.tight_layout()
    path = os.path.join(out_dir, "campaign_from_python.png")
    fig.savefig(path, dpi=110)
    print("figure:", path)

    # One run's residuals straight from the result's numpy arrays.
    segment = results[0].segments[0]
    print(f"{results[0].name}: {segment.times.size} samples, rms residual "
          f"theta {segment.residuals[:, 1].std():.4f} deg")


if __name__ == "__main__":
    main()
