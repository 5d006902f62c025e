#!/usr/bin/env python3
"""Plots of `tmlab discover` (docs/discover.md) from DIR/discover.h5 and DIR/report.json:
DIR/discover_fits.png (data, baseline and final model per test), DIR/discover_residuals.png (the
residual before and after against time) and DIR/discover_residual_vs_strain.png (against
displacement). Usage: tmlab_discover_plot.py DIR"""
import json
import os
import sys
import textwrap

import matplotlib

matplotlib.use("Agg")
import h5py  # noqa: E402
import matplotlib.pyplot as plt  # noqa: E402


def save(fig, path):
    tmp = path + ".tmp.png"
    fig.tight_layout()
    fig.savefig(tmp, dpi=110)
    plt.close(fig)
    os.replace(tmp, path)


def main():
    out = sys.argv[1]
    with open(os.path.join(out, "report.json")) as f:
        rep = json.load(f)
    with h5py.File(os.path.join(out, "discover.h5"), "r") as h5:
        tests = []
        for k in sorted(h5["tests"]):
            g = h5["tests"][k]
            tid = g.attrs.get("id", k)
            if isinstance(tid, bytes):
                tid = tid.decode()
            tests.append((tid, {n: g[n][()] for n in g}))
    b, fi = rep["baseline"], rep["final"]
    lb = "before: %s (RMS %.3g N)" % (b["model"], b["rms_N"])
    lf = "after: %s (RMS %.3g N)" % (fi["model"], fi["rms_N"])
    title = "%s: %s" % (rep["dataset"], ", ".join(rep["selected_effects"]) or "no effect added")
    # Data and both models against time (every test one after the other).
    fig, axes = plt.subplots(2, 1, figsize=(9, 7), sharex=True)
    t0 = 0.0
    for i, (tid, d) in enumerate(tests):
        t = d["time_s"] + t0
        axes[0].plot(t, d["force_N"], ".", color="0.5", ms=2, label="data" if i == 0 else None)
        axes[0].plot(t, d["baseline_N"], "-", color="C3", lw=1, label=lb if i == 0 else None)
        axes[0].plot(t, d["final_N"], "-", color="C0", lw=1, label=lf if i == 0 else None)
        axes[1].plot(t, d["displacement_m"] * 1e3, "-", color="k", lw=1)
        t0 = t[-1] + 0.02 * (t[-1] - t[0] + 1e-9)
    axes[0].set_ylabel("force [N]")
    axes[0].set_title(title, fontsize=10)
    axes[0].legend(fontsize=7)
    axes[0].grid(alpha=0.3)
    axes[1].set_ylabel("displacement [mm]")
    axes[1].set_xlabel("time [s] (tests one after the other)")
    axes[1].grid(alpha=0.3)
    save(fig, os.path.join(out, "discover_fits.png"))
    # Residuals against time.
    fig, ax = plt.subplots(2, 1, figsize=(9, 6), sharex=True)
    t0 = 0.0
    for i, (tid, d) in enumerate(tests):
        t = d["time_s"] + t0
        ax[0].plot(t, d["baseline_N"] - d["force_N"], "-", color="C3", lw=0.8)
        ax[1].plot(t, d["final_N"] - d["force_N"], "-", color="C0", lw=0.8)
        t0 = t[-1] + 0.02 * (t[-1] - t[0] + 1e-9)
    ax[0].set_title("residual (model - data) " + lb, fontsize=9)
    sig = "\n".join(textwrap.wrap("unexplained: " + rep["unexplained_signature"], 120)[:3])
    ax[1].set_title("residual " + lf + ("\n" + sig if rep["unexplained_structure"] else "; residual is noise"),
                    fontsize=8)
    for a in ax:
        a.set_ylabel("N")
        a.grid(alpha=0.3)
    ax[1].set_xlabel("time [s] (tests one after the other)")
    save(fig, os.path.join(out, "discover_residuals.png"))
    # Residuals against displacement.
    fig, ax = plt.subplots(1, 2, figsize=(10, 4), sharey=True)
    for i, (tid, d) in enumerate(tests):
        c = "C%d" % (i % 10)
        ax[0].plot(d["displacement_m"] * 1e3, d["baseline_N"] - d["force_N"], ".", color=c, ms=2)
        ax[1].plot(d["displacement_m"] * 1e3, d["final_N"] - d["force_N"], ".", color=c, ms=2)
    ax[0].set_title("before", fontsize=9)
    ax[1].set_title("after", fontsize=9)
    for a in ax:
        a.set_xlabel("displacement [mm]")
        a.grid(alpha=0.3)
    ax[0].set_ylabel("residual [N]")
    save(fig, os.path.join(out, "discover_residual_vs_strain.png"))


if __name__ == "__main__":
    main()
