"""The cost of calling waam-twin from Python against the command line, on the same scenario and the same outputs.

    PYTHONPATH=build/python /usr/bin/python3 python/benchmarks/overhead.py [scenario] [--repeat N] [--waam build/waam]

For plan and check it times, median of N runs each: the command (`waam plan -q --no-images`, `waam check -q
--no-images`: a new process that loads the scenario, computes and writes its files) and the same in this process
(load_scenario, plan [, check], save(dir, images=False): the same computation and the same files by the same
writers). Then the step alone from Python (wt.plan, wt.check on a loaded scenario) and the cost of getting the
arrays as numpy views (plan.points, check.joints, part.voxels), which does not copy and so does not grow with the
array. Last, what a Python call adds to the same step in C++: the step's C++ computation called directly in this
process (wt._core._native_step_seconds: the plan and its timeline; the cell, the check and check.json's document) against
wt.plan and wt.check, alternated run by run so that both see the same load: the medians, and the median over the
pairs of each pair's ratio. Prints Markdown
tables (docs/PYTHON.md)."""
import argparse
import pathlib
import statistics
import subprocess
import tempfile
import time

import waam_twin as wt

ROOT = pathlib.Path(__file__).resolve().parents[2]


def median_s(fn, repeat):
    times = []
    for _ in range(repeat):
        start = time.perf_counter()
        fn()
        times.append(time.perf_counter() - start)
    return statistics.median(times)


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("scenario", nargs="?", default=str(ROOT / "scenarios" / "planar_demo.yaml"))
    parser.add_argument("--repeat", type=int, default=5)
    parser.add_argument("--waam", default=str(ROOT / "build" / "waam"))
    args = parser.parse_args()
    tmp = pathlib.Path(tempfile.mkdtemp(prefix="waam_overhead_"))
    rows = []
    for step in ("plan", "check"):
        cli = median_s(lambda: subprocess.run([args.waam, step, args.scenario, "-o", str(tmp / f"cli_{step}"), "-q",
                                               "--no-images"], check=True), args.repeat)

        def in_python():
            scn = wt.load_scenario(args.scenario)
            plan = wt.plan(scn)
            result = plan if step == "plan" else wt.check(scn, plan)
            result.save(tmp / f"py_{step}", images=False)
        py = median_s(in_python, args.repeat)
        rows.append((f"`waam {step}` vs load + {'plan' if step == 'plan' else 'plan + check'} + save", cli, py))
    scn = wt.load_scenario(args.scenario)
    plan = wt.plan(scn)
    step_plan = median_s(lambda: wt.plan(scn), args.repeat)
    step_check = median_s(lambda: wt.check(scn, plan), args.repeat)
    part = wt.simulate(scn, plan)
    check = wt.check(scn, plan)
    views = 1000
    view_s = {name: median_s(lambda: [getattr(obj, attr) for _ in range(views)], 3) / views
              for name, obj, attr in (("plan.points", plan, "points"), ("check.joints", check, "joints"),
                                      ("part.voxels", part, "voxels"))}
    print(f"scenario: {args.scenario} ({len(plan.points)} points, {len(check.joints)} samples, "
          f"{len(part.voxels)} voxels), median of {args.repeat}, threads {wt.threads()}\n")
    print("| what | command line, s | Python, s | Python / command line |")
    print("| --- | --- | --- | --- |")
    for name, cli, py in rows:
        print(f"| {name} | {cli:.3f} | {py:.3f} | {py / cli:.3f} |")
    print(f"\nstep alone from Python: wt.plan {step_plan:.3f} s, wt.check {step_check:.3f} s\n")
    print("| view | rows | per call, us |")
    print("| --- | --- | --- |")
    for name, seconds in view_s.items():
        rows_of = {"plan.points": len(plan.points), "check.joints": len(check.joints), "part.voxels": len(part.voxels)}
        print(f"| `{name}` | {rows_of[name]} | {seconds * 1e6:.2f} |")
    print_step_overhead(scn, plan, args.repeat)


def print_step_overhead(scn, plan, repeat):
    """Alternates the C++ step and the Python call `repeat` times each and prints their medians and the median of
    the pairs' ratios: wall time (the C++ side timed inside C++) and this process's CPU time (both timed here, all
    threads counted), which a loaded machine disturbs less."""
    calls = {"plan": lambda: wt.plan(scn), "check": lambda: wt.check(scn, plan)}
    print("\n| step (alternated, median) | C++ step, s | Python call, s | Python / C++ - 1 | C++ CPU, s | Python CPU, s "
          "| CPU: Python / C++ - 1 |")
    print("| --- | --- | --- | --- | --- | --- | --- |")
    for step, call in calls.items():
        wall = {"cpp": [], "py": []}
        cpu = {"cpp": [], "py": []}
        for _ in range(repeat):
            start_cpu = time.process_time()
            wall["cpp"] += wt._core._native_step_seconds(step, scn, plan if step == "check" else None, 1)
            cpu["cpp"].append(time.process_time() - start_cpu)
            start, start_cpu = time.perf_counter(), time.process_time()
            call()
            wall["py"].append(time.perf_counter() - start)
            cpu["py"].append(time.process_time() - start_cpu)
        w = {k: statistics.median(v) for k, v in wall.items()}
        c = {k: statistics.median(v) for k, v in cpu.items()}
        # The median over the pairs of each pair's ratio: a pair runs back to back, so load drift cancels.
        w_ratio = statistics.median(p / n for n, p in zip(wall["cpp"], wall["py"]))
        c_ratio = statistics.median(p / n for n, p in zip(cpu["cpp"], cpu["py"]))
        print(f"| `wt.{step}` | {w['cpp']:.4f} | {w['py']:.4f} | {100 * (w_ratio - 1):+.2f} % "
              f"| {c['cpp']:.4f} | {c['py']:.4f} | {100 * (c_ratio - 1):+.2f} % |")


if __name__ == "__main__":
    main()
