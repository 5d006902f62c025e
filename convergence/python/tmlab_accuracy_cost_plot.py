#!/usr/bin/env python3
"""Accuracy against cost of one quantity over several elements and meshes (docs/verification.md,
"Accuracy against cost: seed-like indentation").

Usage: python3 tmlab_accuracy_cost_plot.py DIR

Reads DIR/accuracy_cost.json:
  {"title": str, "quantity": str, "unit": str,
   "reference": {"value": float, "label": str},
   "series": [{"label": str,
               "points": [{"tets": int, "value": float, "cpu_s": float|null, "wall_s": float|null}, ...]},
              ...]}
(values and the reference in `unit`; cpu_s the user + system CPU seconds of the run, wall_s its wall
time) and writes DIR/accuracy_cost.png: left, log-log, the relative error |value - reference| /
|reference| against the CPU time (wall time where no CPU time was measured, drawn hollow), one line
per series, with the 1 % line; right, the value against the tet count (log), with the reference as a
dashed line. Exit status 1 with a message naming the file when the input is missing or malformed.
"""
import json
import os
import sys

import matplotlib.pyplot as plt
# tmlab_study_plot.py, the helpers the studies' scripts share, is in studies/common/python/.
sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "studies", "common",
                                "python"))
from tmlab_study_plot import fail as _fail  # noqa: E402
from tmlab_study_plot import input_file, label_axes, save  # noqa: E402

MARKERS = ["o", "s", "^", "D", "v", "P", "X"]


def fail(msg):
    _fail("tmlab_accuracy_cost_plot", msg)


def number(v, what):
    if not isinstance(v, (int, float)) or isinstance(v, bool) or v != v:
        fail(f"{what}: not a number ({v!r})")
    return float(v)


def main():
    d, path = input_file("tmlab_accuracy_cost_plot", "accuracy_cost.json")
    try:
        with open(path) as f:
            doc = json.load(f)
        ref = number(doc["reference"]["value"], f"{path}: reference.value")
        ref_label = doc["reference"]["label"]
        series = doc["series"]
        unit = doc["unit"]
        quantity = doc["quantity"]
        title = doc["title"]
    except (OSError, ValueError, KeyError, TypeError) as e:
        fail(f"{path}: {e}")
    if ref == 0.0:
        fail(f"{path}: reference.value is zero (no relative error)")
    if not series:
        fail(f"{path}: no series")
    fig, (ax_err, ax_val) = plt.subplots(1, 2, figsize=(11, 4.2))
    for k, s in enumerate(series):
        try:
            label = s["label"]
            pts = s["points"]
        except (KeyError, TypeError) as e:
            fail(f"{path}: series {k}: {e}")
        marker = MARKERS[k % len(MARKERS)]
        tets, values, cost, hollow = [], [], [], []
        for j, p in enumerate(pts):
            where = f"{path}: series '{label}' point {j}"
            try:
                t = number(p["tets"], where + ": tets")
                v = number(p["value"], where + ": value")
                cpu, wall = p.get("cpu_s"), p.get("wall_s")
            except (KeyError, TypeError, AttributeError) as e:
                fail(f"{where}: {e}")
            tets.append(t)
            values.append(v)
            if cpu is not None:
                cost.append(number(cpu, where + ": cpu_s"))
                hollow.append(False)
            elif wall is not None:
                cost.append(number(wall, where + ": wall_s"))
                hollow.append(True)
            else:
                cost.append(None)
                hollow.append(False)
        err = [abs(v - ref) / abs(ref) for v in values]
        line = [(c, e) for c, e in zip(cost, err) if c is not None and c > 0 and e > 0]
        (l,) = ax_err.loglog([p[0] for p in line], [p[1] for p in line], marker + "-", label=label)
        open_pts = [(c, e) for c, e, h in zip(cost, err, hollow) if h and c is not None and c > 0 and e > 0]
        if open_pts:
            ax_err.loglog([p[0] for p in open_pts], [p[1] for p in open_pts], marker, mfc="white",
                          color=l.get_color())
        ax_val.semilogx(tets, values, marker + "-", color=l.get_color(), label=label)
    ax_err.axhline(0.01, ls=":", color="gray", lw=0.8, label="1 %")
    label_axes(ax_err, f"{title}: error against cost", "CPU time of the run (s; hollow: wall time)",
               f"|F - F_ref| / F_ref (F_ref = {ref:.4g} {unit})", which="both")
    ax_val.axhline(ref, ls="--", color="k", lw=0.8, label=f"{ref_label}: {ref:.4g} {unit}")
    ax_val.axhspan(0.99 * ref, 1.01 * ref, color="gray", alpha=0.15, label="+-1 %")
    label_axes(ax_val, f"{quantity}", "tets (log)", f"{quantity} ({unit})")
    save(fig, os.path.join(d, "accuracy_cost.png"), 110)


if __name__ == "__main__":
    main()
