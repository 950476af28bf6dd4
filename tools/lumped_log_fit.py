#!/usr/bin/python3
"""How much metal a build's plate drags along: one-node energy balances fitted to a process log (docs/THERMAL.md
"A real G-code: SRP-4", "Why the simulated plate levelled off").

    /usr/bin/python3 tools/lumped_log_fit.py LOG.csv --capacity-j-k 3309 [--efficiency 0.8] [--header-rows 5]
        [--probes "Thermocouple 1,...,Thermocouple 10"] [--table "Thermocouple 11"] [--voltage "Weld Voltage"]
        [--current "Weld Current"] [--arc-on "Weld On"]

The plate's mean temperature T (the mean of the probe columns, row by row at the log's 1 s rows) is taken as one
lumped body: C dT/dt = efficiency x V x I (while the arc is on) - G (T - T_table), T_table the table column, explicit
Euler at the log's rows. Fitted by least squares (scipy): G alone with C = --capacity-j-k (the plate and the bead,
rho c V), then G and C together. Prints each fit's G (W/K), C (J/K, and C over the plate's) and rmse (K), and the
mean measured and fitted temperatures at the arc's last row of each layer (a gap over 30 s ends a layer). This is an
analysis of the log, not the twin: a C much larger than the plate's says the plate exchanges heat with a large
mass (a table, clamps) on the build's time scale. Exits 2 with one line on stderr on a missing file or column.
"""
import argparse
import os
import sys

import numpy as np
import pandas as pd


def fail(message):
    print(f"lumped_log_fit: {message}", file=sys.stderr)
    sys.exit(2)


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("log")
    ap.add_argument("--capacity-j-k", type=float, required=True)
    ap.add_argument("--efficiency", type=float, default=0.8)
    ap.add_argument("--header-rows", type=int, default=5)
    ap.add_argument("--probes", default=",".join(f"Thermocouple {i}" for i in range(1, 11)))
    ap.add_argument("--table", default="Thermocouple 11")
    ap.add_argument("--voltage", default="Weld Voltage")
    ap.add_argument("--current", default="Weld Current")
    ap.add_argument("--arc-on", default="Weld On")
    a = ap.parse_args()
    if not os.path.isfile(a.log):
        fail(f"{a.log}: no such file")
    log = pd.read_csv(a.log, skiprows=a.header_rows)
    probes = a.probes.split(",")
    for name in probes + [a.table, a.voltage, a.current, a.arc_on]:
        if name not in log.columns:
            fail(f"{a.log}: no column '{name}'")
    log = log[(log[probes] != 0.0).any(axis=1)]  # an all-zero row is no reading
    t_mean = log[probes].to_numpy(float).mean(axis=1)
    t_table = log[a.table].to_numpy(float)
    on = log[a.arc_on].to_numpy(float) != 0.0
    power = np.where(on, (log[a.voltage] * log[a.current]).clip(lower=0.0).to_numpy(float), 0.0)
    heat = a.efficiency * power

    def lumped(g, c):
        out = np.empty_like(t_mean)
        t = t_mean[0]
        for k in range(len(t_mean)):
            out[k] = t
            t += (heat[k] - g * (t - t_table[k])) / c
        return out

    from scipy.optimize import least_squares  # python3-scipy (tools/install_deps.sh)
    fixed = least_squares(lambda p: lumped(p[0], a.capacity_j_k) - t_mean, [20.0], bounds=([0.0], [1e4]))
    free = least_squares(lambda p: lumped(p[0], p[1]) - t_mean, [20.0, a.capacity_j_k],
                         bounds=([0.0, 0.01 * a.capacity_j_k], [1e4, 1e3 * a.capacity_j_k]))
    print(f"heat in: {heat.sum() / 1e6:.2f} MJ over {len(t_mean)} rows (efficiency {a.efficiency})")
    fits = [("C fixed", fixed.x[0], a.capacity_j_k, fixed.fun), ("C free", free.x[0], free.x[1], free.fun)]
    for name, g, c, res in fits:
        print(f"{name:8}: G = {g:6.1f} W/K, C = {c:8.0f} J/K ({c / a.capacity_j_k:4.1f} x the plate's), "
              f"rmse {np.sqrt(np.mean(res ** 2)):5.1f} K")
    ends = [k for k in range(len(on) - 1) if on[k] and not on[k + 1:k + 31].any()]
    print(f"{'row':>6} | {'measured':>8} | " + " | ".join(f"{name:>8}" for name, *_ in fits) + "  (mean, degC)")
    curves = [lumped(g, c) for _, g, c, _ in fits]
    for k in ends:
        print(f"{k:6d} | {t_mean[k]:8.1f} | " + " | ".join(f"{curve[k]:8.1f}" for curve in curves))


if __name__ == "__main__":
    main()
