"""waam-twin from Python: load a scenario, plan it, check it on the robot cell, build it in the voxel twin and run the
thermal model, in memory, with numpy views of the results.

    import waam_twin as wt
    scn = wt.load_scenario("scenarios/planar_demo.yaml", overrides={"path.pattern": "hybrid"})
    plan = wt.plan(scn)            # plan.points: (points x 11), columns wt.PlanResult.columns
    check = wt.check(scn, plan)    # check.ok, check.violations, check.joints (samples x 8, rad)
    part = wt.simulate(scn, plan)  # part.voxels: (voxels x 3) int32
    plan.to_dict()                 # what plan.json holds; plan.save("out/plan") writes the command's files

Errors a user can cause raise wt.InputError (a ValueError) with the command line's one-line message; the code's own
mistakes raise wt.InternalError. Long calls release the GIL, take an optional progress(label, done, total) callback
and stop on Ctrl-C (KeyboardInterrupt); wt.set_threads(n) sets the threads they use.
"""
from ._core import (CheckResult, InputError, InternalError, OutputError, PlanResult, Scenario, SimulateResult,
                    ThermalResult, export_program, import_program, load_scenario, plan, scenario_from_dict,
                    set_threads, threads, data_dir, version)
from . import _core
from ._commands import (CommandResult, FitResult, ReplayResult, compensate, fit, fit_columns, fit_distortion,
                        fit_thermal, place, replay_thermal, run)
from ._sweep import sweep


def check(scenario, plan=None, progress=None):
    """Checks `plan` (planned here when None) on the scenario's cell, as `waam check` does; returns a CheckResult.

    progress: None or a callable progress(label, done, total). Violations are in the result, not exceptions."""
    return _core._check(scenario, plan, progress)


def simulate(scenario, plan=None, progress=None):
    """Deposits `plan` (planned here when None) in the voxel twin and measures the part, as `waam simulate` does;
    returns a SimulateResult (voxels, voxel_mm, to_dict(), save(dir)). Raises InputError past simulation.max_voxels."""
    return _core._simulate(scenario, plan, progress)


def thermal(scenario, plan=None, progress=None):
    """Runs the thermal model along the build's timeline of `plan` (planned here when None), as `waam thermal`
    does; returns a ThermalResult (probes, sample_time_s, field(i), layers, timeline, energy_balance, to_dict(),
    save(dir)). Raises InputError when the scenario has no thermal: section."""
    return _core._thermal(scenario, plan, progress)


def _violations(self):
    """The violations as check.json lists them (a list of dicts)."""
    return self.to_dict()["violations"]


CheckResult.violations = property(_violations)

__all__ = ["InputError", "OutputError", "InternalError", "Scenario", "PlanResult", "CheckResult", "SimulateResult",
           "ThermalResult", "CommandResult", "FitResult", "ReplayResult", "load_scenario", "scenario_from_dict",
           "plan", "check", "simulate", "thermal", "place", "compensate", "run", "fit", "fit_columns",
           "fit_distortion", "fit_thermal", "replay_thermal", "import_program", "export_program", "sweep",
           "set_threads", "threads", "data_dir", "version"]
