"""The thermal replay and fit from Python: a log made by the model itself (two layers of a 40 mm wall, two
thermocouples) is replayed, fitted on its first minute and replayed again with the fit, as `waam thermal replay` and
`waam fit thermal` do."""
import json

import numpy as np
import pytest

import waam_twin as wt


def wall_log(path, probes=None):
    """Writes a log of two 40 mm layers at 8 mm/s and 2 kW, 20 s apart, then 90 s of cooling, one row a second:
    time, power_w, arc_on, x, y, z (the bead's top) and T1, T2 (`probes`, degC per row; 0 without)."""
    rows = []
    t = 0
    for layer in range(2):
        for k in range(6):  # 5 s of weld: x from -20 to +20 mm and back on the second layer
            x = -20.0 + 8.0 * k if layer == 0 else 20.0 - 8.0 * k
            rows.append((t, 2000.0 if k < 5 else 0.0, 1 if k < 5 else 0, x, 0.0, 2.0 * (layer + 1)))
            t += 1
        for _ in range(19 if layer == 0 else 90):
            rows.append((t, 0.0, 0, rows[-1][3], 0.0, 2.0 * (layer + 1)))
            t += 1
    with open(path, "w") as f:
        f.write("time,power_w,arc_on,x,y,z,T1,T2\n")
        for i, r in enumerate(rows):
            t1, t2 = (probes["near"][i], probes["far"][i]) if probes else (0.0, 0.0)
            f.write(",".join(f"{v:.6g}" for v in r) + f",{t1:.2f},{t2:.2f}\n")
    return len(rows)


SCENARIO = {
    "name": "replay_round_trip",
    "part": {"generator": {"type": "box", "size_mm": [40, 6, 4]}},
    "slicing": {"layer_height_mm": 2},
    "path": {"pattern": "zigzag", "bead_width_mm": 6},
    "process": {"travel_speed_mm_min": 480, "wire_feed_mm_min": 3200,
                "arc": {"power_w": 2000, "efficiency": 0.7}},
    "thermal": {"material": "mild_steel", "substrate": {"size_mm": [70, 30, 6]}, "cell_mm": 2,
                "convection_w_m2k": 25},
    "replay": {"log": "wall.csv", "columns": {"power_w": "power_w"}, "bead": {"width_mm": 6, "height_mm": 2},
               "probes": {"near": {"column": "T1", "at_mm": [0, 7, -1]},
                          "far": {"column": "T2", "at_mm": [25, -10, -4]}}},
}


@pytest.fixture
def round_trip(tmp_path):
    """The scenario at the truth (efficiency 0.7, convection 25) and its log: the model's own temperatures plus
    N(0, 1 degC) noise."""
    rows = wall_log(tmp_path / "wall.csv")
    truth = wt.scenario_from_dict(SCENARIO, base_dir=tmp_path)
    made = wt.replay_thermal(truth)
    assert len(made.time_s) == rows
    noise = np.random.default_rng(7).normal(0.0, 1.0, size=(2, rows))
    wall_log(tmp_path / "wall.csv", {name: np.nan_to_num(made.simulated[name]) + noise[k]
                                     for k, name in enumerate(("near", "far"))})
    return truth


def test_replay_gives_the_histories_and_replay_json(round_trip, tmp_path):
    result = wt.replay_thermal(round_trip, windows=[(0, 60), "60:120"], images=True)
    assert isinstance(result, wt.ReplayResult)
    doc = result.to_dict()
    assert doc["overall"]["rmse_c"] == pytest.approx(1.0, abs=0.15)  # the noise
    assert [w["from_s"] for w in doc["windows"]] == [0, 60]
    assert set(result.files) == {"replay.json", "replay.h5", "probes_replay.png"}
    assert result.time_s.shape == result.measured["near"].shape == result.simulated["far"].shape
    near = result.simulated["near"]
    assert np.nanmax(near) == pytest.approx(doc["probes"]["near"]["peak_simulated_c"])
    assert np.nanmax(result.measured["near"]) == pytest.approx(doc["probes"]["near"]["peak_measured_c"])
    assert np.nanmax(near) > 100.0, "the probe must see the welds"
    result.save(tmp_path / "out")
    assert json.loads((tmp_path / "out" / "replay.json").read_text()) == doc


def test_fit_recovers_the_log_and_its_result_replays(round_trip):
    start = round_trip.with_overrides({"process.arc.efficiency": 0.84, "thermal.convection_w_m2k": 10})
    fit = wt.fit_thermal(start, (0, 60), free=("efficiency", "convection"))
    assert fit.ok, fit.message
    assert fit.model["fitted"]["efficiency"] == pytest.approx(0.7, abs=0.01)
    assert fit.model["fitted"]["convection"] == pytest.approx(25, abs=3)
    assert fit.model["held_out"]["overall"]["rmse_c"] < 1.5
    assert "held out rmse" in fit.summary and "wrote " not in fit.summary
    again = wt.replay_thermal(start, parameters=fit)  # the scenario's start values replaced by the fit
    assert again.to_dict()["parameters"]["efficiency"] == pytest.approx(fit.model["fitted"]["efficiency"])
    assert again.to_dict()["overall"]["rmse_c"] < 1.5


def test_bad_input_raises_input_error(round_trip, tmp_path):
    with pytest.raises(wt.InputError, match="window"):
        wt.fit_thermal(round_trip, (0, 1e6))
    with pytest.raises(wt.InputError, match="window"):
        wt.fit_thermal(round_trip, "later")
    with pytest.raises(wt.InputError, match="jacobian_cell"):
        wt.fit_thermal(round_trip, (0, 60), jacobian_cell="fine")
    (tmp_path / "wall.csv").write_text("time,power_w,arc_on,x,y,z,T1,T2\n0,0,0,0,0,2,20,20\n1,abc,0,0,0,2,20,20\n")
    with pytest.raises(wt.InputError, match="wall.csv:3"):
        wt.replay_thermal(round_trip)
