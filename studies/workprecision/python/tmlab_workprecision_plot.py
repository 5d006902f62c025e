#!/usr/bin/env python3
"""Work-precision diagrams of `tmlab workprecision`.

Usage: python3 tmlab_workprecision_plot.py RESULT_DIR

Reads RESULT_DIR/workprecision.h5 (one group per problem, one sub-group per method with 1-D datasets
value, error, cpu_seconds, ...; see tensormass/include/tmlab/tensormass/work_precision.hpp) and
writes RESULT_DIR/workprecision_<problem>.png: error against CPU time, log-log, one line per method
(failed runs, whose error is NaN, are left out). Exits non-zero with a message naming the missing
file or dataset.
"""
import math
import os
import sys

STYLES = {
    "explicit": ("o", "-"),
    "implicit": ("s", "--"),
    "sundials": ("^", "-."),
}


def _text(v):
    return v.decode("utf-8", "replace") if isinstance(v, bytes) else str(v)


def plot(result_dir):
    try:
        import h5py
        import matplotlib

        matplotlib.use("Agg")
        import matplotlib.pyplot as plt
    except ImportError as e:
        raise SystemExit(f"tmlab_workprecision_plot: {e} (install python3-h5py and python3-matplotlib)")
    path = os.path.join(result_dir, "workprecision.h5")
    if not os.path.exists(path):
        raise SystemExit(f"tmlab_workprecision_plot: {path} not found")
    with h5py.File(path, "r") as f:
        for problem in f:
            g = f[problem]
            fig, ax = plt.subplots(figsize=(8, 5.5))
            for slug in g:
                m = g[slug]
                for ds in ("error", "cpu_seconds", "value"):
                    if ds not in m:
                        raise SystemExit(f"tmlab_workprecision_plot: {path}: /{problem}/{slug}/{ds} missing")
                err, cpu, val = m["error"][()], m["cpu_seconds"][()], m["value"][()]
                pts = [(c, e, v) for c, e, v in zip(cpu, err, val) if not math.isnan(e) and e > 0 and c > 0]
                if not pts:
                    continue
                family = _text(m.attrs.get("family", "sundials"))
                marker, line = STYLES.get(family, ("x", ":"))
                ax.loglog([p[0] for p in pts], [p[1] for p in pts], marker=marker, linestyle=line,
                          label=_text(m.attrs.get("method", slug)))
            ref = _text(g.attrs.get("reference_method", ""))
            rtol = g.attrs.get("reference_rtol", float("nan"))
            ax.set_xlabel("CPU time [s]")
            ax.set_ylabel("max_t |u - u_ref|_inf / max_t |u_ref|_inf")
            ax.set_title(f"work-precision: {problem} (reference {ref}, rtol {rtol:.0e})", fontsize=10)
            ax.grid(True, which="both", alpha=0.3)
            ax.legend(fontsize=8)
            fig.tight_layout()
            out = os.path.join(result_dir, f"workprecision_{problem}.png")
            fig.savefig(out, dpi=120)
            plt.close(fig)
            print(out)


if __name__ == "__main__":
    if len(sys.argv) != 2:
        raise SystemExit(__doc__)
    plot(sys.argv[1])
