#!/usr/bin/env python3
"""Plot time series of a tmlab result directory.

Usage: python3 tmlab_plot.py RESULT_DIR

Reads RESULT_DIR/timeseries.h5 (1-D datasets /series/<name>, each with an optional string
attribute "unit", and /series/time) and RESULT_DIR/plots.json, a list of plot specs:

    [{"file": "energy.png", "x": "time", "y": ["kinetic", "elastic"],
      "title": "Energy", "xlabel": "t [s]", "ylabel": "E [J]", "logy": false}]

and writes each PNG into RESULT_DIR. Only "file" and "y" are required; "x" defaults to "time",
labels default to the series names with their units. Exits non-zero with a message naming the
missing file, dataset or key.
"""
import json
import os
import sys


class PlotError(Exception):
    """A user-facing problem with the inputs (message names the file or dataset)."""


def _unit(dataset):
    unit = dataset.attrs.get("unit", "")
    if isinstance(unit, bytes):
        unit = unit.decode("utf-8", "replace")
    return str(unit)


def _label(name, unit):
    return f"{name} [{unit}]" if unit else name


def load_specs(path):
    try:
        with open(path, encoding="utf-8") as f:
            specs = json.load(f)
    except FileNotFoundError:
        raise PlotError(f"{path}: no such file")
    except json.JSONDecodeError as e:
        raise PlotError(f"{path}:{e.lineno}: invalid JSON: {e.msg}")
    if not isinstance(specs, list):
        raise PlotError(f"{path}: expected a list of plot specs")
    for i, spec in enumerate(specs):
        if not isinstance(spec, dict):
            raise PlotError(f"{path}: plot {i}: expected an object")
        for key in ("file", "y"):
            if key not in spec:
                raise PlotError(f"{path}: plot {i}: missing key '{key}'")
        if isinstance(spec["y"], str):
            spec["y"] = [spec["y"]]
        if os.path.basename(spec["file"]) != spec["file"] or not spec["file"].endswith(".png"):
            raise PlotError(f"{path}: plot {i}: 'file' must be a plain .png name, got '{spec['file']}'")
    return specs


def plot(result_dir):
    """Writes every plot of RESULT_DIR/plots.json; returns the PNG paths written."""
    import h5py  # imported here so --help and spec errors work without it
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    specs = load_specs(os.path.join(result_dir, "plots.json"))
    h5_path = os.path.join(result_dir, "timeseries.h5")
    if not os.path.exists(h5_path):
        raise PlotError(f"{h5_path}: no such file")
    written = []
    with h5py.File(h5_path, "r") as h5:
        def series(name, plot_file):
            key = f"/series/{name}"
            if key not in h5 or not isinstance(h5[key], h5py.Dataset):
                raise PlotError(f"{h5_path}: plot {plot_file}: missing dataset {key}")
            ds = h5[key]
            if ds.ndim != 1:
                raise PlotError(f"{h5_path}: {key}: expected a 1-D series, got shape {ds.shape}")
            return ds[()], _unit(ds)

        for spec in specs:
            xname = spec.get("x", "time")
            x, xunit = series(xname, spec["file"])
            fig, ax = plt.subplots(figsize=(7, 4.5), dpi=100)
            units = set()
            for yname in spec["y"]:
                y, yunit = series(yname, spec["file"])
                if len(y) != len(x):
                    raise PlotError(f"{h5_path}: /series/{yname} has {len(y)} values, "
                                    f"/series/{xname} has {len(x)}")
                units.add(yunit)
                ax.plot(x, y, label=_label(yname, yunit))
            ax.set_xlabel(spec.get("xlabel", _label(xname, xunit)))
            if "ylabel" in spec:
                ax.set_ylabel(spec["ylabel"])
            elif len(spec["y"]) == 1:
                ax.set_ylabel(_label(spec["y"][0], units.pop()))
            elif len(units) == 1 and next(iter(units)):
                ax.set_ylabel(f"[{units.pop()}]")
            if spec.get("title"):
                ax.set_title(spec["title"])
            if spec.get("logy", False):
                ax.set_yscale("log")
            if len(spec["y"]) > 1:
                ax.legend()
            ax.grid(True, alpha=0.3)
            fig.tight_layout()
            out = os.path.join(result_dir, spec["file"])
            fig.savefig(out)
            plt.close(fig)
            written.append(out)
    return written


def main(argv):
    if len(argv) != 2 or argv[1] in ("-h", "--help"):
        print(__doc__.strip(), file=sys.stderr)
        return 0 if len(argv) == 2 else 2
    try:
        for path in plot(argv[1]):
            print(path)
    except PlotError as e:
        print(f"tmlab_plot: error: {e}", file=sys.stderr)
        return 1
    except ImportError as e:
        print(f"tmlab_plot: error: {e.name or e} is required (python3 with matplotlib and h5py)",
              file=sys.stderr)
        return 1
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
