#!/usr/bin/env python3
"""The phantom worked example of `tmlab discover` (docs/measured-data.md): the 10 repeats of one
grade combined as the tests of one data set (every STRIDE-th sample; phantom_ranking.combine of
calibration/fit/python), then `tmlab discover` on it.
Usage: phantom_discover.py TMLAB WORK [GRADE [STRIDE]]   (GRADE default EF10_0T, STRIDE 10)
Writes WORK/combined/GRADE.csv + .json and WORK/discover-GRADE/ (index.html, report.json, ...)."""
import os
import subprocess
import sys

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "fit", "python"))
from phantom_ranking import combine  # noqa: E402


def main():
    tmlab, work = sys.argv[1], sys.argv[2]
    grade = sys.argv[3] if len(sys.argv) > 3 else "EF10_0T"
    stride = int(sys.argv[4]) if len(sys.argv) > 4 else 10
    csv, n = combine(tmlab, work, grade, stride)
    print("%s: %d samples in 10 tests -> %s" % (grade, n, csv), flush=True)
    out = os.path.join(work, "discover-" + grade)
    sys.exit(subprocess.call([tmlab, "discover", csv, "--out", out]))


if __name__ == "__main__":
    main()
