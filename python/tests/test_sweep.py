"""sweep: one row per grid point in grid order, the same rows in this process, on a process pool and on a dask
executor, and refused runs as rows with their error."""
import concurrent.futures
import multiprocessing

import pytest

import waam_twin as wt

GRID = {"path.bead_width_mm": [5, 6], "path.pattern": ["contour", "zigzag"]}


def test_sweep_rows_in_grid_order(tiny):
    seen = []
    rows = wt.sweep(wt.load_scenario(tiny), GRID, steps=["plan", "check"], progress=lambda *a: seen.append(a))
    assert [(r["path.bead_width_mm"], r["path.pattern"]) for r in rows] == [
        (5, "contour"), (5, "zigzag"), (6, "contour"), (6, "zigzag")]
    assert all(r["error"] is None for r in rows)
    assert [r["plan.bead_width_mm"] for r in rows] == pytest.approx([5, 5, 6, 6])
    assert seen[-1] == ("sweep", 4, 4)
    assert all("check.ok" in r and "plan.timeline.total_s" in r for r in rows)


def test_sweep_is_the_same_on_a_process_pool(tiny):
    here = wt.sweep(tiny, GRID, steps=["plan", "simulate"])
    with concurrent.futures.ProcessPoolExecutor(2, mp_context=multiprocessing.get_context("spawn")) as pool:
        there = wt.sweep(tiny, GRID, executor=pool, steps=["plan", "simulate"])
    assert there == here


def test_sweep_on_a_dask_executor(tiny_thermal):
    distributed = pytest.importorskip("distributed")
    here = wt.sweep(tiny_thermal, {"path.bead_width_mm": [5, 6]}, steps=["plan"])
    with distributed.Client(processes=False, n_workers=1, threads_per_worker=2, dashboard_address=None) as client:
        there = wt.sweep(tiny_thermal, {"path.bead_width_mm": [5, 6]}, executor=client.get_executor(),
                         steps=["plan"])
    assert there == here


def test_refused_runs_and_bad_grids(tiny):
    rows = wt.sweep(tiny, {"path.bead_width_mm": [6, -1]}, steps=["plan"])
    assert rows[0]["error"] is None
    assert "path.bead_width_mm = -1: must be in" in rows[1]["error"]
    with pytest.raises(wt.InputError, match="path.nonsense"):
        wt.sweep(tiny, {"path.nonsense": [1]})
    with pytest.raises(wt.InputError, match="must be a list"):
        wt.sweep(tiny, {"path.bead_width_mm": 5})
    with pytest.raises(wt.InputError, match="unknown step 'weld'"):
        wt.sweep(tiny, GRID, steps=["weld"])
