"""scenario_from_dict: the same checks and one-line errors as the file loader, relative paths from base_dir, and
pickling (a scenario is loaded again from its source)."""
import json
import pickle
import random

import numpy as np
import pytest

import waam_twin as wt


def test_dict_plans_as_the_file_does(tiny):
    d = {"name": "tiny", "part": {"generator": {"type": "box", "size_mm": [30, 20, 3]}},
         "slicing": {"type": "planar", "layer_height_mm": 1.5}, "path": {"pattern": "contour", "bead_width_mm": 6},
         "process": {"travel_speed_mm_min": 400, "wire_feed_mm_min": 3200}, "simulation": {"voxel_mm": 1.0}}
    from_dict = wt.plan(wt.scenario_from_dict(d))
    from_file = wt.plan(wt.load_scenario(tiny))
    assert np.array_equal(from_dict.points, from_file.points)
    assert from_dict.to_dict() == from_file.to_dict()


def test_dict_errors_name_the_key(tiny_thermal):
    bad = dict(tiny_thermal, path={"pattern": "zigzag", "bead_width_mm": -1})
    with pytest.raises(wt.InputError, match=r"^\./<dict>: path\.bead_width_mm = -1: must be in \[0\.5, 50\]$"):
        wt.scenario_from_dict(bad)
    with pytest.raises(wt.InputError, match="nope: unknown key"):
        wt.scenario_from_dict(dict(tiny_thermal, nope=1))
    with pytest.raises(wt.InputError, match=r"part\.generator\.size_mm\[1\]: a value of type object"):
        wt.scenario_from_dict(dict(tiny_thermal, part={"generator": {"type": "box", "size_mm": [30, object(), 4]}}))
    with pytest.raises(wt.InputError, match="must be finite"):
        wt.scenario_from_dict(dict(tiny_thermal, slicing={"type": "planar", "layer_height_mm": float("nan")}))
    with pytest.raises(wt.InputError, match="expected a dict"):
        wt.scenario_from_dict([1, 2])
    with pytest.raises(wt.InputError, match="base_dir: folder .*nothere not found"):
        wt.scenario_from_dict(tiny_thermal, base_dir="nothere")


def test_relative_mesh_is_taken_from_base_dir(scenarios):
    d = {"name": "bracket", "part": {"mesh": "meshes/l_shape.stl"}, "slicing": {"type": "planar", "layer_height_mm": 2},
         "path": {"pattern": "contour", "bead_width_mm": 6},
         "process": {"travel_speed_mm_min": 400, "wire_feed_mm_min": 3200}}
    assert wt.plan(wt.scenario_from_dict(d, base_dir=scenarios)).layer_count > 0
    with pytest.raises(wt.InputError, match="mesh file .*l_shape.stl not found"):
        wt.scenario_from_dict(d, base_dir=scenarios / "cell")


def test_numpy_values_and_overrides(tiny_thermal):
    tiny_thermal["part"]["generator"]["size_mm"] = np.array([30.0, 8.0, 4.0])
    scn = wt.scenario_from_dict(tiny_thermal, overrides={"path.bead_width_mm": np.float64(5)})
    assert wt.plan(scn).points[:, 6].max() == pytest.approx(5.0)
    assert scn.overrides == ["path.bead_width_mm=5.0"]
    wider = scn.with_overrides({"path.bead_width_mm": 7})
    assert wt.plan(wider).points[:, 6].max() == pytest.approx(7.0)


def test_pickle_loads_the_scenario_again(tiny, tiny_thermal):
    for scn in (wt.load_scenario(tiny, overrides={"path.pattern": "zigzag"}), wt.scenario_from_dict(tiny_thermal)):
        copy = pickle.loads(pickle.dumps(scn))
        assert copy.name == scn.name and copy.overrides == scn.overrides
        assert np.array_equal(wt.plan(copy).points, wt.plan(scn).points)
    assert wt.scenario_from_dict(tiny_thermal).document() == json.loads(json.dumps(tiny_thermal))


def test_random_dicts_never_crash(tiny_thermal):
    """Fuzz the dict-to-scenario path: random edits either load or raise InputError, never anything else."""
    rng = random.Random(11)
    values = [None, True, -1, 0, 2.5, 1e308, float("inf"), "zigzag", "", [1, 2, 3], {"x": 1}, [[]], "\x00", (1,)]
    for _ in range(300):
        d = json.loads(json.dumps(tiny_thermal))
        for _ in range(rng.randint(1, 3)):
            section = rng.choice(list(d))
            if isinstance(d[section], dict) and d[section] and rng.random() < 0.7:
                d[section][rng.choice(list(d[section]) + ["junk"])] = rng.choice(values)
            else:
                d[section] = rng.choice(values)
        try:
            wt.scenario_from_dict(d)
        except wt.InputError:
            pass
