#!/usr/bin/env python3
"""Convergence plot of one verification case.

Usage: python3 plot_convergence.py SPEC.json OUT.png

SPEC.json: {"title": str, "series": {name: {"x": [...], "y": [...], "x_label": str, "y_label": str,
            "observed_order": float|null, "expected_order": float|null, "fit_points": int}}}
Log-log: measured points, the least-squares line over the fitted points (slope in the legend) and
a dashed line of the expected slope through the finest point. Exits non-zero naming the bad input.
"""
import json
import math
import sys
import textwrap


def main(argv):
    if len(argv) != 3:
        print(__doc__, file=sys.stderr)
        return 2
    try:
        with open(argv[1], encoding="utf-8") as f:
            spec = json.load(f)
    except (OSError, json.JSONDecodeError) as e:
        print(f"plot_convergence.py: {argv[1]}: {e}", file=sys.stderr)
        return 1
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    series = spec.get("series", {})
    if not series:
        print(f"plot_convergence.py: {argv[1]}: no series", file=sys.stderr)
        return 1
    fig, ax = plt.subplots(figsize=(6.0, 4.2), dpi=110)
    colors = plt.rcParams["axes.prop_cycle"].by_key()["color"]
    xlabel, ylabel = "h", "error"
    for k, (name, s) in enumerate(sorted(series.items())):
        pts = sorted((x, y) for x, y in zip(s["x"], s["y"]) if x > 0 and y > 0)
        if len(pts) < 1:
            continue
        xs, ys = [p[0] for p in pts], [p[1] for p in pts]
        c = colors[k % len(colors)]
        xlabel, ylabel = s.get("x_label", xlabel), s.get("y_label", ylabel)
        obs = s.get("observed_order")
        label = name if obs is None else f"{name} (fitted slope {obs:.2f})"
        ax.loglog(xs, ys, "o-", color=c, label=label)
        m = s.get("fit_points") or len(xs)
        m = min(max(m, 2), len(xs))
        if obs is not None and len(xs) >= 2:
            fx, fy = xs[:m], ys[:m]
            # least-squares intercept for the fitted slope, drawn over the fitted range
            b = sum(math.log(y) - obs * math.log(x) for x, y in zip(fx, fy)) / len(fx)
            ax.loglog([fx[0], fx[-1]], [math.exp(b) * fx[0] ** obs, math.exp(b) * fx[-1] ** obs], "-",
                      color=c, alpha=0.35, linewidth=4)
        exp_order = s.get("expected_order")
        if exp_order is not None:
            x0, y0 = xs[0], ys[0]
            ax.loglog([x0, xs[-1]], [y0, y0 * (xs[-1] / x0) ** exp_order], "--", color=c, alpha=0.8,
                      label=f"slope {exp_order:g} (expected)")
    ax.set_xlabel(xlabel)
    ax.set_ylabel(ylabel)
    ax.set_title(textwrap.fill(spec.get("title", ""), 70), fontsize=9)
    ax.grid(True, which="both", alpha=0.3)
    ax.legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(argv[2])
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
