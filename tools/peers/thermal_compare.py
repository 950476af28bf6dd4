#!/usr/bin/python3
"""Compares the probe histories of two thermal peers (JSON from waam_thermal_peer and thermal_fenicsx.py).

For each probe: the peak temperature of each, and the largest difference over the run divided by the reference's
peak rise above ambient (the reference is the second file, FEniCSx). waam's samples are interpolated linearly onto
the reference's times. Prints one line per probe, then the worst relative difference, the 2 % target and the
ratios of wall-clock and CPU time (reference / waam: above 1 means waam is faster).
Usage: thermal_compare.py <waam.json> <fenicsx.json> <problem.json>
"""
import json
import sys

import numpy as np


def main():
    if len(sys.argv) != 4:
        sys.exit("usage: thermal_compare.py <waam.json> <fenicsx.json> <problem.json>")
    ours, ref, spec = (json.load(open(p)) for p in sys.argv[1:4])
    ambient = spec["ambient_c"]
    t_ref = np.asarray(ref["time_s"])
    worst = 0.0
    print(f"{'probe':14s} {'peak_waam_c':>11s} {'peak_fenicsx_c':>14s} {'max_diff_k':>10s} {'of_rise_%':>9s}")
    for name, history in ref["probes_c"].items():
        r = np.asarray(history)
        w = np.interp(t_ref, np.asarray(ours["time_s"]), np.asarray(ours["probes_c"][name]))
        rise = r.max() - ambient
        diff = np.abs(w - r).max()
        worst = max(worst, diff / rise)
        print(f"{name:14s} {w.max():11.2f} {r.max():14.2f} {diff:10.2f} {100 * diff / rise:9.2f}")
    print(f"worst difference {100 * worst:.2f} % of the peak rise (target 2 %: {'met' if worst <= 0.02 else 'NOT met'})")
    print(f"waam: {ours['cells']} cells, {ours['steps']} steps, wall {ours['wall_s']:.3f} s, cpu {ours['cpu_s']:.3f} s; "
          f"fenicsx: {ref['dofs']} dofs, {ref['steps']} steps, wall {ref['wall_s']:.3f} s "
          f"(setup incl. form compile {ref['setup_s']:.3f} s), cpu {ref['cpu_s']:.3f} s")
    print(f"time ratio fenicsx / waam: wall {ref['wall_s'] / ours['wall_s']:.1f}x, "
          f"cpu {ref['cpu_s'] / ours['cpu_s']:.1f}x")


if __name__ == "__main__":
    main()
