"""The Python module, as a user has it: `import scen` from the installed
wheel (scripts/wheel.sh --check runs these with the wheel's venv)."""

import contextlib
import json
import math
import os
import subprocess
import threading

import numpy as np
import pytest

import scen

from common import ROOT, SCEN, SCENARIOS, TIMINGS, without_timings


def test_the_module_is_the_installed_wheel_not_the_sources():
    assert "site-packages" in scen.__file__, scen.__file__
    assert scen.__version__.count(".") == 2


WALL = """scenario "a wall"
world {
  bounds (0, 0) (10, 10)
  rect wall (4, 0) (6, 8)
}
robot r point
plan p astar r {
  start (1, 1)
  goal (9, 1)
  cell 0.5
}
expect p.found
"""


def test_load_run_and_the_path_as_numpy():
    sc = scen.load(SCENARIOS / "apartment_disk.scen")
    assert sc.plans, "the scenario has plans"
    report = sc.run()
    assert report.failed == 0 and report.passed >= 1
    for name in sc.plans:
        r = report[name]
        assert r.name == name
        if r.found:
            assert isinstance(r.path, np.ndarray) and r.path.dtype == np.float64
            assert r.path.ndim == 2 and r.path.shape[1] in (2, 3) and len(r.path) >= 2
            assert r.valid and r.collision is None
            # The path's length is the metric of the same name.
            steps = np.diff(r.path[:, :2], axis=0)
            assert math.isclose(np.hypot(steps[:, 0], steps[:, 1]).sum(), r.metrics["length"], rel_tol=1e-9)
    assert all(isinstance(c["passed"], bool) for c in report.checks)
    # Each plan's picture shows that plan alone; the report's shows all.
    first, second = sc.plans[:2]
    whole = report._repr_svg_()
    alone = report[first]._repr_svg_()
    assert f"{first} (" in whole and f"{second} (" in whole
    assert f"{first} (" in alone and f"{second} (" not in alone


def test_loads_reads_text_and_reports_the_name():
    text = WALL
    sc = scen.loads(text, name="tiny.scen")
    assert sc.title == "a wall" and sc.file.endswith("tiny.scen") and sc.plans == ["p"] and sc.planners == [("p", "astar")]
    report = sc.run()
    assert report.passed == 1 and report["p"].found and report["p"].valid
    # It goes round the wall: up past y = 8.
    assert report["p"].path[:, 1].max() >= 8.0
    svg = report._repr_svg_()
    assert svg.startswith("<svg") or svg.startswith("<?xml"), svg[:60]
    assert "<svg" in sc._repr_svg_()


def test_bad_input_raises_scen_error_with_code_and_line():
    text = WALL.replace("  cell 0.5", "  cel 0.5")
    with pytest.raises(scen.ScenError) as info:
        scen.loads(text, name="bad.scen")
    diags = info.value.diagnostics
    assert diags, "the error carries its diagnostics"
    first = diags[0]
    assert first["severity"] == "error"
    assert first["code"].startswith("scen::")
    assert first["line"] == 10 and first["file"].endswith("bad.scen")
    assert "bad.scen" in str(info.value) and first["code"] in str(info.value)


def test_a_missing_file_and_an_unknown_plan_raise_scen_error():
    with pytest.raises(scen.ScenError) as info:
        scen.load(ROOT / "no-such-file.scen")
    assert info.value.diagnostics[0]["code"].startswith("scen::")
    sc = scen.load(SCENARIOS / "apartment_disk.scen")
    with pytest.raises(scen.ScenError) as info:
        sc.run(["no_such_plan"])
    assert info.value.diagnostics[0]["code"] == "scen::python::no_plan"
    assert "no_such_plan" in str(info.value)


def test_validate_accepts_the_planners_path_and_locates_a_collision():
    text = WALL
    sc = scen.loads(text, name="wall.scen")
    planned = sc.run()["p"].path
    ok = sc.validate("p", planned)
    assert ok["p"].valid and ok["p"].collision is None
    assert math.isclose(ok["p"].metrics["length"], sc.run()["p"].metrics["length"], rel_tol=1e-12)
    through = np.array([[1.0, 1.0], [9.0, 1.0]])
    bad = sc.validate("p", through)
    r = bad["p"]
    assert not r.valid
    assert r.collision["segment"] == 0 and r.collision["obstacle"] == "wall"
    assert "wall" in r.collision["reason"]
    # The pose of the failing sub-step: on the segment (a translation of a
    # point robot is one sub-step, so its end).
    x, y, _ = r.collision["at"]
    assert 4.0 <= x <= 9.0 and y == pytest.approx(1.0)
    # The second leg of a path round the wall's top, cut through its corner.
    corner = sc.validate("p", np.array([[1.0, 1.0], [3.5, 8.5], [9.0, 1.0]]))["p"]
    assert not corner.valid and corner.collision["segment"] == 1
    with pytest.raises(scen.ScenError) as info:
        sc.validate("p", np.zeros((3, 5)))
    assert info.value.diagnostics[0]["code"] == "scen::python::bad_path"
    with pytest.raises(scen.ScenError):
        sc.validate("p", np.array([[1.0, 1.0], [math.nan, 2.0]]))


def test_validate_a_trajectory_among_moving_obstacles():
    sc = scen.load(SCENARIOS / "time_door.scen")
    report = sc.run()
    name = sc.plans[0]
    traj = report[name].trajectory
    assert traj is not None and traj.shape[1] == 4
    assert np.all(np.diff(traj[:, 3]) >= 0), "times never go back"
    again = sc.validate(name, traj)
    assert again[name].valid
    # Without its times the path cannot be judged among moving obstacles.
    with pytest.raises(scen.ScenError) as info:
        sc.validate(name, traj[:, :3])
    assert info.value.diagnostics[0]["code"] == "scen::validate::needs_times"
    # Straight through at the robot's speed, without waiting: the door,
    # which stands until t = 10 s, is in the way at t = 6.1 s.
    straight = np.array([[2.5, 5.5, 0.0, 0.0], [17.5, 5.5, 0.0, 15.0]])
    hit = sc.validate(name, straight)[name]
    assert not hit.valid and hit.collision["obstacle"] == "door"


def test_seeds_are_explicit_and_runs_repeat():
    sc = scen.load(SCENARIOS / "apartment_rrt.scen") if (SCENARIOS / "apartment_rrt.scen").exists() else None
    if sc is None:
        candidates = [p for p in sorted(SCENARIOS.glob("*.scen")) if any(k in p.read_text() for k in (" rrt ", " prm "))]
        assert candidates, "a scenario with a sampling planner"
        sc = scen.load(candidates[0])
    a = json.loads(sc.run(seed=7).to_json())
    b = json.loads(sc.run(seed=7).to_json())
    assert without_timings(a) == without_timings(b)


def scenario_files():
    # As `scen test` does: a leading `_` marks an include-only fragment.
    return sorted(p for p in SCENARIOS.glob("*.scen") if not p.name.startswith("_"))


@pytest.mark.parametrize("path", scenario_files(), ids=lambda p: p.name)
def test_run_is_scen_run_json_to_the_bit(path):
    """Every scenario: the module's run and the command's `--json` give the
    same document (timings aside), and the numpy paths hold the JSON's
    numbers exactly."""
    cli = subprocess.run(
        [str(SCEN), "run", "--json", path.name], cwd=SCENARIOS, capture_output=True, text=True
    )
    assert cli.returncode in (0, 1), cli.stderr
    expected = json.loads(cli.stdout)
    with contextlib.chdir(SCENARIOS):
        report = scen.load(path.name).run()
    got = json.loads(report.to_json())
    assert without_timings(got) == without_timings(expected)
    for name, plan in expected["plans"].items():
        r = report[name]
        if "agents" in plan:
            # A team plan (SPEC 2.10): each agent's path, no robot path.
            assert r.path is None
            assert r.found == (plan["agents"] is not None)
            for agent in plan["agents"] or []:
                rows = agent["path"] if "path" in agent else agent["trajectory"]
                expected_path = np.array(rows, dtype=np.float64)
                assert np.array_equal(r.agents[agent["name"]], expected_path)
        else:
            assert r.agents is None
            assert r.found == (plan["path"] is not None)
        if plan.get("path") is not None:
            assert np.array_equal(r.path, np.array(plan["path"], dtype=np.float64))
        if "trajectory" in plan:
            assert np.array_equal(r.trajectory, np.array(plan["trajectory"], dtype=np.float64))
        metrics = {k: v for k, v in plan["metrics"].items() if k not in TIMINGS}
        assert {k: v for k, v in r.metrics.items() if k not in TIMINGS} == metrics


LONG = ROOT / "tests" / "python" / "long_search.scen"


def test_the_gil_is_released_while_planning():
    """While one thread plans, another runs Python. With the GIL held for
    the whole call, the other thread, woken by `inside`, could only take
    the GIL after the call returned: it would count (almost) nothing."""
    sc = scen.load(LONG)
    inside = threading.Event()
    done = threading.Event()
    result = []

    def work():
        inside.set()
        result.append(sc.run())
        done.set()

    counted = 0
    t = threading.Thread(target=work)
    t.start()
    inside.wait()
    while not done.is_set():
        counted += 1
    t.join()
    assert result[0]["p"].found
    assert counted > 1000, counted


DATA = ROOT.parent / "shared" / "data" / "movingai"


def movingai_grid(path):
    """A MovingAI map as a bool array, True where blocked (row 0 the top)."""
    lines = path.read_text().splitlines()
    rows = lines[lines.index("map") + 1 :]
    return np.array([[c not in ".GS" for c in row] for row in rows if row], dtype=bool)


def centre(h, col, row):
    """The world point of a MovingAI cell (x right, y down from the top)."""
    return (col + 0.5, h - 1 - row + 0.5)


def test_plan_on_a_numpy_grid_is_the_cli_on_the_same_map(tmp_path):
    """`scen.plan` on a MovingAI map read into numpy gives the path `scen
    run` gives on the map file, to the bit, and the benchmark's optimal
    length."""
    map_file = DATA / "maze512-32-9.map"
    if not map_file.exists():
        if os.environ.get("CI") == "true":
            pytest.fail(f"{map_file} is missing (CI always has ../shared/data)")
        pytest.skip(f"{map_file} is missing: the MovingAI data lives in ../shared/data")
    grid = movingai_grid(map_file)
    h, w = grid.shape
    assert (h, w) == (512, 512)
    rows = [l.split("\t") for l in (DATA / "maze512-32-9.map.scen").read_text().splitlines()[1:]]
    row = rows[-1]  # the longest query
    start = centre(h, int(row[4]), int(row[5]))
    goal = centre(h, int(row[6]), int(row[7]))
    optimal = float(row[8])
    mine = scen.plan(grid, start, goal, connect=8)
    assert mine.found and mine.valid
    assert mine.metrics["length"] == pytest.approx(optimal, abs=1e-6)
    (tmp_path / "maze.map").write_text(map_file.read_text())
    (tmp_path / "maze.scen").write_text(
        f"""scenario "maze"
world {{
  bounds (0, 0) ({w}, {h})
  grid cells "maze.map" cell 1 origin (0, 0)
}}
robot r point
plan p astar r {{
  start ({start[0]}, {start[1]})
  goal ({goal[0]}, {goal[1]})
  connect 8
}}
"""
    )
    cli = subprocess.run([str(SCEN), "run", "--json", "maze.scen"], cwd=tmp_path, capture_output=True, text=True)
    assert cli.returncode == 0, cli.stderr
    expected = json.loads(cli.stdout)["plans"]["p"]
    assert np.array_equal(mine.path, np.array(expected["path"]))
    assert {k: v for k, v in mine.metrics.items() if k != "time_ms"} == {
        k: v for k, v in expected["metrics"].items() if k != "time_ms"
    }


def test_plan_reads_row_0_as_the_top_row_and_any_dtype():
    # Only the top row is free: the path stays on it (y = 4.5 of 0..5).
    grid = np.ones((5, 6), dtype=bool)
    grid[0, :] = False
    r = scen.plan(grid, (0.5, 4.5), (5.5, 4.5), connect=4)
    assert r.found and r.valid and np.all(r.path[:, 1] == 4.5)
    assert r.metrics["length"] == pytest.approx(5.0)
    assert "<svg" in r._repr_svg_() and "p (astar)" in r.to_svg()
    for dtype in (np.uint8, np.int32, np.int64, np.float32, np.float64):
        again = scen.plan(grid.astype(dtype), (0.5, 4.5), (5.5, 4.5), connect=4)
        assert np.array_equal(again.path, r.path), dtype
    # A transposed view (not C-contiguous) reads the same cells.
    assert scen.plan(np.ascontiguousarray(grid.T).T, (0.5, 4.5), (5.5, 4.5), connect=4).found
    # Free cells only on the diagonal: 4-connected, they do not meet.
    none = scen.plan(np.ones((5, 6), dtype=bool) & ~np.eye(5, 6, dtype=bool), (0.5, 4.5), (4.5, 0.5), connect=4)
    assert not none.found and none.path is None and not none.valid


def test_plan_with_cell_origin_robot_and_params():
    grid = np.zeros((10, 10), dtype=bool)
    grid[2:10, 5] = True  # a wall from the bottom, open at the top two rows
    # The grid spans x in [-2, 3] and y in [0, 5]: (9, 1) is outside.
    with pytest.raises(scen.ScenError) as info:
        scen.plan(grid, (-1.0, 1.0), (9.0, 1.0), cell=0.5, origin=(-2.0, 0.0), robot="disk 0.2")
    assert info.value.diagnostics[0]["code"] == "scen::analyze::pose_outside"
    r = scen.plan(grid, (-1.0, 1.0), (2.0, 1.0), cell=0.5, origin=(-2.0, 0.0), robot="disk 0.2", heuristic="zero")
    assert r.found and r.valid and r.path[:, 1].max() >= 4.0


def test_plan_refuses_bad_input_with_its_code():
    grid = np.zeros((4, 4), dtype=bool)
    cases = [
        (lambda: scen.plan([[0, 1], [1, 0]], (0.5, 0.5), (1.5, 1.5)), "scen::python::bad_grid"),
        (lambda: scen.plan(np.zeros((2, 2, 2)), (0.5, 0.5), (1.5, 1.5)), "scen::python::bad_grid"),
        (lambda: scen.plan(grid, (0.5,), (1.5, 1.5)), "scen::python::bad_plan"),
        (lambda: scen.plan(grid, (0.5, 0.5), (1.5, math.inf)), "scen::python::bad_plan"),
        (lambda: scen.plan(grid, (0.5, 0.5), (1.5, 1.5), cell=0), "scen::python::bad_plan"),
        (lambda: scen.plan(grid, (0.5, 0.5), (1.5, 1.5), planner="astar }"), "scen::python::bad_plan"),
        (lambda: scen.plan(grid, (0.5, 0.5), (1.5, 1.5), heuristic="zero\n}"), "scen::python::bad_plan"),
        (lambda: scen.plan(grid, (0.5, 0.5), (1.5, 1.5), cel=0.5), "scen::analyze::unknown_key"),
        (lambda: scen.plan(grid, (0.5, 0.5), (1.5, 1.5), planner="astra"), "scen::analyze::unknown_planner"),
        (lambda: scen.plan(grid, (0.5, 0.5), (9.5, 1.5)), "scen::analyze::pose_outside"),
    ]
    for call, code in cases:
        with pytest.raises(scen.ScenError) as info:
            call()
        assert info.value.diagnostics[0]["code"] == code, (code, str(info.value))
