"""run, place, the fits and the programs from Python, against the command line's outputs."""
import json

import numpy as np
import pytest

import waam_twin as wt
from conftest import SOURCE_DIR, files_under, run_cli


def test_run_is_the_command_line_run(tiny, tmp_path):
    run_cli("run", tiny, "-o", tmp_path / "cli", "-q", "--steps", "plan,check", "--no-images")
    result = wt.run(wt.load_scenario(tiny), steps=["plan", "check"])
    cli = json.loads((tmp_path / "cli" / "summary.json").read_text())
    doc = result.to_dict()
    assert doc.pop("timing") and cli.pop("timing"), "timings only under timing"
    assert doc == cli
    result.save(tmp_path / "py")
    assert files_under(tmp_path / "py") == files_under(tmp_path / "cli")
    with pytest.raises(wt.InputError, match="nonsense"):
        wt.run(wt.load_scenario(tiny), steps=["nonsense"])


def test_place_from_a_dict_scenario(tiny, scenarios, tmp_path):
    scn = wt.load_scenario(scenarios / "cell" / "cell_ok.yaml",
                           overrides={"place": {"part_yaw_deg": [0, 90, 90]}})
    result = wt.place(scn)
    doc = result.to_dict()
    assert "feasible" in doc and "scenario.yaml" in result.files
    result.save(tmp_path / "placed")
    assert json.loads((tmp_path / "placed" / "place.json").read_text()) == doc


def test_fit_csw_from_array_dict_and_dataframe(tmp_path):
    pandas = pytest.importorskip("pandas")
    table = SOURCE_DIR / "models" / "data" / "dai2020_csw_table1.csv"
    frame = pandas.read_csv(table, comment="#")
    run_cli("fit", "csw", table, "-o", tmp_path / "cli.json")
    cli = json.loads((tmp_path / "cli.json").read_text())
    from_frame = wt.fit("csw", frame)
    assert from_frame.ok, from_frame.message
    names = [c for _, c in wt.fit_columns("csw")]
    from_array = wt.fit("csw", frame[names].to_numpy())
    from_dict = wt.fit("csw", {c: frame[c].to_list() for c in frame.columns})
    for result in (from_frame, from_array, from_dict):
        assert result.model["params"] == pytest.approx(cli["params"], rel=1e-9)
    from_frame.save(tmp_path / "py.json")
    assert json.loads((tmp_path / "py.json").read_text())["params"] == from_frame.model["params"]
    with pytest.raises(wt.InputError, match=r"expected \(rows x 3\)"):
        wt.fit("csw", np.zeros((4, 2)))
    with pytest.raises(wt.InputError, match="width_mm"):
        wt.fit("csw", frame.drop(columns=["width_mm"]))
    renamed = frame.rename(columns={"travel_speed_mm_per_min": "v"})
    assert wt.fit("csw", renamed, columns={"speed": "v"}).ok


def test_export_then_import_the_program(tiny, tmp_path):
    scn = wt.load_scenario(tiny)
    plan = wt.plan(scn)
    exported = wt.export_program(scn, plan, format="csv")
    assert exported["format"] == "csv" and exported["points"] > 0
    path = tmp_path / "tiny.csv"
    path.write_text(exported["files"][""])
    run_cli("export", tiny, "-o", tmp_path / "cli.csv", "-q")  # by extension
    assert (tmp_path / "cli.csv").read_text() == exported["files"][""]
    imported = wt.import_program(path, scn)
    assert imported.to_dict()["import"]["file"] == str(path)
    assert imported.layer_count == plan.layer_count
    weld = plan.points[plan.points[:, 9] == 1]
    back = imported.points[imported.points[:, 9] == 1]
    assert np.allclose(back[[0, -1], :3], weld[[0, -1], :3], atol=1e-3), "the program reaches the plan's points"
    with pytest.raises(wt.InputError, match="unknown program format"):
        wt.export_program(scn, plan, format="punched_cards")


def read_scan_ply(data):
    """The points of the twin's binary scan PLY (x, y, z, deviation_mm as float32)."""
    header, body = data.split(b"end_header\n", 1)
    count = int(header.split(b"element vertex ")[1].split(b"\n")[0])
    return np.frombuffer(body, dtype="<f4", count=4 * count).reshape(count, 4)[:, :3].astype(float)


def test_compensate_scan_then_fit_distortion(scenarios, tmp_path):
    """The twin's scan of a distorted tube (compensate with no iteration) fitted back from a perturbed start."""
    scn = wt.load_scenario(scenarios / "distortion" / "small_bent_tube.yaml")
    truth = SOURCE_DIR / "models" / "data" / "distortion_part1_demo.json"
    twin = wt.compensate(scn, max_iterations=0, tolerance_mm=1.0, model=truth)
    assert twin.status["status"] in ("max_iterations", "converged") and "scan_before.ply" in twin.files
    assert twin.to_dict()["correction"] == "axis"
    points = read_scan_ply(twin.files["scan_before.ply"])
    start = json.loads(truth.read_text())
    start["params"]["strain"] *= 0.5
    (tmp_path / "start.json").write_text(json.dumps(start))
    fitted = wt.fit_distortion(points, scn, start=tmp_path / "start.json", max_points=300)
    assert fitted.ok, fitted.message
    assert fitted.model["fit"]["scenario"] == "small_bent_tube"
    assert fitted.model["params"]["strain"] == pytest.approx(0.03, rel=0.05), "the known strain recovered"
    with pytest.raises(wt.InputError, match=r"expected \(N x 3\)"):
        wt.fit_distortion(points[:, :2], scn)
