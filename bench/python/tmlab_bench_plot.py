"""Plots of tmlab bench: DIR/bench.json -> DIR/bench_ns_per_tet.png (force kernels, ns per tet
against mesh size, 1 thread) and DIR/bench_threads.png (speed-up of the fast kernel against threads)."""
import json
import sys
from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402


def main(d: Path) -> None:
    b = json.loads((d / "bench.json").read_text())
    force = [r for r in b["records"] if r["kind"] == "force"]
    series = {}
    for r in force:
        if r["threads"] != 1:
            continue
        key = f'{r["kernel"]} / {r["history"]} / {r["law"]}'
        series.setdefault(key, []).append((r["tets"], r["ns_per_tet"]))
    fig, ax = plt.subplots(figsize=(8, 5))
    for key, pts in sorted(series.items()):
        pts.sort()
        ax.plot([p[0] for p in pts], [p[1] for p in pts], "o-", label=key)
    peak = b["limits"]["peak_gflops_1t"]
    ax.axhline(249.0 / peak, color="k", ls="--", lw=0.8, label="compute floor, fast St VK (249 flops)")
    ax.set_xscale("log")
    ax.set_yscale("log")
    ax.set_xlabel("tets")
    ax.set_ylabel("ns per tet (1 thread)")
    ax.set_title("Internal force per tet")
    ax.legend(fontsize=7)
    ax.grid(True, which="both", alpha=0.3)
    fig.tight_layout()
    fig.savefig(d / "bench_ns_per_tet.png", dpi=120)

    fig, ax = plt.subplots(figsize=(7, 4.5))
    by = {}
    for r in force:
        if r["kernel"] != "fast":
            continue
        by.setdefault((r["history"], r["law"], r["mesh"], r["tets"]), {})[r["threads"]] = r["ns_per_tet"]
    for (hist, law, mesh, tets), t in sorted(by.items(), key=lambda kv: kv[0][3]):
        if 1 not in t:
            continue
        th = sorted(t)
        ax.plot(th, [t[1] / t[k] for k in th], "o-", label=f"{hist}/{law} {mesh}")
    ax.plot([1, 2], [1, 2], "k--", lw=0.8, label="ideal")
    ax.set_xlabel("threads")
    ax.set_ylabel("speed-up over 1 thread")
    ax.set_title("Fast kernel: speed-up against threads")
    ax.legend(fontsize=6, ncol=2)
    ax.grid(True, alpha=0.3)
    fig.tight_layout()
    fig.savefig(d / "bench_threads.png", dpi=120)


if __name__ == "__main__":
    main(Path(sys.argv[1]))
