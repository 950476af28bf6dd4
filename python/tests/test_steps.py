"""thermal, save(dir) of every result against the command line's files and JSON, the progress callback and Ctrl-C."""
import gc
import json
import os
import signal
import threading

import numpy as np
import pytest

import waam_twin as wt
from conftest import SOURCE_DIR, files_under, run_cli


def write_scenario(d, path):
    path.write_text(json.dumps(d))  # JSON is YAML
    return path


def without_timing(doc, *paths):
    for path in paths:
        node = doc
        for key in path[:-1]:
            node = node[key]
        node.pop(path[-1], None)
    return doc


def test_thermal_views_and_balance(tiny_thermal, tiny):
    th = wt.thermal(wt.scenario_from_dict(tiny_thermal))
    times = th.sample_time_s
    assert times.ndim == 1 and np.all(np.diff(times) > 0) and not times.flags.writeable
    assert set(th.probes) == {"plate", "wall"}
    plate = th.probes["plate"]
    assert plate.shape == times.shape and plate.base is not None
    assert np.nanmax(plate) == pytest.approx(th.to_dict()["probes"]["plate"]["max_c"])
    balance = th.energy_balance
    assert balance["heat_input_j"] == pytest.approx(balance["stored_j"] + balance["lost_j"], rel=1e-9)
    assert len(th.layers) == 2 and th.timeline["total_s"] == pytest.approx(th.to_dict()["build_time_s"])
    field = th.field(th.field_count - 1)
    t = field["temperature_c"]
    assert t.dtype == np.float32 and t.ndim == 3 and np.nanmax(t) > tiny_thermal["thermal"].get("ambient_c", 20)
    del th
    gc.collect()
    assert np.isfinite(plate[-1]) and np.isfinite(np.nanmax(t)), "the views keep their result alive"
    with pytest.raises(wt.InputError, match="no thermal: section"):
        wt.thermal(wt.load_scenario(tiny))


def test_thermal_save_is_the_command_line(tiny_thermal, tmp_path):
    yaml = write_scenario(tiny_thermal, tmp_path / "s.yaml")
    run_cli("thermal", yaml, "-o", tmp_path / "cli", "-q")
    th = wt.thermal(wt.load_scenario(yaml))
    th.save(tmp_path / "py")
    assert files_under(tmp_path / "py") == files_under(tmp_path / "cli")
    cli = json.loads((tmp_path / "cli" / "thermal.json").read_text())
    saved = json.loads((tmp_path / "py" / "thermal.json").read_text())
    assert without_timing(saved, ("solver", "wall_s")) == without_timing(cli, ("solver", "wall_s"))
    assert without_timing(th.to_dict(), ("solver", "wall_s")) == cli


def test_check_and_simulate_save_are_the_command_line(tiny, tmp_path):
    run_cli("check", tiny, "-o", tmp_path / "cli_check", "-q", "--no-images")
    run_cli("simulate", tiny, "-o", tmp_path / "cli_sim", "-q", "--no-images")
    scn = wt.load_scenario(tiny)
    plan = wt.plan(scn)
    check = wt.check(scn, plan)
    check.save(tmp_path / "py_check", images=False)
    assert files_under(tmp_path / "py_check") == files_under(tmp_path / "cli_check")
    cli_check = json.loads((tmp_path / "cli_check" / "check.json").read_text())
    assert check.to_dict() == cli_check
    assert json.loads((tmp_path / "py_check" / "check.json").read_text()) == cli_check
    part = wt.simulate(scn, plan)
    part.save(tmp_path / "py_sim", images=False)
    assert files_under(tmp_path / "py_sim") == files_under(tmp_path / "cli_sim")
    timing = [("performance",), ("stl_voxel_mm",), ("stl_facets",)]
    cli_sim = json.loads((tmp_path / "cli_sim" / "simulate.json").read_text())
    saved = json.loads((tmp_path / "py_sim" / "simulate.json").read_text())
    assert saved["stl_facets"] == cli_sim["stl_facets"]
    assert without_timing(saved, *timing) == without_timing(cli_sim, *timing)
    assert without_timing(part.to_dict(), ("performance",)) == cli_sim


def test_plan_save_writes_the_command_files(tiny, tmp_path):
    run_cli("plan", tiny, "-o", tmp_path / "cli", "-q")
    plan = wt.plan(wt.load_scenario(tiny))
    plan.save(tmp_path / "py")
    assert files_under(tmp_path / "py") == files_under(tmp_path / "cli")
    assert json.loads((tmp_path / "py" / "plan.json").read_text()) == plan.to_dict()


def test_progress_callback_is_told_and_can_stop(tiny_thermal):
    calls = []
    scn = wt.scenario_from_dict(tiny_thermal)
    wt.thermal(scn, progress=lambda label, done, total: calls.append((label, done, total)))
    labels = {c[0] for c in calls}
    assert {"plan", "thermal"} <= labels, calls
    last = [c for c in calls if c[0] == "thermal"][-1]
    assert last[1] == last[2] > 0, "the finished bar reports done == total"

    def stop(label, done, total):
        raise RuntimeError("stop here")
    with pytest.raises(RuntimeError, match="stop here"):
        wt.thermal(scn, progress=stop)
    with pytest.raises(wt.InputError, match="progress: expected None or a callable"):
        wt.plan(scn, progress=3)
    assert wt.plan(scn).layer_count == 2, "a call after a stopped one runs normally"


def test_ctrl_c_interrupts_a_long_call(tiny_thermal):
    """A SIGINT during a call without a callback raises KeyboardInterrupt long before the call would end."""
    long = dict(tiny_thermal, part={"generator": {"type": "box", "size_mm": [100, 8, 20]}})
    scn = wt.scenario_from_dict(long)
    timer = threading.Timer(0.2, lambda: os.kill(os.getpid(), signal.SIGINT))
    timer.start()
    with pytest.raises(KeyboardInterrupt):
        wt.thermal(scn)
    timer.join()
    assert wt.plan(scn).layer_count == 10


def test_native_step_seconds_times_the_same_computation(tiny):
    """The benchmark aid behind python/benchmarks/overhead.py runs the C++ step alone: one positive time per run,
    the check only with a plan, and the same plan as wt.plan (so the two sides time the same work)."""
    scn = wt.load_scenario(tiny)
    plan = wt.plan(scn)
    seconds = wt._core._native_step_seconds("plan", scn, None, 2)
    assert len(seconds) == 2 and all(s > 0 for s in seconds)
    assert len(wt._core._native_step_seconds("check", scn, plan, 1)) == 1
    with pytest.raises(wt.InputError, match="check with a plan"):
        wt._core._native_step_seconds("check", scn, None, 1)
    with pytest.raises(wt.InputError, match="step 'simulate'"):
        wt._core._native_step_seconds("simulate", scn, plan, 1)
