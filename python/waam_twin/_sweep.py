"""Sweeps: one scenario run over a grid of overrides, in this process or on any concurrent.futures.Executor."""
import itertools
import os

from . import _core

# The key numbers of each step, as `waam run` puts them in summary.json (analysis/run_steps.cc), by step.
_METRICS = {
    "plan": ["layers", "passes", "path_elements", "weld_length_mm", "travel_length_mm", "estimated_time_s",
             "bead_width_mm", "bead_height_mm", "layer_height_mm", "travel_speed_mm_min"],
    "check": ["ok", "samples", "violation_count", "min_joint_margin_deg", "max_joint_speed_ratio", "min_j5_deg",
              "max_torch_tilt_deg", "duration_s"],
    "simulate": ["voxels", "deposited_volume_mm3", "expected_volume_mm3", "volume_error_pct", "ra_mm",
                 "waviness_mm", "boundary_lag_mm", "build_time_s"],
    "thermal": ["build_time_s", "total_wait_s", "max_interpass_c", "peak_c", "interpass_wait_s"],
}
_NESTED = {"plan": [("timeline", "total_s")], "simulate": [("deviation", "rms_mm"), ("deviation", "max_mm"),
                                                           ("voids", "count")],
           "thermal": [("energy_balance", "relative_error")]}
STEPS = tuple(_METRICS)


def _scenario_of(base):
    if isinstance(base, _core.Scenario):
        return base
    if isinstance(base, dict):
        return _core.scenario_from_dict(base)
    if isinstance(base, (str, os.PathLike)):
        return _core.load_scenario(base)
    raise _core.InputError(f"sweep: base must be a Scenario, a scenario file or a dict, got {type(base).__name__}")


def _row(document, step):
    row = {f"{step}.{key}": document[key] for key in _METRICS[step] if key in document}
    for outer, inner in _NESTED.get(step, []):
        if isinstance(document.get(outer), dict) and inner in document[outer]:
            row[f"{step}.{outer}.{inner}"] = document[outer][inner]
    return row


def run_one(base, overrides, steps):
    """One run of a sweep: the base scenario with `overrides` through `steps`; returns its row (the overrides, then
    '<step>.<metric>' columns, and 'error' with the InputError's message when the run is refused). Module-level, so
    an executor can pickle it; `base` is a Scenario (picklable), a file or a dict."""
    row = dict(overrides)
    try:
        scn = _scenario_of(base).with_overrides(overrides)
        plan = _core.plan(scn)
        row.update(_row(plan.to_dict(), "plan"))
        if "check" in steps:
            row.update(_row(_core._check(scn, plan, None).to_dict(), "check"))
        if "simulate" in steps:
            row.update(_row(_core._simulate(scn, plan, None).to_dict(), "simulate"))
        if "thermal" in steps and scn.has_thermal:
            row.update(_row(_core._thermal(scn, plan, None).to_dict(), "thermal"))
        row["error"] = None
    except _core.InputError as e:
        row["error"] = str(e)
    return row


def grid_runs(grid):
    """The overrides of every run of `grid` ({key path: [values]}), the last key varying fastest."""
    if not isinstance(grid, dict) or not grid:
        raise _core.InputError("sweep: grid must be a non-empty dict of key paths to lists of values")
    keys = list(grid)
    values = []
    for key in keys:
        v = grid[key]
        if isinstance(v, (str, bytes)) or not hasattr(v, "__iter__"):
            raise _core.InputError(f"sweep: grid['{key}'] must be a list of values, got {type(v).__name__}")
        v = list(v)
        if not v:
            raise _core.InputError(f"sweep: grid['{key}'] is empty")
        values.append(v)
    return [dict(zip(keys, combo)) for combo in itertools.product(*values)]


def sweep(base, grid, executor=None, steps=("plan", "check", "simulate"), progress=None):
    """Runs the base scenario (a Scenario, a scenario file or a dict) once per point of `grid` ({key path: [values]},
    every combination, the last key fastest) through `steps` (plan always; check, simulate, thermal), and returns
    one dict per run in grid order, ready for pandas.DataFrame: the overrides, '<step>.<metric>' columns and
    'error' (None, or the InputError message of a refused run).

    executor: None runs here, one run after the other; any concurrent.futures.Executor (a ProcessPoolExecutor, a
    dask.distributed Client's get_executor()) runs them there. The rows are the same whatever the executor.
    progress: None or progress("sweep", done, total), called after each run."""
    steps = tuple(steps)
    unknown = [s for s in steps if s not in STEPS]
    if unknown:
        raise _core.InputError(f"sweep: unknown step '{unknown[0]}' (steps: {', '.join(STEPS)})")
    runs = grid_runs(grid)
    scn = _scenario_of(base)
    _core._check_override_keys(runs[0])  # an unknown key is refused once, up front
    if progress is not None and not callable(progress):
        raise _core.InputError("progress: expected None or a callable progress(label, done, total)")
    rows = [None] * len(runs)
    if executor is None:
        for i, overrides in enumerate(runs):
            rows[i] = run_one(scn, overrides, steps)
            if progress is not None:
                progress("sweep", i + 1, len(runs))
        return rows
    import concurrent.futures
    futures = {executor.submit(run_one, scn, overrides, steps): i for i, overrides in enumerate(runs)}
    done = 0
    for future in concurrent.futures.as_completed(futures):
        rows[futures[future]] = future.result()
        done += 1
        if progress is not None:
            progress("sweep", done, len(runs))
    return rows
