"""waam-twin from Python: load a scenario, plan it, check it on the robot cell and build it in the voxel twin, in
memory, with numpy views of the results.

    import waam_twin as wt
    scn = wt.load_scenario("scenarios/planar_demo.yaml", overrides={"path.pattern": "hybrid"})
    plan = wt.plan(scn)            # plan.points: (points x 11), columns wt.PlanResult.columns
    check = wt.check(scn, plan)    # check.ok, check.violations, check.joints (samples x 8, rad)
    part = wt.simulate(scn, plan)  # part.voxels: (voxels x 3) int32
    plan.to_dict()                 # what plan.json holds

Errors a user can cause raise wt.InputError (a ValueError) with the command line's one-line message; the code's own
mistakes raise wt.InternalError. Long calls release the GIL; wt.set_threads(n) sets the threads they use.
"""
from ._core import (InputError, InternalError, PlanResult, CheckResult, Scenario, SimulateResult, load_scenario,
                    plan, set_threads, simulate, threads)
from ._core import check as _check


def check(scenario, plan=None):
    """Checks `plan` (planned here when None) on the scenario's cell, as `waam check` does; returns a CheckResult."""
    return _check(scenario, plan)


def _violations(self):
    """The violations as check.json lists them (a list of dicts)."""
    return self.to_dict()["violations"]


CheckResult.violations = property(_violations)

__all__ = ["InputError", "InternalError", "Scenario", "PlanResult", "CheckResult", "SimulateResult",
           "load_scenario", "plan", "check", "simulate", "set_threads", "threads"]
