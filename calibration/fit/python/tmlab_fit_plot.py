#!/usr/bin/env python3
"""Plots of `tmlab fit` (docs/identification.md): data vs model and residuals per test, and the
profile likelihood, from DIR/fit.h5 and DIR/fit.json into DIR/fit_data_vs_model.png,
DIR/fit_residuals.png and DIR/fit_profile.png. Usage: tmlab_fit_plot.py DIR TITLE"""
import json
import os
import sys

import matplotlib

matplotlib.use("Agg")
import h5py  # noqa: E402
import matplotlib.pyplot as plt  # noqa: E402


def save(fig, path):
    tmp = path + ".tmp.png"
    fig.savefig(tmp, dpi=110)
    plt.close(fig)
    os.replace(tmp, path)


def main():
    out, title = sys.argv[1], sys.argv[2]
    with open(os.path.join(out, "fit.json")) as f:
        fj = json.load(f)
    with h5py.File(os.path.join(out, "fit.h5"), "r") as h5:
        tests = [(h5["tests"][k].attrs.get("id", k), {n: h5["tests"][k][n][()] for n in h5["tests"][k]})
                 for k in sorted(h5["tests"])]
        profile = None
        if "profile" in h5:
            profile = (h5["profile"].attrs["parameter"], h5["profile"]["value"][()], h5["profile"]["sse_N2"][()])
    if isinstance(tests[0][0], bytes):
        tests = [(i.decode(), d) for i, d in tests]
    # Indentation with a hold: force against time; platen tests: force against displacement.
    against_time = any(len(set(d["displacement_m"])) < 0.8 * len(d["displacement_m"]) for _, d in tests)
    xkey, xlabel, xs = ("time_s", "time [s]", 1.0) if against_time else ("displacement_m", "displacement [mm]", 1e3)
    fig, ax = plt.subplots(figsize=(8, 5))
    for i, (tid, d) in enumerate(tests):
        c = "C%d" % (i % 10)
        step = max(1, len(d[xkey]) // 400)
        ax.plot(d[xkey][::step] * xs, d["force_N"][::step], ".", color=c, ms=3, label="data %s" % (tid or ""))
        ax.plot(d[xkey] * xs, d["model_force_N"], "-", color=c, lw=1.5, label="model %s" % (tid or ""))
    ax.set_xlabel(xlabel)
    ax.set_ylabel("force [N]")
    ax.set_title(title + "\nresidual RMS %.3g N (%.2g %% of peak)" % (fj["residual_rms_N"], fj["residual_rms_percent_of_peak"]),
                 fontsize=10)
    ax.legend(fontsize=7, ncol=2)
    ax.grid(alpha=0.3)
    fig.tight_layout()
    save(fig, os.path.join(out, "fit_data_vs_model.png"))

    fig, ax = plt.subplots(figsize=(8, 4))
    for i, (tid, d) in enumerate(tests):
        ax.plot(d[xkey] * xs, d["residual_N"], "-", color="C%d" % (i % 10), lw=0.8, label=tid or "residual")
    ax.axhline(0.0, color="k", lw=0.5)
    ax.set_xlabel(xlabel)
    ax.set_ylabel("model - data [N]")
    ax.set_title(title + ": residuals", fontsize=10)
    ax.legend(fontsize=7)
    ax.grid(alpha=0.3)
    fig.tight_layout()
    save(fig, os.path.join(out, "fit_residuals.png"))

    if profile is not None:
        name, v, s = profile
        if isinstance(name, bytes):
            name = name.decode()
        import math
        n = fj["samples"]
        smin = min(s)
        fig, ax = plt.subplots(figsize=(6, 4))
        ax.plot(v, [n * math.log(x / smin) for x in s], "o-")
        ax.axhline(3.841, color="r", lw=0.8, label="chi2_1(0.95) = 3.84")
        ax.set_xlabel(name)
        ax.set_ylabel("n ln(SSE / SSE_min)")
        ax.set_title(title + ": profile likelihood", fontsize=10)
        ax.legend(fontsize=8)
        ax.grid(alpha=0.3)
        fig.tight_layout()
        save(fig, os.path.join(out, "fit_profile.png"))


if __name__ == "__main__":
    main()
