"""waam_twin from Python: the same checks and messages as the command line, numpy views that keep their owner
alive, the same results on any thread count, and a run whose JSON equals the command line's."""
import gc
import json
import random
import subprocess

import numpy as np
import pytest

import waam_twin as wt
from conftest import SOURCE_DIR, WAAM_BINARY


def test_load_scenario_applies_overrides(tiny):
    scn = wt.load_scenario(tiny, overrides={"path.pattern": "zigzag", "path.bead_width_mm": 5})
    assert scn.name == "tiny"
    plan = wt.plan(scn)
    default = wt.plan(wt.load_scenario(tiny))
    assert plan.points[:, 6].max() == pytest.approx(5.0), "bead_width_mm column follows the override"
    assert default.points[:, 6].max() == pytest.approx(6.0)


def test_bad_input_is_input_error_with_the_cli_message(tiny):
    with pytest.raises(wt.InputError) as e:
        wt.load_scenario(tiny, overrides={"slicing.layer_height_mm": -1})
    assert isinstance(e.value, ValueError)
    assert "slicing.layer_height_mm = -1: must be in [0.05, 20]" in str(e.value)
    with pytest.raises(wt.InputError, match="path.nonsense"):
        wt.load_scenario(tiny, overrides={"path.nonsense": 3})
    with pytest.raises(wt.InputError, match="overrides"):
        wt.load_scenario(tiny, overrides=["path.pattern=zigzag"])
    with pytest.raises(wt.InputError, match="not found"):
        wt.load_scenario(tiny.parent / "nothere.yaml")


def test_plan_points_are_views_that_outlive_their_result(tiny):
    plan = wt.plan(wt.load_scenario(tiny))
    points = plan.points
    assert points.dtype == np.float64 and points.shape[1] == len(wt.PlanResult.columns) == 11
    assert points.base is not None and not points.flags.writeable, "a read-only view, not a copy"
    layers = [plan.layer_points(i) for i in range(plan.layer_count)]
    assert sum(len(l) for l in layers) == len(points)
    assert np.array_equal(np.vstack(layers), points)
    assert np.all(layers[1][:, 10] == 1), "the layer column of layer 1"
    expected = points.copy()
    del plan
    gc.collect()
    assert np.array_equal(points, expected), "the view keeps its plan alive"
    with pytest.raises(wt.InputError, match="layer 99"):
        wt.plan(wt.load_scenario(tiny)).layer_points(99)


def test_check_reports_ok_and_joints(scenarios):
    scn = wt.load_scenario(scenarios / "cell" / "cell_ok.yaml")
    check = wt.check(scn)
    assert check.ok and check.violations == []
    doc = check.to_dict()
    assert check.joints.shape == (doc["samples"], 8)
    assert check.joints.base is not None
    bad = wt.check(wt.load_scenario(scenarios / "cell" / "cell_out_of_reach.yaml"))
    assert not bad.ok
    assert {v["kind"] for v in bad.violations} == {"unreachable"}


def test_simulate_gives_voxels_as_in_part_h5(tiny):
    scn = wt.load_scenario(tiny)
    part = wt.simulate(scn, wt.plan(scn))
    voxels = part.voxels
    assert voxels.dtype == np.int32 and voxels.shape[1] == 3 and len(voxels) > 0
    assert part.voxel_mm == pytest.approx(1.0)
    # Deposited volume: the voxels times their volume, as simulate.json counts it.
    doc = part.to_dict()
    assert json.dumps(doc)  # plain JSON types
    assert voxels[:, 2].min() >= 0, "metal lies on the plate (z >= 0)"


def test_same_results_on_one_and_two_threads(tiny):
    scn = wt.load_scenario(tiny)
    wt.set_threads(1)
    one = wt.plan(scn).points.copy()
    wt.set_threads(2)
    two = wt.plan(scn).points.copy()
    wt.set_threads(0)
    assert np.array_equal(one, two)


def test_plan_json_equals_the_command_line(tiny, tmp_path):
    out = tmp_path / "cli"
    subprocess.run([WAAM_BINARY, "plan", str(tiny), "-o", str(out), "-q", "--no-images"], check=True)
    cli = json.loads((out / "plan.json").read_text())
    plan = wt.plan(wt.load_scenario(tiny))
    assert plan.to_dict() == cli
    timeline = plan.timeline
    assert timeline == cli["timeline"]
    assert timeline["total_s"] == pytest.approx(timeline["arc_on_s"] + timeline["travel_s"] + timeline["wait_s"])


def test_random_overrides_never_crash(tiny):
    """Fuzz the dict-to-scenario path: any dict either loads or raises InputError, never anything else."""
    rng = random.Random(7)
    keys = ["path.pattern", "path.bead_width_mm", "slicing.layer_height_mm", "process.wire_feed_mm_min",
            "simulation.voxel_mm", "cell.robot.base_mm", "part.generator.size_mm", "nope", "path", "", "a..b"]
    values = [None, True, -1, 0, 1.5, 1e308, float("nan"), "zigzag", "", "[1, 2", [1, 2, 3], {"x": 1}, [[]], "\x00"]
    for _ in range(200):
        overrides = {rng.choice(keys): rng.choice(values) for _ in range(rng.randint(1, 3))}
        try:
            wt.load_scenario(tiny, overrides=overrides)
        except wt.InputError:
            pass
