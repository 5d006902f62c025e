#!/usr/bin/env python3
"""Synthetic sphere-indentation relaxation data in the tmlab-measured/1 format, made with the
Lee-Radok hereditary integral (a measuring aid for docs/identification.md, "Measured: a
6-parameter fit to 4 indentation depths"; not used by the tests).

Usage: lee_radok_data.py OUTDIR NAME [SEED]
Writes OUTDIR/NAME.csv and NAME.json: a sphere of radius 5 mm on a half-space, nu 0.45, E(t) =
3000 + 2000 exp(-t/0.4) + 1000 exp(-t/4) Pa, four tests to 0.5, 1, 1.5 and 2 mm in a 1 s ramp
(samples every 0.1 s), held to 20 s (25 log-spaced samples), Gaussian noise of 1 % of each test's
peak force.

F(t) = 4 sqrt(R) / (3 (1 - nu^2)) int_0^t E(t - s) d/ds [d(s)^(3/2)] ds, integrated with the
midpoint rule on 4000 intervals of the ramp (d is constant in the hold)."""
import json
import os
import sys

import numpy as np

R, NU = 0.005, 0.45
E_INF, E1, E2, TAU1, TAU2 = 3000.0, 2000.0, 1000.0, 0.4, 4.0
DEPTHS = [0.5e-3, 1.0e-3, 1.5e-3, 2.0e-3]
RAMP = 1.0


def relaxation(t):
    return E_INF + E1 * np.exp(-t / TAU1) + E2 * np.exp(-t / TAU2)


def force(t, depth):
    s = np.linspace(0.0, min(t, RAMP), 4001)
    g = (depth * s / RAMP) ** 1.5
    mid = 0.5 * (s[1:] + s[:-1])
    return 4.0 * np.sqrt(R) / (3.0 * (1.0 - NU ** 2)) * np.sum(relaxation(t - mid) * np.diff(g))


def main():
    if len(sys.argv) < 3:
        sys.exit(__doc__)
    out, name = sys.argv[1], sys.argv[2]
    seed = int(sys.argv[3]) if len(sys.argv) > 3 else 20261127
    rng = np.random.default_rng(seed)
    times = np.concatenate([np.arange(0.0, RAMP + 1e-9, 0.1), RAMP + np.geomspace(0.1, 19.0, 25)])
    rows = []
    for k, depth in enumerate(DEPTHS):
        f = np.array([force(t, depth) for t in times])
        f += rng.normal(0.0, 0.01 * f.max(), f.size)
        rows += ["d%d,%.6g,%.6g,%.8g" % (k + 1, t, depth * min(t, RAMP) / RAMP, y) for t, y in zip(times, f)]
    os.makedirs(out, exist_ok=True)
    with open(os.path.join(out, name + ".csv"), "w") as c:
        c.write("test_id,time_s,displacement_m,force_N\n" + "\n".join(rows) + "\n")
    meta = {"format": "tmlab-measured/1", "name": name, "test": "indentation",
            "indenter": {"shape": "sphere", "radius_m": R}, "sample": {"shape": "half_space"},
            "source": "synthetic (calibration/fit/python/lee_radok_data.py): Lee-Radok, E_inf 3000 Pa, "
                      "e 2000 / 1000 Pa, tau 0.4 / 4 s, nu 0.45, noise 1 %% of peak, seed %d" % seed,
            "license": "CC0-1.0"}
    with open(os.path.join(out, name + ".json"), "w") as j:
        json.dump(meta, j, indent=1)
    print("%s: %d samples in %d tests" % (os.path.join(out, name + ".csv"), len(rows), len(DEPTHS)))


if __name__ == "__main__":
    main()
