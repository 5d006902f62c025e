#!/usr/bin/env python3
"""Draws one figure of `tmlab paper` from the runs listed in DIR/figure.json.

figure.json: {"name", "title", "xlabel", "ylabel", "runs": [{"id", "label", "scheme", "dir",
"x", "y", "x_sign", "y_sign"}]}. Each run directory holds timeseries.h5 (/series/<name>) and
summary.json. Writes DIR/<name>.png, DIR/<name>.h5 (the plotted curves) and, for the hysteresis
figure (fig7), DIR/<name>_energy.json: the loop area (closed-path integral of force over
indentation) next to the dissipated energy the model reports and the energy still stored in the
Maxwell branches at the end of the cycle (loop = dissipated + stored_end for one cycle from rest).
Exit status 1 with a message naming the file when an input is missing.
"""
import json
import os
import sys

import h5py
import matplotlib.pyplot as plt
import numpy as np
# tmlab_study_plot.py, the helpers the studies' scripts share, is in studies/common/python/.
sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "common", "python"))
from tmlab_study_plot import fail as _fail  # noqa: E402
from tmlab_study_plot import input_file  # noqa: E402


def fail(msg):
    _fail("tmlab_paper_figure", msg)


def series(run_dir, name):
    path = os.path.join(run_dir, "timeseries.h5")
    if not os.path.exists(path):
        fail(f"{path}: missing (did the run fail?)")
    with h5py.File(path, "r") as f:
        key = f"/series/{name}"
        if key not in f:
            fail(f"{path}: no dataset {key}")
        return np.asarray(f[key][...], dtype=float)


def main():
    d, spec_path = input_file("tmlab_paper_figure", "figure.json")
    with open(spec_path) as fh:
        spec = json.load(fh)
    name = spec["name"]
    styles = {"xu2011": "-", "seed": "-", "objective": "--"}
    colours = plt.rcParams["axes.prop_cycle"].by_key()["color"]
    fig, ax = plt.subplots(figsize=(8, 5))
    energy = []
    groups = {}
    with h5py.File(os.path.join(d, f"{name}.h5"), "w") as out:
        for run in spec["runs"]:
            # "dir" is relative to the figure directory (older figure.json files hold absolute paths).
            run["dir"] = os.path.join(d, run["dir"])
            x = run["x_sign"] * series(run["dir"], run["x"])
            y = run["y_sign"] * series(run["dir"], run["y"])
            g = out.create_group(run["id"])
            g["x"], g["y"] = x, y
            g.attrs["label"], g.attrs["x"], g.attrs["y"] = run["label"], spec["xlabel"], spec["ylabel"]
            key = run["label"].split(", ", 1)[1] if ", " in run["label"] else run["label"]
            colour = groups.setdefault(key, colours[len(groups) % len(colours)])
            ax.plot(x, y, styles.get(run["scheme"], ":"), color=colour, label=run["label"], lw=1.6)
            if name == "fig7":
                # Loop area: closed-path integral of F d(delta); x in mm -> metres.
                area = float(np.trapz(y, x * 1e-3))
                with open(os.path.join(run["dir"], "summary.json")) as fh:
                    s = json.load(fh)
                e = s.get("energy", {})
                diss, stored = e.get("total_dissipation_J"), e.get("stored_J")
                if diss is None or stored is None:
                    fail(f"{run['dir']}/summary.json: no energy bookkeeping (not a viscoelastic run?)")
                # One cycle from rest: loop area = dissipated + still stored at the end of the cycle
                # (the Maxwell branches have not relaxed); the residual is discretisation error.
                energy.append({"run": run["id"], "loop_area_J": area, "dissipation_J": diss,
                               "stored_end_J": stored, "balance_residual_J": area - diss - stored,
                               "relative_residual": abs(area - diss - stored) / abs(area) if area else None})
    ax.set_title(spec["title"])
    ax.set_xlabel(spec["xlabel"])
    ax.set_ylabel(spec["ylabel"])
    ax.grid(alpha=0.3)
    ax.legend(fontsize=7, ncol=2, loc="lower right" if energy else "best")
    if energy:
        rows = [f"{e['run']}: loop {e['loop_area_J']:.3e} J = dissipated {e['dissipation_J']:.3e}"
                f" + stored {e['stored_end_J']:.3e} (residual {e['relative_residual']:.1e})" for e in energy]
        ax.text(0.01, 0.99, "\n".join(rows), transform=ax.transAxes, va="top", fontsize=6, family="monospace")
        with open(os.path.join(d, f"{name}_energy.json"), "w") as fh:
            json.dump(energy, fh, indent=2)
    fig.tight_layout()
    fig.savefig(os.path.join(d, f"{name}.png"), dpi=130)
    print(os.path.join(d, f"{name}.png"))


if __name__ == "__main__":
    main()
