#!/usr/bin/env python3
"""Plots of `tmlab hereditary` from DIR/hereditary.h5 (written by apps/tmlab/cmd_hereditary.cpp).

Usage: python3 tmlab_hereditary_plot.py DIR

Writes into DIR:
  error_vs_dt_over_tau.png  one panel per history: error of each recursion against dt/tau (log-log),
                            fitted slopes in the legend, 1 % and 10 % lines
  time_history.png          ramp-hold X(t_n) at dt/tau = 0.5, 2.5, 5 per recursion against the exact X
  amplification.png         a and c of each recursion against dt/tau, the exact weights, and for
                            comparison the trapezoidal factor (1 - x/2)/(1 + x/2) (not used by tmlab)
  haptic.png                error at dt = 1 ms against tau (if present)
  liver_error.png           liver relaxation: coupled and isolated error against dt (if present)
Exit status 1 with a message naming the file or dataset when an input is missing.
"""
import os
import sys

import h5py
import matplotlib.pyplot as plt
import numpy as np
# tmlab_study_plot.py, the helpers the studies' scripts share, is in studies/common/python/.
sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "common", "python"))
from tmlab_study_plot import fail as _fail  # noqa: E402
from tmlab_study_plot import input_file, label_axes, save  # noqa: E402

SCHEMES = ["midpoint", "exact_linear", "backward_euler"]
COLORS = {"midpoint": "tab:red", "exact_linear": "tab:blue", "backward_euler": "tab:green"}
LABELS = {"midpoint": "midpoint (xu2011, eq. 20)", "exact_linear": "exact_linear", "backward_euler": "backward_euler"}


def fail(msg):
    _fail("tmlab_hereditary_plot", msg)


def read(f, path):
    if path not in f:
        fail(f"{f.filename}: no dataset {path}")
    return np.asarray(f[path][...], dtype=float)


def sweep_plot(f, out):
    histories = list(f["/sweep"].keys()) if "/sweep" in f else []
    if not histories:
        return
    n = len(histories)
    cols = min(3, n)
    rows = (n + cols - 1) // cols
    fig, axes = plt.subplots(rows, cols, figsize=(5.0 * cols, 4.0 * rows), squeeze=False)
    for i, h in enumerate(histories):
        ax = axes[i // cols][i % cols]
        for s in SCHEMES:
            g = f"/sweep/{h}/{s}"
            if g not in f:
                continue
            q = read(f, g + "/dt_over_tau")
            e = read(f, g + "/error")
            order = f[g].attrs.get("order", np.nan)
            lab = f"{LABELS[s]}, slope {order:.2f}" if np.isfinite(order) else f"{LABELS[s]}, slope -"
            ax.loglog(q, e, "o-", color=COLORS[s], ms=3, label=lab)
        ax.axhline(0.01, color="grey", lw=0.8, ls=":")
        ax.axhline(0.1, color="grey", lw=0.8, ls="--")
        ax.axvline(2.0, color="k", lw=0.5, ls=":")
        label_axes(ax, h, "dt / tau", "max |X_rec - X| / max |X|", which="both")
    for j in range(n, rows * cols):
        axes[j // cols][j % cols].axis("off")
    fig.suptitle("Prony recursions against the exact hereditary integral (one term, alpha = 1)")
    save(fig, os.path.join(out, "error_vs_dt_over_tau.png"), 110)


def time_history_plot(f, out):
    if "/time_history/exact_fine" not in f:
        return
    tf = read(f, "/time_history/exact_fine/t")
    xf = read(f, "/time_history/exact_fine/x")
    qs = sorted({k.split("dt_over_tau_")[1] for s in SCHEMES if f"/time_history/{s}" in f
                 for k in f[f"/time_history/{s}"].keys()}, key=float)
    fig, axes = plt.subplots(1, len(qs), figsize=(5.0 * len(qs), 4.0), squeeze=False)
    for i, q in enumerate(qs):
        ax = axes[0][i]
        ax.plot(tf, xf, "k-", lw=1.2, label="exact")
        for s in SCHEMES:
            g = f"/time_history/{s}/dt_over_tau_{q}"
            if g not in f:
                continue
            ax.plot(read(f, g + "/t"), read(f, g + "/x_rec"), "o--", color=COLORS[s], ms=4, label=LABELS[s])
        label_axes(ax, f"ramp-hold (ramp over tau), dt/tau = {q}", "t / tau", "X = X_e + alpha h  (X_e / E_inf)")
    save(fig, os.path.join(out, "time_history.png"), 110)


def amplification_plot(f, out):
    if "/amplification" not in f:
        return
    x = read(f, "/amplification/dt_over_tau")
    fig, (a1, a2) = plt.subplots(1, 2, figsize=(11, 4))
    for s in SCHEMES:
        a1.semilogx(x, read(f, f"/amplification/{s}_a"), color=COLORS[s], label=LABELS[s])
        a2.loglog(x, read(f, f"/amplification/{s}_c"), color=COLORS[s], label=LABELS[s])
    a1.semilogx(x, np.exp(-x), "k:", lw=2, label="exact decay e^{-dt/tau}")
    a1.semilogx(x, (1 - x / 2) / (1 + x / 2), color="grey", ls="--",
                label="trapezoidal (1-x/2)/(1+x/2): NOT used by tmlab")
    a1.axhline(0.0, color="k", lw=0.5)
    a1.set_ylim(-1.05, 1.05)
    label_axes(a1, "", "dt / tau", "a (decay of h per step)", which="both")
    a2.loglog(x, -np.expm1(-x) / x, "k:", lw=2, label="exact for linear X_e: (1-e^{-x})/x")
    a2.set_ylim(1e-4, 2)
    label_axes(a2, "", "dt / tau", "c (weight of the increment of X_e)", which="both")
    save(fig, os.path.join(out, "amplification.png"), 110)


def haptic_plot(f, out):
    if "/haptic" not in f:
        return
    tau = read(f, "/haptic/tau")
    hist = [k for k in f["/haptic"].keys() if k != "tau"]
    fig, axes = plt.subplots(1, len(hist), figsize=(4.5 * len(hist), 4.0), squeeze=False)
    for i, h in enumerate(hist):
        ax = axes[0][i]
        for s in SCHEMES:
            p = f"/haptic/{h}/{s}_error"
            if p in f:
                ax.loglog(tau * 1e3, read(f, p), "o-", color=COLORS[s], ms=3, label=LABELS[s])
        ax.axhline(0.01, color="grey", lw=0.8, ls=":")
        ax.axvline(0.5, color="k", lw=0.5, ls=":")
        label_axes(ax, f"{h}, dt = 1 ms", "tau [ms]", "max |X_rec - X| / max |X|", which="both")
    save(fig, os.path.join(out, "haptic.png"), 110)


def liver_plot(f, out):
    if "/liver" not in f:
        return
    fig, (a1, a2) = plt.subplots(1, 2, figsize=(12, 4.5))
    styles = {"nodal_force": "-", "pk2": "--"}
    for hist in f["/liver"].keys():
        root = f"/liver/{hist}"
        ls = styles.get(hist, "-.")
        a1.plot(read(f, root + "/t_ref"), read(f, root + "/force_ref"), color="k", ls=ls, lw=1.5,
                label=f"{hist}: reference (Richardson, exact_linear)")
        for s in SCHEMES:
            g = f"{root}/{s}"
            if g not in f:
                continue
            dt = read(f, g + "/dt")
            a2.loglog(dt, read(f, g + "/error"), "o" + ls, color=COLORS[s], label=f"{hist}, {LABELS[s]}: coupled")
            iso = read(f, g + "/isolated_error")
            if np.all(np.isfinite(iso)):
                a2.loglog(dt, iso, "x", color=COLORS[s], ms=9, label=f"{hist}, {LABELS[s]}: isolated")
            runs = [k for k in f[g].keys() if k.startswith("dt_")]
            if runs and hist == "nodal_force":
                k = max(runs, key=lambda n: float(n[3:]))
                a1.plot(read(f, f"{g}/{k}/t"), read(f, f"{g}/{k}/force"), "o", ms=3, color=COLORS[s],
                        label=f"{hist}, {LABELS[s]}, dt = {k[3:]} s")
    label_axes(a1, "liver relaxation (fig6)", "t [s]", "indentation force [N]", legend_size=6)
    label_axes(a2, "reaction-force error (solid: nodal_force, dashed: pk2)", "dt [s]",
               "max |F - F_ref| / max |F_ref|", legend_size=6, which="both")
    save(fig, os.path.join(out, "liver_error.png"), 110)


def main():
    out, path = input_file("tmlab_hereditary_plot", "hereditary.h5")
    with h5py.File(path, "r") as f:
        sweep_plot(f, out)
        time_history_plot(f, out)
        amplification_plot(f, out)
        haptic_plot(f, out)
        liver_plot(f, out)


if __name__ == "__main__":
    main()
