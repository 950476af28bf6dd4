#!/usr/bin/python3
"""Compares a `waam thermal` run with a build's process log: the timeline per layer against the log's arc-on
intervals, and the probes against the thermocouples (docs/THERMAL.md "A real G-code: SRP-4").

    /usr/bin/python3 tools/compare_thermal_log.py THERMAL_DIR LOG.csv [--header-rows 5] [--time Timestamp]
        [--arc-on "Weld On"] [--column tc1="Thermocouple 1" ...] [--layer-gap-s 30] [--figure FILE.png]

- THERMAL_DIR holds thermal.json (the timeline) and thermal.h5 (/probes/time_s, /probes/<NAME>).
- The log is a CSV with `--header-rows` metadata lines before its column names (as tools/xlsx_to_csv.py writes
  it); its time column is in seconds or hh:mm:ss, counted from its first row.
- The log's arc-on intervals (rows where the arc-on column is not 0) are grouped into layers: an arc-off gap longer
  than --layer-gap-s starts a new layer. The simulation's clock is shifted so that its first arc start falls on the
  log's first arc-on row; the shift is printed.
- A probe NAME is compared with the column given by --column NAME=COLUMN, else with "Thermocouple <n>" for a probe
  named tc<n>; the simulated history is interpolated linearly at the log's rows inside the simulated span.
Prints three tables (layers; probes: peak, time of peak, peak error, rmse, mean absolute error, mean error; the
mean over the compared probes at each logged layer's last arc off and at the end of the log, measured and simulated)
and writes the figure (probes, measured and simulated) when --figure is given. Exits 2 with one line on stderr on a missing file or column.
"""
import argparse
import json
import os
import re
import sys

import numpy as np
import pandas as pd


def fail(message):
    print(f"compare_thermal_log: {message}", file=sys.stderr)
    sys.exit(2)


def log_seconds(column):
    """The log's time column in seconds from its first row (numbers as seconds, else hh:mm:ss)."""
    numbers = pd.to_numeric(column, errors="coerce")
    if numbers.notna().all():
        t = numbers.to_numpy(float)
    else:
        t = pd.to_timedelta(column.astype(str)).dt.total_seconds().to_numpy(float)
    return t - t[0]


def arc_intervals(t, on):
    """[start, end) of each run of arc-on rows: start the first on row's time, end the first off row's time."""
    out, start = [], None
    for k in range(len(on)):
        if on[k] and start is None:
            start = t[k]
        elif not on[k] and start is not None:
            out.append((start, t[k]))
            start = None
    if start is not None:
        out.append((start, t[-1]))
    return out


def group_layers(intervals, gap_s):
    layers = []
    for a, b in intervals:
        if layers and a - layers[-1][-1][1] <= gap_s:
            layers[-1].append((a, b))
        else:
            layers.append([(a, b)])
    return layers


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("thermal_dir")
    ap.add_argument("log")
    ap.add_argument("--header-rows", type=int, default=5)
    ap.add_argument("--time", default="Timestamp")
    ap.add_argument("--arc-on", default="Weld On")
    ap.add_argument("--column", action="append", default=[], help="NAME=COLUMN")
    ap.add_argument("--layer-gap-s", type=float, default=30.0)
    ap.add_argument("--figure")
    a = ap.parse_args()

    json_path = os.path.join(a.thermal_dir, "thermal.json")
    h5_path = os.path.join(a.thermal_dir, "thermal.h5")
    for path in (json_path, h5_path, a.log):
        if not os.path.isfile(path):
            fail(f"{path}: no such file")
    import h5py  # python3-h5py (tools/install_deps.sh)

    with open(json_path) as f:
        thermal = json.load(f)
    log = pd.read_csv(a.log, skiprows=a.header_rows)
    for name in (a.time, a.arc_on):
        if name not in log.columns:
            fail(f"{a.log}: no column '{name}'")
    t_log = log_seconds(log[a.time])
    on = log[a.arc_on].to_numpy(float) != 0.0
    logged = group_layers(arc_intervals(t_log, on), a.layer_gap_s)
    sim = thermal["timeline"]["layers"]
    if not logged:
        fail(f"{a.log}: no row with the arc on")
    shift = logged[0][0][0] - sim[0]["start_s"]

    print(f"clock: simulated t + {shift:.1f} s = log t (the first arc starts aligned)")
    print(f"{'layer':>5} | {'sim start':>9} {'log start':>9} | {'sim end':>8} {'log end':>8} | "
          f"{'sim arc':>7} {'log arc':>7} | {'sim gap':>7} {'log gap':>7} | sim wait")
    for k in range(max(len(sim), len(logged))):
        s = sim[k] if k < len(sim) else None
        g = logged[k] if k < len(logged) else None
        cells = []
        cells.append(f"{s['start_s'] + shift:9.1f}" if s else f"{'-':>9}")
        cells.append(f"{g[0][0]:9.1f}" if g else f"{'-':>9}")
        cells.append(f"{s['end_s'] + shift:8.1f}" if s else f"{'-':>8}")
        cells.append(f"{g[-1][1]:8.1f}" if g else f"{'-':>8}")
        cells.append(f"{s['arc_on_s']:7.1f}" if s else f"{'-':>7}")
        cells.append(f"{sum(b - a for a, b in g):7.1f}" if g else f"{'-':>7}")
        sim_gap = sim[k + 1]["start_s"] - s["end_s"] if s and k + 1 < len(sim) else None
        log_gap = logged[k + 1][0][0] - g[-1][1] if g and k + 1 < len(logged) else None
        cells.append(f"{sim_gap:7.1f}" if sim_gap is not None else f"{'-':>7}")
        cells.append(f"{log_gap:7.1f}" if log_gap is not None else f"{'-':>7}")
        wait = f"{s['wait_s']:8.1f}" if s else f"{'-':>8}"
        print(f"{k:5d} | {cells[0]} {cells[1]} | {cells[2]} {cells[3]} | {cells[4]} {cells[5]} | "
              f"{cells[6]} {cells[7]} | {wait}")
    print(f"total: simulated {thermal['timeline']['total_s']:.1f} s from the program's start; log's last arc off at "
          f"{logged[-1][-1][1]:.1f} s, simulated {sim[-1]['end_s'] + shift:.1f} s")

    columns = dict(item.split("=", 1) for item in a.column)
    with h5py.File(h5_path, "r") as f:
        t_sim = f["probes/time_s"][:] + shift
        names = sorted((n for n in f["probes"] if n != "time_s"),
                       key=lambda n: (re.sub(r"\d+$", "", n), int(re.search(r"\d*$", n).group() or 0)))
        histories = {n: f[f"probes/{n}"][:] for n in names}
    rows = []
    inside = (t_log >= t_sim[0]) & (t_log <= t_sim[-1])
    print(f"\n{'probe':>6} | {'peak log':>8} {'at':>6} | {'peak sim':>8} {'at':>6} | {'peak err':>8} | {'rmse':>6} "
          f"{'mae':>6} {'mean err':>8}  (degC, s; simulated minus measured over the {inside.sum()} log rows the run "
          f"spans)")
    for n in names:
        match = re.fullmatch(r"tc(\d+)", n)
        column = columns.get(n, f"Thermocouple {match.group(1)}" if match else None)
        if column is None or column not in log.columns:
            print(f"{n:>6} | no log column" + (f" '{column}'" if column else ""))
            continue
        measured = log[column].to_numpy(float)
        simulated = np.interp(t_log, t_sim, histories[n])
        valid = inside & np.isfinite(measured) & (measured != 0.0)  # an all-zero first row is no reading
        err = simulated[valid] - measured[valid]
        km, ks = np.argmax(np.where(valid, measured, -np.inf)), np.argmax(histories[n])
        rows.append((n, column, measured, simulated, valid))
        print(f"{n:>6} | {measured[km]:8.1f} {t_log[km]:6.0f} | {histories[n][ks]:8.1f} {t_sim[ks]:6.0f} | "
              f"{histories[n][ks] - measured[km]:+8.1f} | {np.sqrt(np.mean(err ** 2)):6.1f} {np.mean(np.abs(err)):6.1f} "
              f"{np.mean(err):+8.1f}")

    if rows:
        # The mean over the compared probes where both have a value: how the part's heat level climbs layer by layer.
        ends = [layer[-1][1] for layer in logged] + [t_log[inside][-1]]
        print(f"\n{'at log t':>8} | {'mean log':>8} {'mean sim':>8} {'diff':>6}  (degC; the mean of the compared probes at "
              f"each logged layer's last arc off, then at the run's last log row)")
        for te in ends:
            k = int(np.argmin(np.abs(t_log - te)))
            pairs = [(m[k], s[k]) for _, _, m, s, v in rows if v[k]]
            if not pairs:
                continue
            ml, ms = np.mean([p[0] for p in pairs]), np.mean([p[1] for p in pairs])
            print(f"{t_log[k]:8.0f} | {ml:8.1f} {ms:8.1f} {ms - ml:+6.1f}")

    if a.figure and rows:
        import matplotlib
        matplotlib.use("Agg")
        import matplotlib.pyplot as plt
        cols = 2
        fig, axes = plt.subplots((len(rows) + cols - 1) // cols, cols, figsize=(12, 2.2 * ((len(rows) + 1) // 2)),
                                 sharex=True, squeeze=False)
        for ax, (n, column, measured, simulated, valid) in zip(axes.flat, rows):
            ax.plot(t_log[valid], measured[valid], "k", lw=0.8, label=f"log: {column}")
            ax.plot(t_log[valid], simulated[valid], "tab:red", lw=0.8, label=f"simulated {n}")
            for layer in logged:
                for s0, s1 in layer:
                    ax.axvspan(s0, s1, color="tab:orange", alpha=0.08, lw=0)
            ax.set_ylabel("degC")
            ax.legend(loc="upper left", fontsize=7)
        for ax in axes[-1]:
            ax.set_xlabel("time from the log's first row, s (shaded: arc on in the log)")
        fig.tight_layout()
        fig.savefig(a.figure, dpi=110)
        print(f"\nfigure: {a.figure}")


if __name__ == "__main__":
    main()
