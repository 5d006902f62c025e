"""Shared by the plotting scripts of the studies (studies/<study>/python/*.py):
the command line (one result directory), the error exit, and the finishing of axes and figures.
The scripts run as `python3 SCRIPT DIR` from studies/<study>/python/ and put this folder
(studies/common/python/) first on sys.path to import it.
"""
import os
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402


def fail(prog, msg):
    """Exit status 1 with `prog: msg` on standard error."""
    print(f"{prog}: {msg}", file=sys.stderr)
    sys.exit(1)


def input_file(prog, name):
    """The result directory DIR (the only argument) and DIR/name, which must exist."""
    if len(sys.argv) != 2:
        fail(prog, f"usage: {prog}.py DIR")
    d = sys.argv[1]
    path = os.path.join(d, name)
    if not os.path.exists(path):
        fail(prog, f"{path}: missing")
    return d, path


def label_axes(ax, title, xlabel, ylabel, legend_size=7, which="major"):
    """Title, axis labels, a light grid (`which` lines) and the legend."""
    ax.set_title(title)
    ax.set_xlabel(xlabel)
    ax.set_ylabel(ylabel)
    ax.grid(True, which=which, alpha=0.3)
    ax.legend(fontsize=legend_size)


def save(fig, path, dpi):
    """Lays out, writes and closes the figure."""
    fig.tight_layout()
    fig.savefig(path, dpi=dpi)
    plt.close(fig)
