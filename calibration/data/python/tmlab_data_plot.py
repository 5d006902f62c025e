#!/usr/bin/env python3
"""Plot a measured data set (`tmlab data show`): force against displacement and against time.

Usage: python3 tmlab_data_plot.py PLOT_JSON OUT_PNG

PLOT_JSON is written by `tmlab data show` from a data set the strict C++ reader has accepted:

    {"name": "EF10_0T_A1", "title": "...",
     "tests": [{"id": "", "time_s": [...], "displacement_m": [...], "force_N": [...]}]}

OUT_PNG gets one figure with two panels (displacement in mm, force in N, one line per test). The
PNG is written to OUT_PNG.tmp.png first and renamed, so a failed plot leaves no half-written file.
Exits non-zero with a message naming the file on bad input.
"""
import json
import os
import sys


class PlotError(Exception):
    """A user-facing problem with the inputs (the message names the file)."""


def load(path):
    try:
        with open(path, encoding="utf-8") as f:
            data = json.load(f)
    except FileNotFoundError:
        raise PlotError(f"{path}: no such file")
    except json.JSONDecodeError as e:
        raise PlotError(f"{path}:{e.lineno}: invalid JSON: {e.msg}")
    tests = data.get("tests") if isinstance(data, dict) else None
    if not isinstance(tests, list) or not tests:
        raise PlotError(f"{path}: expected an object with a non-empty list 'tests'")
    for i, t in enumerate(tests):
        for key in ("time_s", "displacement_m", "force_N"):
            if not isinstance(t.get(key), list):
                raise PlotError(f"{path}: test {i}: missing list '{key}'")
        if not len(t["time_s"]) == len(t["displacement_m"]) == len(t["force_N"]):
            raise PlotError(f"{path}: test {i}: time, displacement and force differ in length")
    return data


def plot(data, out_png):
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig, (ax_d, ax_t) = plt.subplots(1, 2, figsize=(11, 4.5))
    tests = data["tests"]
    for i, t in enumerate(tests):
        label = t.get("id") or data.get("name", "")
        # Beyond 12 tests the legend would hide the curves: label the first 12 only.
        kw = {"label": label} if i < 12 else {}
        d_mm = [1e3 * d for d in t["displacement_m"]]
        ax_d.plot(d_mm, t["force_N"], lw=1.2, **kw)
        ax_t.plot(t["time_s"], t["force_N"], lw=1.2, **kw)
    ax_d.set_xlabel("displacement [mm] (positive into the sample)")
    ax_d.set_ylabel("force [N] (positive: the sample pushes back)")
    ax_d.set_title("force vs displacement")
    ax_t.set_xlabel("time [s]")
    ax_t.set_ylabel("force [N]")
    ax_t.set_title("force vs time")
    for ax in (ax_d, ax_t):
        ax.grid(True, alpha=0.3)
        if len(tests) > 1:
            ax.legend(fontsize=8)
    fig.suptitle(data.get("title", data.get("name", "")), fontsize=10)
    fig.tight_layout()
    tmp = out_png + ".tmp.png"
    fig.savefig(tmp, dpi=110, format="png")
    plt.close(fig)
    os.replace(tmp, out_png)


def main(argv):
    if len(argv) != 3:
        print(__doc__, file=sys.stderr)
        return 2
    try:
        plot(load(argv[1]), argv[2])
    except PlotError as e:
        print(f"tmlab_data_plot: {e}", file=sys.stderr)
        return 1
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
