"""Plots of fit3dof output directories (the report's Figs. 5 and 21-26, and
more).

    python3 -m fit3dof.plot DIR [--window S] [--max-panels N] [--against KEY]
    tools/plot DIR ...            (the same)

DIR is what a command wrote:
  fit3dof fit       DIR/<segment>_motion.png     phi, theta, psi: measured
                                                  points, computed line
                    DIR/<segment>_residuals.png  the three residuals with
                                                  labelled +-rms lines
                    DIR/<segment>_psi_theta.png  the psi-theta plane over
                                                  consecutive windows, start
                                                  and direction marked
                    DIR/coefficients.png         every free coefficient with
                                                  its standard error, the
                                                  probable error
  fit3dof diagnose  the above in every DIR/stepN/, and DIR/steps.png: the
                    residuals before and after each step side by side
  fit3dof batch     the above for every run, and DIR/campaign.png: each
                    coefficient against run (or --against a config key,
                    e.g. flow.dynamic_pressure) with its error bars

Needs only matplotlib (Debian's python3-matplotlib); PyYAML
(python3-yaml) for --against.
"""

import argparse
import csv
import json
import math
import os
import sys
import textwrap

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

CHANNELS = ("phi", "theta", "psi")
INITIAL_CONDITIONS = {"phi0", "phidot0", "theta0", "thetadot0", "psi0",
                      "psidot0", "p0", "q0", "r0"}
MEASURED = dict(marker=".", ms=3, ls="none", color="tab:gray")
COMPUTED = dict(lw=1.0, color="tab:blue")


def read_fit(path):
    """fit.csv as {segment: {column: [values]}}."""
    segments = {}
    with open(path, newline="") as f:
        for row in csv.DictReader(f):
            name = row.get("segment") or "fit"
            s = segments.setdefault(name, {k: [] for k in (
                "t", "phi", "phi_fit", "theta", "theta_fit", "psi",
                "psi_fit")})
            for k in s:
                s[k].append(float(row[k]))
    return segments


def read_json(path):
    if not os.path.exists(path):
        return {}
    with open(path) as f:
        return json.load(f)


def safe(name):
    return "".join(c if c.isalnum() or c in "-_." else "_" for c in name)


def rms(values):
    return math.sqrt(sum(v * v for v in values) / len(values)) if values \
        else 0.0


def residual(s, ch):
    """computed - measured (the report's theta - theta_m), roll wrapped."""
    r = [c - m for c, m in zip(s[ch + "_fit"], s[ch])]
    if ch == "phi":
        r = [x - 360.0 * round(x / 360.0) for x in r]
    return r


def save(fig, path, dpi=110):
    fig.savefig(path, dpi=dpi)
    plt.close(fig)
    return path


def fit_title(report, segment, step=""):
    name = report.get("name", "fit")
    if segment not in ("fit", name):
        name += f" [{segment}]"
    if step:
        name += f" ({step})"
    status = "converged" if report.get("converged", True) else \
        "NOT CONVERGED"
    e = report.get("probable_error")
    return f"{name}: {status}" + (f", probable error {e:.4g}"
                                  if e is not None else "")


def coefficients(report):
    """The free coefficients (no initial conditions, no segment's own)."""
    out = []
    for name, p in report.get("parameters", {}).items():
        if p.get("free") and "segment" not in p and \
                name not in INITIAL_CONDITIONS:
            out.append((name, p))
    return out


def plot_motion(s, title, path):
    fig, axes = plt.subplots(3, 1, figsize=(11, 8.5), sharex=True)
    for ax, ch in zip(axes, CHANNELS):
        ax.plot(s["t"], s[ch], label="measured", **MEASURED)
        ax.plot(s["t"], s[ch + "_fit"], label="computed", **COMPUTED)
        ax.set_ylabel(f"{ch} (deg)")
        ax.grid(alpha=0.3)
    axes[0].legend(loc="upper right")
    axes[-1].set_xlabel("t (s)")
    fig.suptitle(title)
    fig.tight_layout()
    return save(fig, path)


def plot_residuals(s, title, path):
    fig, axes = plt.subplots(3, 1, figsize=(11, 8), sharex=True)
    for ax, ch in zip(axes, CHANNELS):
        r = residual(s, ch)
        level = rms(r)
        ax.plot(s["t"], r, ".", ms=3, color="tab:red")
        ax.axhline(level, color="k", lw=0.8, ls="--",
                   label=f"+-rms = {level:.4g} deg")
        ax.axhline(-level, color="k", lw=0.8, ls="--")
        ax.set_ylabel(f"{ch} - {ch}_m (deg)")
        ax.legend(loc="upper right", fontsize=8)
        ax.grid(alpha=0.3)
    axes[-1].set_xlabel("t (s)")
    fig.suptitle(title + ": residuals")
    fig.tight_layout()
    return save(fig, path)


def mark_path(ax, x, y):
    """The start of a window's path and its direction of travel."""
    if len(x) < 2:
        return
    ax.plot(x[0], y[0], "o", ms=6, mfc="none", mec="tab:green", mew=1.5,
            label="start")
    k = min(len(x) - 1, max(1, len(x) // 20))
    ax.annotate("", xy=(x[k], y[k]), xytext=(x[0], y[0]),
                arrowprops=dict(arrowstyle="->", color="tab:green", lw=1.5))


def plot_windows(s, title, path, window, max_panels):
    t = s["t"]
    start, end = t[0], t[-1]
    if window <= 0:
        window = max((end - start) / 8.0, 1e-9)
    count = min(max_panels, max(1, int(math.ceil((end - start) / window))))
    cols = min(4, count)
    rows = int(math.ceil(count / cols))
    fig, axes = plt.subplots(rows, cols, figsize=(3.3 * cols, 3.3 * rows),
                             squeeze=False)
    for p in range(rows * cols):
        ax = axes[p // cols][p % cols]
        if p >= count:
            ax.axis("off")
            continue
        a, b = start + p * window, start + (p + 1) * window
        idx = [i for i, x in enumerate(t) if a <= x <= b]
        psi = [s["psi"][i] for i in idx]
        theta = [s["theta"][i] for i in idx]
        psi_fit = [s["psi_fit"][i] for i in idx]
        theta_fit = [s["theta_fit"][i] for i in idx]
        ax.plot(psi, theta, label="measured", **MEASURED)
        ax.plot(psi_fit, theta_fit, label="computed", lw=0.9,
                color="tab:blue")
        mark_path(ax, psi_fit, theta_fit)
        ax.set_title(f"{a:.2f} to {b:.2f} s", fontsize=9)
        ax.set_aspect("equal", adjustable="datalim")
        ax.grid(alpha=0.3)
        if p == 0:
            ax.legend(loc="best", fontsize=7)
        if p % cols == 0:
            ax.set_ylabel("theta (deg)")
        if p // cols == rows - 1:
            ax.set_xlabel("psi (deg)")
    fig.suptitle(title + " (circle: start, arrow: direction)")
    fig.tight_layout()
    return save(fig, path, dpi=100)


def plot_coefficients(report, title, path):
    """Each free coefficient on its own axis: the value with +-1 and +-3
    standard errors, the numbers beside it."""
    rows = coefficients(report)
    if not rows:
        return None
    fig, axes = plt.subplots(len(rows), 1,
                             figsize=(10, 0.9 * len(rows) + 1.2),
                             squeeze=False)
    for ax, (name, p) in zip(axes[:, 0], rows):
        value, se = p["value"], p.get("standard_error")
        ok = se is not None and math.isfinite(se) and se > 0
        if ok:
            ax.errorbar([value], [0], xerr=[[3 * se], [3 * se]], fmt="none",
                        ecolor="tab:blue", alpha=0.35, lw=6)
            ax.errorbar([value], [0], xerr=[[se], [se]], fmt="o",
                        color="tab:blue", ecolor="tab:blue", capsize=4)
            ax.set_xlim(value - 4 * se, value + 4 * se)
            text = f"{name} = {value:.6g} +- {se:.2g} {p.get('units', '')}"
            if p.get("rms_error") is not None:
                text += f"   (rms error, Eq. 27: {p['rms_error']:.2g})"
        else:
            ax.plot([value], [0], "x", color="tab:red")
            text = f"{name} = {value:.6g} {p.get('units', '')} " \
                   "(not determined)"
        ax.set_yticks([])
        ax.set_ylim(-1, 1)
        ax.text(0.01, 0.9, text, transform=ax.transAxes, va="top",
                fontsize=9)
        ax.ticklabel_format(axis="x", useOffset=False, style="sci",
                            scilimits=(-3, 4))
        ax.tick_params(axis="x", labelsize=7)
    fig.suptitle(title + "\nthick: +-3 standard errors, bar: +-1",
                 fontsize=10)
    fig.tight_layout()
    return save(fig, path)


def plot_fit_dir(directory, args, step=""):
    report = read_json(os.path.join(directory, "report.json"))
    written = []
    for segment, s in read_fit(os.path.join(directory, "fit.csv")).items():
        title = fit_title(report, segment, step)
        base = os.path.join(directory, safe(segment))
        written.append(plot_motion(s, title, base + "_motion.png"))
        written.append(plot_residuals(s, title, base + "_residuals.png"))
        written.append(plot_windows(s, title, base + "_psi_theta.png",
                                    args.window, args.max_panels))
    path = plot_coefficients(report, fit_title(report, "fit", step),
                             os.path.join(directory, "coefficients.png"))
    if path:
        written.append(path)
    return written


def step_dirs(directory):
    steps = [d for d in os.listdir(directory) if d.startswith("step")
             and d[4:].isdigit()
             and os.path.exists(os.path.join(directory, d, "fit.csv"))]
    return sorted(steps, key=lambda d: int(d[4:]))


def plot_steps(directory, diagnosis, path):
    """Each step's residuals (theta, psi) before and after, side by side."""
    entries = [(s, "added") for s in diagnosis.get("steps", [])] + \
        [(s, "partial: not adopted") for s in diagnosis.get("partial", [])] + \
        [(s, "dropped again: redundant")
         for s in diagnosis.get("pruned", [])]
    if not entries:
        return None
    fig, axes = plt.subplots(len(entries), 2,
                             figsize=(12, 3.2 * len(entries) + 0.8),
                             squeeze=False, sharey="row")
    for i, (step, how) in enumerate(entries):
        # Older diagnosis.json files lack "fits": the steps in order then.
        for col, k in enumerate(step.get("fits", (i, i + 1))):
            ax = axes[i][col]
            fit_csv = os.path.join(directory, f"step{k}", "fit.csv")
            if not os.path.exists(fit_csv):
                ax.axis("off")
                continue
            levels = []
            for s in read_fit(fit_csv).values():
                for ch, color in (("theta", "tab:red"), ("psi", "tab:blue")):
                    r = residual(s, ch)
                    levels.append(f"{ch} {rms(r):.3g}")
                    ax.plot(s["t"], r, ".", ms=2, color=color,
                            label=ch if len(levels) <= 2 else None)
            when = "before" if col == 0 else "after"
            ax.set_title(f"{when} {step['effect']} ({how}): rms "
                         + ", ".join(levels) + " deg", fontsize=9)
            ax.grid(alpha=0.3)
            ax.set_ylabel("computed - measured (deg)")
            if i == len(entries) - 1:
                ax.set_xlabel("t (s)")
            ax.legend(loc="upper right", fontsize=7)
    verdict = f"{diagnosis.get('name', '')}: " \
        f"{diagnosis.get('verdict_text', '')}"
    fig.suptitle("\n".join(textwrap.wrap(verdict, 150)[:4]), fontsize=9)
    fig.tight_layout()
    return save(fig, path)


def plot_diagnose_dir(directory, args):
    written = []
    for step in step_dirs(directory):
        written += plot_fit_dir(os.path.join(directory, step), args, step)
    diagnosis = read_json(os.path.join(directory, "diagnosis.json"))
    path = plot_steps(directory, diagnosis,
                      os.path.join(directory, "steps.png"))
    if path:
        written.append(path)
    return written


def config_value(run_dir, key):
    """A dotted key (flow.dynamic_pressure) of the run's config.yaml."""
    import yaml  # python3-yaml; only for --against
    with open(os.path.join(run_dir, "config.yaml")) as f:
        node = yaml.safe_load(f)
    for part in key.split("."):
        if not isinstance(node, dict) or part not in node:
            return None
        node = node[part]
    try:
        return float(node)
    except (TypeError, ValueError):
        return None


def plot_campaign(directory, summary, against, path):
    runs = [r for r in summary.get("runs", []) if r.get("parameters")]
    if not runs:
        return None
    if against == "run":
        xs = list(range(len(runs)))
    else:
        xs = [config_value(os.path.join(directory, r["name"]), against)
              for r in runs]
        if any(x is None for x in xs):
            missing = [r["name"] for r, x in zip(runs, xs) if x is None]
            raise SystemExit(f"--against {against}: not a number in the "
                             f"config.yaml of {', '.join(missing)}")
    names = []
    for r in runs:
        for name in r["parameters"]:
            if name not in INITIAL_CONDITIONS and name not in names:
                names.append(name)
    fig, axes = plt.subplots(len(names), 1,
                             figsize=(11, 2.3 * len(names) + 1.0),
                             sharex=True, squeeze=False)
    for ax, name in zip(axes[:, 0], names):
        for x, r in zip(xs, runs):
            p = r["parameters"].get(name)
            if p is None:
                continue
            se = p.get("standard_error")
            good = r["status"] == "converged"
            ax.errorbar([x], [p["value"]],
                        yerr=[se] if se is not None else None, fmt="o",
                        capsize=3, color="tab:blue" if good else "tab:red",
                        mfc="tab:blue" if good else "none")
        ax.set_ylabel(name, fontsize=9)
        ax.grid(alpha=0.3)
        ax.ticklabel_format(axis="y", useOffset=False)
    bottom = axes[-1][0]
    if against == "run":
        bottom.set_xticks(xs)
        bottom.set_xticklabels([r["name"] for r in runs], rotation=45,
                               ha="right", fontsize=8)
    else:
        bottom.set_xlabel(against)
    converged = sum(r["status"] == "converged" for r in runs)
    fig.suptitle(f"campaign {os.path.basename(os.path.abspath(directory))}: "
                 f"{converged} of {len(runs)} runs converged (red, hollow: "
                 "not converged); bars: +-1 standard error", fontsize=10)
    fig.tight_layout()
    return save(fig, path)


def plot_batch_dir(directory, args):
    summary = read_json(os.path.join(directory, "summary.json"))
    written = []
    for run in summary.get("runs", []):
        run_dir = os.path.join(directory, run["name"])
        if os.path.exists(os.path.join(run_dir, "fit.csv")):
            written += plot_fit_dir(run_dir, args)
        elif step_dirs(run_dir) if os.path.isdir(run_dir) else False:
            written += plot_diagnose_dir(run_dir, args)
    path = plot_campaign(directory, summary, args.against,
                         os.path.join(directory, "campaign.png"))
    if path:
        written.append(path)
    return written


def plot(directory, args):
    """The figures of a fit, diagnose or batch directory; their paths."""
    if os.path.exists(os.path.join(directory, "summary.json")):
        return plot_batch_dir(directory, args)
    if os.path.exists(os.path.join(directory, "fit.csv")):
        return plot_fit_dir(directory, args)
    if os.path.isdir(directory) and step_dirs(directory):
        return plot_diagnose_dir(directory, args)
    return None


def main(argv=None, prog=None):
    parser = argparse.ArgumentParser(prog=prog,
                                     description=__doc__.splitlines()[0])
    parser.add_argument("dir")
    parser.add_argument("--window", type=float, default=0.0,
                        help="seconds per psi-theta panel (default: 1/8 of "
                             "the record)")
    parser.add_argument("--max-panels", type=int, default=12)
    parser.add_argument("--against", default="run",
                        help="campaign figure's abscissa: run (default) or "
                             "a dotted config key, e.g. "
                             "flow.dynamic_pressure")
    args = parser.parse_args(argv)
    written = plot(args.dir, args)
    if written is None:
        print(f"{parser.prog}: {args.dir}: no fit.csv, stepN/ or "
              "summary.json (run fit3dof fit, diagnose or batch first)",
              file=sys.stderr)
        return 2
    for path in written:
        print(path)
    return 0


if __name__ == "__main__":
    sys.exit(main(prog="python3 -m fit3dof.plot"))
