"""The cost of calling waam-twin from Python against the command line, on the same scenario and the same outputs.

    PYTHONPATH=build/python /usr/bin/python3 python/benchmarks/overhead.py [scenario] [--repeat N] [--waam build/waam]

For plan and check it times, median of N runs each: the command (`waam plan -q --no-images`, `waam check -q
--no-images`: a new process that loads the scenario, computes and writes its files) and the same in this process
(load_scenario, plan [, check], save(dir, images=False): the same computation and the same files by the same
writers). Then the step alone from Python (wt.plan, wt.check on a loaded scenario) and the cost of getting the
arrays as numpy views (plan.points, check.joints, part.voxels), which does not copy and so does not grow with the
array. Prints a Markdown table (docs/PYTHON.md)."""
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


if __name__ == "__main__":
    main()
