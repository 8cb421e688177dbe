"""scen: declarative 2D motion-planning scenarios, from Python.

    import scen
    sc = scen.load("scenarios/apartment_disk.scen")
    report = sc.run()
    report["astar"].path          # numpy (N, 2) float64
    sc.validate("astar", my_path) # the validator on a path of your own
    scen.plan(occupancy, (1, 1), (40, 30), connect=4)  # A* on a numpy grid

The manual's chapter is docs/python.md. Bad input raises `scen.ScenError`,
whose `diagnostics` locate each problem (file, line, column, code, help).
"""

from ._scen import PlanResult, Report, Scenario, ScenError, __version__, bench_merge, load, loads, plan

__all__ = [
    "PlanResult",
    "Report",
    "Scenario",
    "ScenError",
    "__version__",
    "bench_merge",
    "load",
    "loads",
    "plan",
]
