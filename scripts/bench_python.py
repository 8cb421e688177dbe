#!/usr/bin/env python3
"""The Python module's speed (issue 42 item 4), with the wheel installed:

    target/wheel-venv/bin/python scripts/bench_python.py

- call overhead: a run of a tiny scenario (a 2-cell A*), timed from
  Python, minus the planner's own `time_ms`; and `validate` of a 2-pose
  path;
- the GIL: one long A* alone, then two at once in two threads;
- a 1,000 x 1,000 numpy grid (20 % of cells blocked at random, seed 1):
  `scen.plan` against `scen run` on the same grid written as a map file,
  both timed whole (the command: process, reading, parsing, planning,
  JSON; the module: the grid's conversion, parsing, planning, results).
Prints one line per measure (medians of repeated calls)."""

import statistics
import subprocess
import sys
import tempfile
import threading
import time
from pathlib import Path

import numpy as np
import scen

TINY = """scenario "tiny"
world {
  bounds (0, 0) (2, 1)
}
robot r point
plan p astar r {
  start (0.5, 0.5)
  goal (1.5, 0.5)
}
"""

LONG = Path(__file__).resolve().parents[1] / "tests" / "python" / "long_search.scen"


def median_us(f, n):
    times = []
    for _ in range(n):
        t = time.perf_counter()
        f()
        times.append((time.perf_counter() - t) * 1e6)
    return statistics.median(times)


def main():
    sc = scen.loads(TINY, name="tiny.scen")
    for _ in range(100):
        sc.run()
    walls, inner = [], []
    for _ in range(2000):
        t = time.perf_counter()
        r = sc.run()
        walls.append((time.perf_counter() - t) * 1e6)
        inner.append(r["p"].metrics["time_ms"] * 1e3)
    wall, plan = statistics.median(walls), statistics.median(inner)
    print(f"run, tiny scenario: {wall:.1f} us per call, of which the planner {plan:.1f} us: overhead {wall - plan:.1f} us")
    path = np.array([[0.5, 0.5], [1.5, 0.5]])
    print(f"validate, 2 poses: {median_us(lambda: sc.validate('p', path), 2000):.1f} us per call")
    print(f"Scenario.plans: {median_us(lambda: sc.plans, 2000):.2f} us per call")

    heavy = scen.load(LONG)
    heavy.run()
    one = statistics.median(median_us(heavy.run, 1) for _ in range(5)) / 1e6

    def two():
        ts = [threading.Thread(target=heavy.run) for _ in range(2)]
        t = time.perf_counter()
        for x in ts:
            x.start()
        for x in ts:
            x.join()
        return time.perf_counter() - t

    both = statistics.median(two() for _ in range(5))
    print(f"one long A* alone: {one * 1e3:.0f} ms; two at once in two threads: {both * 1e3:.0f} ms ({both / one:.2f}x)")

    rng = np.random.default_rng(1)
    grid = rng.random((1000, 1000)) < 0.2
    grid[-1, 0] = grid[0, -1] = False
    start, goal = (0.5, 0.5), (999.5, 999.5)
    mine = scen.plan(grid, start, goal)
    assert mine.found
    with tempfile.TemporaryDirectory() as tmp:
        tmp = Path(tmp)
        rows = "\n".join("".join("@" if b else "." for b in row) for row in grid)
        (tmp / "big.map").write_text(f"type octile\nheight 1000\nwidth 1000\nmap\n{rows}\n")
        (tmp / "big.scen").write_text(
            'scenario "1000 x 1000"\nworld {\n  bounds (0, 0) (1000, 1000)\n  grid cells "big.map" cell 1 origin (0, 0)\n}\n'
            "robot r point\nplan p astar r {\n  start (0.5, 0.5)\n  goal (999.5, 999.5)\n}\n"
        )
        scen_bin = Path(sys.executable).parent / "scen"

        def cli():
            out = subprocess.run([str(scen_bin), "run", "--json", "big.scen"], cwd=tmp, capture_output=True, check=True)
            return out.stdout

        cli()
        cli_s = statistics.median(median_us(cli, 1) for _ in range(5)) / 1e6
        mod_s = statistics.median(median_us(lambda: scen.plan(grid, start, goal), 1) for _ in range(5)) / 1e6
        import json

        their = json.loads(cli())["plans"]["p"]
        assert np.array_equal(mine.path, np.array(their["path"]))
        print(
            f"1000 x 1000 grid, A* ({mine.metrics['expanded']} expanded, same path): "
            f"scen run {cli_s * 1e3:.0f} ms, scen.plan {mod_s * 1e3:.0f} ms ({mod_s / cli_s:.2f}x); "
            f"planner alone {mine.metrics['time_ms']:.0f} ms"
        )


if __name__ == "__main__":
    main()
