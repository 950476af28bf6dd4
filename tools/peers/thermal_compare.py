#!/usr/bin/python3
"""Compares the probe histories of two thermal peers (JSON from waam_thermal_peer and thermal_fenicsx.py).

For each probe: the peak temperature of each, and the largest difference over the run divided by the reference's
peak rise above ambient (the reference is the second file, FEniCSx). waam's samples are interpolated linearly onto
the reference's times (both sample at the end of every step of the problem). Prints one line per probe, the worst
relative difference against the 2 % target, and the CPU and wall times of each side, the whole run and its time
stepping alone (after the mesh, the forms and the matrices, or waam's grid and wall, are set up), with their ratios
(reference / waam: above 1 means waam is faster).
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
    print(f"waam: {ours['cells']} cells, {ours['steps']} steps (incl. the wall's laying), {ours['iterations']} CG "
          f"iterations; fenicsx: {ref['dofs']} dofs (Q{ref['degree']}, {ref['mass']} mass, CG + {ref['pc']}, "
          f"rtol {ref['rtol']:g}), {ref['steps']} steps, {ref['iterations']} CG iterations")
    print(f"{'seconds':8s} {'waam_cpu':>9s} {'fenicsx_cpu':>11s} {'ratio':>6s} {'waam_wall':>9s} {'fenicsx_wall':>12s} "
          f"{'ratio':>6s}")
    for label, a, b, c, d in (
            ("run", ours["cpu_s"], ref["cpu_s"], ours["wall_s"], ref["wall_s"]),
            ("stepping", ours["cpu_s"] - ours["setup_cpu_s"], ref["cpu_s"] - ref["setup_cpu_s"],
             ours["wall_s"] - ours["setup_s"], ref["wall_s"] - ref["setup_s"])):
        print(f"{label:8s} {a:9.3f} {b:11.3f} {b / a:5.1f}x {c:9.3f} {d:12.3f} {d / c:5.1f}x")


if __name__ == "__main__":
    main()
