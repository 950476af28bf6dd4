#!/usr/bin/python3
"""Compares the probe histories of two thermal peers (JSON from waam_thermal_peer and thermal_fenicsx.py).

For each probe: the peak temperature of each, and the largest difference over the run divided by the reference's
peak rise above ambient (the reference is the second file, FEniCSx). waam's samples are interpolated linearly onto
the reference's times (both sample at the end of every step of the problem). Prints one line per probe, the worst
relative difference against the 2 % target, and the CPU and wall times of each side, the whole run and its time
stepping alone (after the mesh, the forms and the matrices, or waam's grid and wall, are set up), with their ratios
(reference / waam: above 1 means waam is faster).
With --against FILE... (finer runs of the same problem, from either peer) it also prints, per probe, how far each of
the two compared runs lies from each finer run (largest difference over the run, % of that run's peak rise, signed
as compared minus finer at that time): which side the difference between the two comes from.
With --brief it prints one line instead: waam's stepping, each probe's difference (% of the peak rise), the worst,
and the CPU ratios of the whole run and of the stepping.
Usage: thermal_compare.py <waam.json> <fenicsx.json> <problem.json> [--brief] [--against <finer.json>...]
"""
import argparse
import json

import numpy as np


def largest_difference(run, ref, name):
    """The signed difference of run from ref where it is largest over ref's times (K), and that time (s)."""
    t_ref = np.asarray(ref["time_s"])
    r = np.asarray(ref["probes_c"][name])
    w = np.interp(t_ref, np.asarray(run["time_s"]), np.asarray(run["probes_c"][name]))
    i = int(np.abs(w - r).argmax())
    return w[i] - r[i], t_ref[i]


def label(run, cell_mm):
    """waam 2mm, Q1 1mm, ...: the side and its cell size (FEniCSx: the Lagrange degree on that mesh)."""
    side = "waam" if run["peer"] == "waam" else f"Q{run['degree']}"
    return f"{side} {cell_mm / run['refine']:g}mm"


def brief(ours, ref, ambient):
    """One line: waam's stepping, each probe's largest difference (% of FEniCSx's peak rise), the CPU ratios."""
    parts = []
    worst = 0.0
    for name, history in ref["probes_c"].items():
        r = np.asarray(history)
        w = np.interp(np.asarray(ref["time_s"]), np.asarray(ours["time_s"]), np.asarray(ours["probes_c"][name]))
        d = np.abs(w - r).max() / (r.max() - ambient)
        worst = max(worst, d)
        parts.append(f"{name} {100 * d:.2f}")
    run = ref["cpu_s"] / ours["cpu_s"]
    stepping = (ref["cpu_s"] - ref["setup_cpu_s"]) / (ours["cpu_s"] - ours["setup_cpu_s"])
    print(f"  {ours.get('stepping', 'single-rate')}:\n    % of the rise: {', '.join(parts)}; worst {100 * worst:.2f} "
          f"({'met' if worst <= 0.02 else 'NOT met'}); waam CPU {ours['cpu_s']:.2f} s, FEniCSx / waam CPU "
          f"{run:.1f}x (run), {stepping:.1f}x (stepping)")


def main():
    parser = argparse.ArgumentParser(description="compares waam's and FEniCSx's probe histories")
    parser.add_argument("waam")
    parser.add_argument("fenicsx")
    parser.add_argument("problem")
    parser.add_argument("--against", nargs="*", default=[], help="finer runs to measure both against")
    parser.add_argument("--brief", action="store_true", help="one line: differences and CPU ratios")
    args = parser.parse_args()
    ours, ref, spec = (json.load(open(p)) for p in (args.waam, args.fenicsx, args.problem))
    ambient = spec["ambient_c"]
    if args.brief:
        brief(ours, ref, ambient)
        return
    worst = 0.0
    print(f"{'probe':14s} {'peak_waam_c':>11s} {'peak_fenicsx_c':>14s} {'max_diff_k':>10s} {'of_rise_%':>9s}")
    for name, history in ref["probes_c"].items():
        r = np.asarray(history)
        w = np.interp(np.asarray(ref["time_s"]), np.asarray(ours["time_s"]), np.asarray(ours["probes_c"][name]))
        rise = r.max() - ambient
        diff = np.abs(w - r).max()
        worst = max(worst, diff / rise)
        print(f"{name:14s} {w.max():11.2f} {r.max():14.2f} {diff:10.2f} {100 * diff / rise:9.2f}")
    print(f"worst difference {100 * worst:.2f} % of the peak rise (target 2 %: {'met' if worst <= 0.02 else 'NOT met'})")
    print(f"waam: {ours['cells']} cells, {ours.get('stepping', 'single-rate')}, {ours['steps']} micro steps, "
          f"{ours['iterations']} CG "
          f"iterations; fenicsx: {ref['dofs']} dofs (Q{ref['degree']}, {ref['mass']} mass, CG + {ref['pc']}, "
          f"rtol {ref['rtol']:g}), {ref['steps']} steps, {ref['iterations']} CG iterations")
    print(f"{'seconds':8s} {'waam_cpu':>9s} {'fenicsx_cpu':>11s} {'ratio':>6s} {'waam_wall':>9s} {'fenicsx_wall':>12s} "
          f"{'ratio':>6s}")
    for row, a, b, c, d in (
            ("run", ours["cpu_s"], ref["cpu_s"], ours["wall_s"], ref["wall_s"]),
            ("stepping", ours["cpu_s"] - ours["setup_cpu_s"], ref["cpu_s"] - ref["setup_cpu_s"],
             ours["wall_s"] - ours["setup_s"], ref["wall_s"] - ref["setup_s"])):
        print(f"{row:8s} {a:9.3f} {b:11.3f} {b / a:5.1f}x {c:9.3f} {d:12.3f} {d / c:5.1f}x")
    finer = [json.load(open(p)) for p in args.against]
    if finer:
        h = spec["cell_mm"]
        print("against finer runs (largest difference over the run, % of the finer run's peak rise, at time s):")
        for f in finer:
            print(f"{'probe':14s} " + " ".join(f"{label(a, h) + ' - ' + label(f, h):>24s}" for a in (ours, ref)))
            for name in ref["probes_c"]:
                rise = max(f["probes_c"][name]) - ambient
                cells = []
                for a in (ours, ref):
                    d, t = largest_difference(a, f, name)
                    cells.append(f"{100 * d / rise:+7.2f} % at {t:5.1f} s")
                print(f"{name:14s} " + " ".join(f"{c:>24s}" for c in cells))


if __name__ == "__main__":
    main()
