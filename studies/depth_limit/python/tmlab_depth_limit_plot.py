#!/usr/bin/env python3
"""Plot of `tmlab depth-limit` from DIR/depth_limit.json (written by apps/tmlab/cmd_depth_limit.cpp).

Usage: python3 tmlab_depth_limit_plot.py DIR

Writes DIR/depth_limit.png: left, the smallest volume ratio min det F against the indentation
depth, one panel line per law and mesh (line style by mesh), the end of each run marked (x: a tet
inverted, o: the contact solve failed, nothing: the depth range reached); right, the depth each run
ended at against the spacing at the indentation point.
Exit status 1 with a message naming the file when the input is missing or malformed.
"""
import json
import os
import sys

import matplotlib.pyplot as plt
# tmlab_study_plot.py, the helpers the studies' scripts share, is in studies/common/python/.
sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "common", "python"))
from tmlab_study_plot import fail as _fail  # noqa: E402
from tmlab_study_plot import input_file, label_axes, save  # noqa: E402

STYLES = ["-", "--", ":", "-."]


def fail(msg):
    _fail("tmlab_depth_limit_plot", msg)


def main():
    d, path = input_file("tmlab_depth_limit_plot", "depth_limit.json")
    try:
        with open(path) as f:
            doc = json.load(f)
        runs = doc["runs"]
    except (OSError, ValueError, KeyError) as e:
        fail(f"{path}: {e}")
    laws = []
    cells = sorted({r["cells"] for r in runs})
    for r in runs:
        if r["law"] not in laws:
            laws.append(r["law"])
    colors = {law: f"C{i}" for i, law in enumerate(laws)}
    fig, (ax, bx) = plt.subplots(1, 2, figsize=(12, 5))
    for r in runs:
        s = r["samples"]
        depth = [1e3 * x for x in s["depth_m"]]
        style = STYLES[cells.index(r["cells"]) % len(STYLES)]
        ax.plot(depth, s["min_J"], style, color=colors[r["law"]], label=f"{r['law']}, n = {r['cells']}")
        if depth and r["outcome"] != "max_depth":
            ax.plot(depth[-1], s["min_J"][-1], "x" if r["outcome"] == "inverted" else "o", color=colors[r["law"]])
    ax.axhline(0.0, color="k", lw=0.8)
    label_axes(ax, "smallest det F under the sphere (x inverted, o solver failed)", "depth [mm]", "min det F",
               legend_size=6)
    for law in laws:
        rs = sorted((r for r in runs if r["law"] == law), key=lambda r: r["h_min_m"])
        h = [1e3 * r["h_min_m"] for r in rs]
        end = [1e3 * (r["limit_depth_m"] if r["limit_depth_m"] is not None else r["deepest_converged_m"])
               for r in rs]
        bx.plot(h, end, "-o", color=colors[law], label=law)
    label_axes(bx, "depth reached (inversion, failure or the range end)", "spacing at the tip h [mm]",
               "depth [mm]")
    bx.set_xscale("log")
    save(fig, os.path.join(d, "depth_limit.png"), 120)


if __name__ == "__main__":
    main()
