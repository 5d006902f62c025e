#!/usr/bin/env python3
"""Plot of `tmlab converge` from DIR/converge.json (convergence/convergence_report.cpp).

Usage: python3 tmlab_converge_plot.py DIR

Writes DIR/converge.png, one row per quantity and time: left, the value against h (log h; a study in
time, options.refine = "time": against the time step dt), with the
Richardson-extrapolated value as a dashed line when the levels are asymptotic; right, log-log
against h, the estimated relative error |f_k - f_inf| / |f_inf| and the GCI when asymptotic, else
the relative change between successive levels |f_k - f_k-1| / |f_k|, with a line of the observed
order through the finest point.
Exit status 1 with a message naming the file when the input is missing or malformed.
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


def fail(msg):
    _fail("tmlab_converge_plot", msg)


def main():
    d, path = input_file("tmlab_converge_plot", "converge.json")
    try:
        with open(path) as f:
            doc = json.load(f)
        quantities = doc["quantities"]
        name = doc["options"]["name"]
        in_time = doc["options"].get("refine", "space") == "time"
    except (OSError, ValueError, KeyError) as e:
        fail(f"{path}: {e}")
    if not quantities:
        fail(f"{path}: no quantities")
    size_label = "dt (s, log)" if in_time else "h (mm, log)"
    rows = len(quantities)
    fig, axes = plt.subplots(rows, 2, figsize=(10, 3.6 * rows), squeeze=False)
    for row, q in enumerate(quantities):
        try:
            # The level sizes: dt in s (time) or h in mm (space).
            h = list(q["dt_s"]) if in_time else [1e3 * x for x in q["h_m"]]
            v = q["values"]
            unit = q["unit"]
            label = f'{q["name"]} at t = {q["time_s"]:g} s'
            asymptotic = q["verdict"] == "asymptotic"
            f_inf = q["extrapolated"]
            order = q["order"]
            levels = q["levels"]
        except (KeyError, TypeError) as e:
            fail(f"{path}: quantity {row}: {e}")
        ax = axes[row][0]
        ax.semilogx(h, v, "o-", label="levels")
        if asymptotic and f_inf is not None:
            ax.axhline(f_inf, ls="--", color="k", lw=0.8, label=f"extrapolated {f_inf:.6g}")
        ax.invert_xaxis()
        label_axes(ax, f"{name}: {label}", size_label, f"value ({unit})" if unit else "value")
        ax = axes[row][1]
        if asymptotic:
            err = [lv["relative_error"] for lv in levels]
            pts = [(x, e) for x, e in zip(h, err) if e is not None and e > 0]
            if pts:
                ax.loglog([p[0] for p in pts], [p[1] for p in pts], "o-", label="|f_k - f_inf| / |f_inf|")
            gci = [(x, lv["gci"]) for x, lv in zip(h, levels) if lv["gci"] is not None and lv["gci"] > 0]
            if gci:
                ax.loglog([p[0] for p in gci], [p[1] for p in gci], "s--", label="GCI")
            if pts and order is not None:
                x0, e0 = pts[-1]
                xs = [h[0], x0]
                ax.loglog(xs, [e0 * (x / x0) ** order for x in xs], ":", color="gray", label=f"slope p = {order:.3g}")
            title = f"asymptotic, p = {order:.3g}"
        else:
            pts = [(h[k], abs(v[k] - v[k - 1]) / abs(v[k])) for k in range(1, len(v)) if v[k] != 0 and v[k] != v[k - 1]]
            if pts:
                ax.loglog([p[0] for p in pts], [p[1] for p in pts], "o-", label="|f_k - f_k-1| / |f_k|")
            title = "not asymptotic: " + (q.get("reason") or "")
            if len(title) > 60:
                title = title[:57] + "..."
        ax.invert_xaxis()
        label_axes(ax, title, size_label, "relative error")
    save(fig, os.path.join(d, "converge.png"), 110)


if __name__ == "__main__":
    main()
