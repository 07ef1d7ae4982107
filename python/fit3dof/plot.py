#!/usr/bin/python3
"""Plots of a fit3dof fit, the report's Figs. 5 and 21-26.

    tools/plot DIR [--window SECONDS] [--max-panels N]

DIR is a `fit3dof fit` output, or a `fit3dof diagnose` output (then every
stepN/ is drawn: the residuals before and after each added effect).

reads DIR/fit.csv and DIR/report.json (written by `fit3dof fit`) and writes,
for each segment:
  DIR/<segment>_motion.png     computed and measured theta and psi vs time
  DIR/<segment>_residuals.png  theta - theta_m and psi - psi_m vs time
  DIR/<segment>_psi_theta.png  the fit in the psi-theta plane over
                               consecutive time windows
Uses Debian's python3-matplotlib (/usr/bin/python3).
"""

import argparse
import csv
import json
import math
import os
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402


def read_fit(path):
    segments = {}
    with open(path, newline="") as f:
        for row in csv.DictReader(f):
            name = row.get("segment") or "fit"
            s = segments.setdefault(name, {k: [] for k in (
                "t", "phi", "phi_fit", "theta", "theta_fit", "psi", "psi_fit")})
            for k in s:
                s[k].append(float(row[k]))
    return segments


def safe(name):
    return "".join(c if c.isalnum() or c in "-_." else "_" for c in name)


def rms(values):
    return math.sqrt(sum(v * v for v in values) / len(values)) if values else 0.0


def plot_motion(s, title, path):
    fig, axes = plt.subplots(2, 1, figsize=(11, 7), sharex=True)
    for ax, ch, label in ((axes[0], "theta", "theta (deg)"),
                          (axes[1], "psi", "psi (deg)")):
        ax.plot(s["t"], s[ch], ".", ms=3, color="tab:gray", label="measured")
        ax.plot(s["t"], s[ch + "_fit"], "-", lw=1.0, color="tab:blue",
                label="computed")
        ax.set_ylabel(label)
        ax.grid(alpha=0.3)
    axes[0].legend(loc="upper right")
    axes[1].set_xlabel("t (s)")
    fig.suptitle(title)
    fig.tight_layout()
    fig.savefig(path, dpi=110)
    plt.close(fig)


def plot_residuals(s, title, path):
    fig, axes = plt.subplots(2, 1, figsize=(11, 6), sharex=True)
    for ax, ch in ((axes[0], "theta"), (axes[1], "psi")):
        r = [c - m for c, m in zip(s[ch + "_fit"], s[ch])]
        level = rms(r)
        ax.plot(s["t"], r, ".", ms=3, color="tab:red")
        for sign in (-1, 1):
            ax.axhline(sign * level, color="k", lw=0.6, ls="--")
        ax.set_ylabel(f"{ch} - {ch}_m (deg)")
        ax.set_title(f"rms {level:.4g} deg", fontsize=9, loc="right")
        ax.grid(alpha=0.3)
    axes[1].set_xlabel("t (s)")
    fig.suptitle(title)
    fig.tight_layout()
    fig.savefig(path, dpi=110)
    plt.close(fig)


def plot_windows(s, title, path, window, max_panels):
    t = s["t"]
    start, end = t[0], t[-1]
    if window <= 0:
        window = max((end - start) / 8.0, 1e-9)
    count = min(max_panels, max(1, int(math.ceil((end - start) / window))))
    cols = min(4, count)
    rows = int(math.ceil(count / cols))
    fig, axes = plt.subplots(rows, cols, figsize=(3.3 * cols, 3.2 * rows),
                             squeeze=False)
    for p in range(rows * cols):
        ax = axes[p // cols][p % cols]
        if p >= count:
            ax.axis("off")
            continue
        a, b = start + p * window, start + (p + 1) * window
        idx = [i for i, x in enumerate(t) if a <= x <= b]
        ax.plot([s["psi"][i] for i in idx], [s["theta"][i] for i in idx],
                ".", ms=3, color="tab:gray")
        ax.plot([s["psi_fit"][i] for i in idx],
                [s["theta_fit"][i] for i in idx], "-", lw=0.9,
                color="tab:blue")
        ax.set_title(f"{a:.2f} to {b:.2f} s", fontsize=9)
        ax.set_aspect("equal", adjustable="datalim")
        ax.grid(alpha=0.3)
        if p % cols == 0:
            ax.set_ylabel("theta (deg)")
        if p // cols == rows - 1:
            ax.set_xlabel("psi (deg)")
    fig.suptitle(title + " (points: measured, line: computed)")
    fig.tight_layout()
    fig.savefig(path, dpi=100)
    plt.close(fig)


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("dir")
    parser.add_argument("--window", type=float, default=0.0,
                        help="seconds per psi-theta panel (default: 1/8 of "
                             "the record)")
    parser.add_argument("--max-panels", type=int, default=12)
    args = parser.parse_args()
    fit_csv = os.path.join(args.dir, "fit.csv")
    steps = sorted((d for d in os.listdir(args.dir) if d.startswith("step")
                    and os.path.exists(os.path.join(args.dir, d, "fit.csv")))
                   if os.path.isdir(args.dir) else [],
                   key=lambda d: int(d[4:]) if d[4:].isdigit() else 0)
    if not os.path.exists(fit_csv) and steps:
        # A `fit3dof diagnose` directory: the fit before and after each step.
        for step in steps:
            for line in plot_directory(os.path.join(args.dir, step), args):
                print(line)
        return 0
    if not os.path.exists(fit_csv):
        print(f"tools/plot: {fit_csv}: not found (run fit3dof fit first)",
              file=sys.stderr)
        return 2
    for line in plot_directory(args.dir, args):
        print(line)
    return 0


def plot_directory(directory, args):
    fit_csv = os.path.join(directory, "fit.csv")
    report = {}
    report_path = os.path.join(directory, "report.json")
    if os.path.exists(report_path):
        with open(report_path) as f:
            report = json.load(f)
    name = report.get("name", os.path.basename(os.path.normpath(directory)))
    step = os.path.basename(os.path.normpath(directory))
    if step.startswith("step"):
        name += f" ({step})"
    status = "converged" if report.get("converged", True) else "NOT CONVERGED"
    written = []
    for segment, s in read_fit(fit_csv).items():
        title = f"{name} {status}" if segment == name else \
            f"{name} [{segment}] {status}"
        base = os.path.join(directory, safe(segment))
        plot_motion(s, title, base + "_motion.png")
        plot_residuals(s, title, base + "_residuals.png")
        plot_windows(s, title, base + "_psi_theta.png", args.window,
                     args.max_panels)
        written += [base + "_motion.png", base + "_residuals.png",
                    base + "_psi_theta.png"]
    return written


if __name__ == "__main__":
    sys.exit(main())
