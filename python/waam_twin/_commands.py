"""The commands that write files (place, compensate, run, the fits, the thermal replay): each runs in a temporary
folder, and its outputs come back in memory as a CommandResult (to_dict(): the command's JSON; save(dir): the files
it wrote)."""
import copy
import json
import os
import pathlib
import tempfile

import numpy as np

from . import _core

_SKIP = {".input", ".waam.lock"}


class CommandResult:
    """The outputs of a command: `to_dict()` is its JSON document (e.g. place.json), `files` maps each output's
    path relative to the output folder to its bytes, and `save(dir)` writes them there (the JSON last)."""

    def __init__(self, command, summary, folder, document=None):
        folder = pathlib.Path(folder)
        self.command = command
        self.summary = summary
        self.files = {}
        for path in sorted(folder.rglob("*")):
            relative = path.relative_to(folder)
            if path.is_file() and not (set(relative.parts) & _SKIP):
                self.files[str(relative)] = path.read_bytes()
        self._document = document if document is not None else json.loads(self.files[summary])

    def to_dict(self):
        """The command's JSON document (a copy)."""
        return copy.deepcopy(self._document)

    def save(self, dir):
        """Writes the command's files into `dir` (created if missing), the JSON document last."""
        dir = pathlib.Path(dir)
        for name in sorted(self.files, key=lambda n: n == self.summary):
            target = dir / name
            target.parent.mkdir(parents=True, exist_ok=True)
            tmp = target.with_name(target.name + ".tmp")
            tmp.write_bytes(self.files[name])
            os.replace(tmp, target)

    def __repr__(self):
        return f"<waam_twin.CommandResult {self.command}: {len(self.files)} files>"


def place(scenario, images=False, progress=None):
    """Searches the cell layout of the scenario's place: ranges, as `waam place` does. Returns a CommandResult:
    to_dict() is place.json (feasible, best layout, its overrides, every layout tried); files hold scenario.yaml
    (the scenario laid out) and place_margin.png with images."""
    with tempfile.TemporaryDirectory(prefix="waam_place_") as tmp:
        _core._place(scenario, tmp, images, progress)
        return CommandResult("place", "place.json", tmp)


def compensate(scenario, max_iterations=3, tolerance_mm=0.0, correction="axis", model=None, images=False,
               progress=None):
    """Runs the offline compensation loop against the twin, as `waam compensate` does (model: a distortion model
    JSON, None = models/data/distortion.json; images: the pictures and the compensated program too). Returns a
    CommandResult with to_dict() = compensate.json, the scans (scan_before.ply, scan_after.ply) and the compensated
    path in `files`, and `status` ({converged, status, message}); non-convergence is a status, not an exception."""
    with tempfile.TemporaryDirectory(prefix="waam_compensate_") as tmp:
        status = _core._compensate(scenario, tmp, max_iterations, tolerance_mm, correction,
                                   "" if model is None else model, images, progress)
        result = CommandResult("compensate", "compensate.json", tmp)
    result.status = status
    return result


def run(scenario, steps=None, images=False, progress=None):
    """Runs the scenario's steps end to end, as `waam run` does (steps: a list such as ["plan", "check",
    "simulate", "thermal"]; None = the scenario's run.steps or the default chain). Returns a CommandResult with
    to_dict() = summary.json and every step's files under '<step>/'."""
    with tempfile.TemporaryDirectory(prefix="waam_run_") as tmp:
        summary = _core._run(scenario, tmp, list(steps or []), images, progress)
        return CommandResult("run", "summary.json", tmp, document=summary)


class FitResult:
    """A fitted model: `ok` (the solver's answer is usable), `message` (why not), `model` (the model JSON, as
    `waam fit` writes it), `summary` (what `waam fit` prints). to_dict() is the model; save(path) writes it."""

    def __init__(self, ok, message, model, summary):
        # The command's last line names the temporary file it wrote: save(path) writes the model where asked.
        summary = "".join(line for line in summary.splitlines(keepends=True) if not line.startswith("wrote "))
        self.ok, self.message, self.model, self.summary = ok, message, model, summary

    def to_dict(self):
        """The model JSON (a copy)."""
        return copy.deepcopy(self.model)

    def save(self, path):
        """Writes the model JSON to `path` (raises InputError when the fit is not usable)."""
        if not self.ok:
            raise _core.InputError(f"fit: not usable, nothing to save: {self.message}")
        path = pathlib.Path(path)
        tmp = path.with_name(path.name + ".tmp")
        tmp.write_text(json.dumps(self.model, indent=2) + "\n")
        os.replace(tmp, path)

    def __repr__(self):
        return f"<waam_twin.FitResult ok={self.ok}>"


def _table_columns(table, model):
    """The table as {column name: 1-D float array}: a pandas DataFrame, a dict of columns, or a 2-D numpy array
    whose columns are the model's default columns in their order (wt.fit_columns(model))."""
    if hasattr(table, "to_dict") and hasattr(table, "columns"):  # a pandas DataFrame
        table = {str(c): table[c].to_numpy() for c in table.columns}
    if isinstance(table, dict):
        columns = {}
        for name, values in table.items():
            if not isinstance(name, str) or not name or any(ch in name for ch in ",\n\"#"):
                raise _core.InputError(f"table: column name {name!r} must be a non-empty string without , \" # or "
                                       "newline")
            array = np.asarray(values, dtype=float)
            if array.ndim != 1:
                raise _core.InputError(f"table: column '{name}' has shape {array.shape}, expected one value a row")
            columns[name] = array
    else:
        array = np.asarray(table, dtype=float)
        names = [column for _, column in _core._fit_columns(model)]
        if array.ndim != 2 or array.shape[1] != len(names):
            raise _core.InputError(f"table: an array of shape {array.shape}, expected (rows x {len(names)}) with "
                                   f"the columns {', '.join(names)}")
        columns = {name: array[:, i] for i, name in enumerate(names)}
    lengths = {len(v) for v in columns.values()}
    if len(lengths) > 1:
        raise _core.InputError(f"table: columns of different lengths {sorted(lengths)}")
    return columns


def _write_csv(columns, path):
    names = list(columns)
    rows = zip(*(columns[n] for n in names))
    with open(path, "w") as f:
        f.write("# Source: a table given to waam_twin.fit from Python\n")
        f.write(",".join(names) + "\n")
        for row in rows:
            f.write(",".join(repr(float(x)) for x in row) + "\n")


def fit(model, table, columns=None, progress=None, **options):
    """Fits a process model (csw, speed-height, width-height) to a table, as `waam fit` does: a pandas DataFrame,
    a dict of columns or a 2-D numpy array (its columns: wt.fit_columns(model), in order). columns maps roles to
    column names ({"speed": "v"}); options: degree, space, speed_range, seed. Returns a FitResult. Raises
    InputError for a bad table (naming the column and row)."""
    if model in ("distortion", "void-length"):
        raise _core.InputError(f"fit: model '{model}': use fit_distortion for a scan; void-length reads its CSV "
                               "with `waam fit`")
    data = _table_columns(table, model)
    with tempfile.TemporaryDirectory(prefix="waam_fit_") as tmp:
        csv = pathlib.Path(tmp) / "table.csv"
        _write_csv(data, csv)
        roles = [f"{role}={name}" for role, name in (columns or {}).items()]
        ok, message, result, printed = _core._fit(model, csv, pathlib.Path(tmp) / "model.json", roles, options,
                                                  progress)
    return FitResult(ok, message, result, printed)


def fit_distortion(scan_points, scenario, progress=None, **options):
    """Fits the distortion model to a scan of a part built from `scenario`, as `waam fit distortion` does:
    scan_points is an (N x 3) array of points in the part frame, mm. options: start (a distortion model JSON to
    start from), free (the parameters fitted), max_points, max_iterations, mode. Returns a FitResult."""
    points = np.asarray(scan_points, dtype=float)
    if points.ndim != 2 or points.shape[1] != 3 or len(points) == 0:
        raise _core.InputError(f"scan_points: an array of shape {points.shape}, expected (N x 3) points in mm")
    if not np.all(np.isfinite(points)):
        raise _core.InputError("scan_points: every coordinate must be finite")
    with tempfile.TemporaryDirectory(prefix="waam_fit_") as tmp:
        scan = pathlib.Path(tmp) / "scan.xyz"
        np.savetxt(scan, points, fmt="%.17g")
        file, overrides = _core._scenario_file(scenario, pathlib.Path(tmp) / ".input")
        options = dict(options, scenario=file, overrides=overrides)
        ok, message, result, printed = _core._fit("distortion", scan, pathlib.Path(tmp) / "model.json", [],
                                                  options, progress)
    return FitResult(ok, message, result, printed)


def _window_text(window, name):
    """A window as "A:B" (s from the log's first row) from a string or an (A, B) pair."""
    if isinstance(window, str):
        return window
    try:
        start, end = window
        return f"{float(start)!r}:{float(end)!r}"
    except (TypeError, ValueError):
        raise _core.InputError(f"{name}: {window!r}: expected (start_s, end_s) or 'A:B'") from None


def _fitted_file(fitted, tmp, name):
    """A fitted file's path: `fitted` itself (a path), or a FitResult or dict written into tmp."""
    if fitted is None:
        return ""
    if isinstance(fitted, FitResult):
        fitted = fitted.model
    if isinstance(fitted, dict):
        path = pathlib.Path(tmp) / f"{name}.json"
        path.write_text(json.dumps(fitted))
        return path
    return pathlib.Path(fitted)


class ReplayResult(CommandResult):
    """A replayed process log: a CommandResult (to_dict() is replay.json; files replay.h5 and, with images,
    probes_replay.png) with the histories as numpy arrays: `time_s` (s from the log's first row), `measured` and
    `simulated` ({probe: degC per row}, NaN where the log has no reading or no metal is yet)."""

    def __init__(self, folder, histories):
        super().__init__("thermal replay", "replay.json", folder)
        self.time_s = np.asarray(histories["time_s"], dtype=float)
        self.measured = {k: np.asarray(v, dtype=float) for k, v in histories["measured"].items()}
        self.simulated = {k: np.asarray(v, dtype=float) for k, v in histories["simulated"].items()}

    def __repr__(self):
        return f"<waam_twin.ReplayResult {len(self.time_s)} rows, {len(self.measured)} probes>"


def replay_thermal(scenario, windows=None, parameters=None, images=False, progress=None):
    """Replays the scenario's process log (its replay: section) through the thermal model and compares every
    thermocouple, as `waam thermal replay` does. windows: (start_s, end_s) pairs (or "A:B,C:D") reported under
    replay.json's windows[]; parameters: a fitted file (path), or a FitResult or dict from fit_thermal, whose
    parameters replace the scenario's. Returns a ReplayResult. Raises InputError for a bad scenario or log (naming
    the file and the row or key)."""
    if windows is None:
        text = ""
    elif isinstance(windows, str):
        text = windows
    else:
        text = ",".join(_window_text(w, "windows") for w in windows)
    with tempfile.TemporaryDirectory(prefix="waam_replay_") as tmp:
        out = pathlib.Path(tmp) / "out"
        fitted = _fitted_file(parameters, tmp, "parameters")
        histories = _core._replay_thermal(scenario, out, text, fitted, images, progress)
        return ReplayResult(out, histories)


def fit_thermal(scenario, window, free=("efficiency", "convection", "contact"), start=None, progress=None,
                **options):
    """Fits the thermal model to the scenario's process log inside `window` ((start_s, end_s) or "A:B", s from the
    log's first row) and predicts the rest, as `waam fit thermal` does. free: any of efficiency, convection,
    contact, emissivity, clamps; start: a fitted file (path, FitResult or dict) to start from; options:
    max_iterations, coarse_cell (mm), jacobian_cell ("auto", the default, 0 or mm), prior (degC). Returns a
    FitResult whose model is fitted.json (parameters, fitted, window, held_out, solver, identifiability) and whose
    summary is what the command prints; a fit that did not converge has ok False and its reason in message. Pass
    the result to replay_thermal(parameters=...) to replay with it."""
    with tempfile.TemporaryDirectory(prefix="waam_fit_") as tmp:
        file, overrides = _core._scenario_file(scenario, pathlib.Path(tmp) / ".input")
        options = dict(options, overrides=overrides, free=list(free), window=_window_text(window, "window"))
        fitted = _fitted_file(start, tmp, "start")
        if fitted:
            options["start"] = fitted
        ok, message, result, printed = _core._fit("thermal", file, pathlib.Path(tmp) / "fitted.json", [], options,
                                                  progress)
    return FitResult(ok, message, result, printed)


def fit_columns(model):
    """The roles of a model's table and their default column names, as (role, column) pairs."""
    return _core._fit_columns(model)
