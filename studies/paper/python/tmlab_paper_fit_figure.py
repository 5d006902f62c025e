#!/usr/bin/env python3
"""Draws Fig. 2 or Fig. 3 of `tmlab paper` (Section IV-A of Xu et al. 2011) from DIR/paper_fit.json.

paper_fit.json: {"figure", "viscoelastic", "fits": [{"kind", "law", "depth_m", "status", "time_s",
"force_N" (the noisy reference), "reference_force_N" (noise-free), "model_force_N" (the fitted
model, when status is ok)}], "usable_depth": {"statement"}}. Left: force against time, the reference
(markers) and the tensor-mass fits (St VK solid, neo-Hookean dashed) at every depth. Right: the
residual of each tensor-mass fit in % of its curve's peak. Writes DIR/<figure>.png. Exit status 1 with
a message naming the file when an input is missing.
"""
import json
import os
import sys
import textwrap

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402
# tmlab_study_plot.py, the helpers the studies' scripts share, is in studies/common/python/.
sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "common", "python"))
from tmlab_study_plot import input_file, label_axes, save  # noqa: E402

STYLE = {"stvk": "-", "neo_hookean": "--"}


def main():
    d, path = input_file("tmlab_paper_fit_figure", "paper_fit.json")
    with open(path) as fh:
        spec = json.load(fh)
    fits = spec["fits"]
    depths = sorted({f["depth_m"] for f in fits})
    colors = plt.rcParams["axes.prop_cycle"].by_key()["color"]
    fig, (ax, axr) = plt.subplots(1, 2, figsize=(12, 5))
    for i, depth in enumerate(depths):
        c = colors[i % len(colors)]
        ref = next(f for f in fits if f["depth_m"] == depth)
        t = np.asarray(ref["time_s"])
        ax.plot(t, ref["force_N"], "o", color=c, ms=4, label=f"reference {depth * 1e3:g} mm")
        peak = max(abs(v) for v in ref["reference_force_N"]) or 1.0
        for f in fits:
            if f["depth_m"] != depth or f["kind"] != "tensor_mass" or f["status"] != "ok":
                continue
            style = STYLE.get(f["law"], ":")
            ax.plot(t, f["model_force_N"], style, color=c, lw=1.2, label=f"{f['law']} {depth * 1e3:g} mm")
            res = 100.0 * (np.asarray(f["model_force_N"]) - np.asarray(f["force_N"])) / peak
            axr.plot(t, res, style, color=c, marker=".", label=f"{f['law']} {depth * 1e3:g} mm")
    kind = "relaxation (Lee-Radok reference)" if spec["viscoelastic"] else "elastic (Hertz reference)"
    label_axes(ax, f"{spec['figure']}: tensor-mass fits, {kind}", "time [s]", "indentation force [N]")
    label_axes(axr, "\n".join(textwrap.wrap(spec["usable_depth"]["statement"], 55)), "time [s]",
               "residual [% of peak]")
    save(fig, os.path.join(d, spec["figure"] + ".png"), 120)


if __name__ == "__main__":
    main()
