#!/usr/bin/env python3
"""Issue 43 item 4: the success rate of scen's `cbs` by agent count, beside
an optimal CBS variant of the literature (CBSH2-RTC, Jiaoyang-Li/CBSH2-RTC:
CBS with prioritised conflicts, bypass, the WDG heuristic, generalised
rectangle, corridor and target reasoning) and a Python CBS (pymapf's
ConflictBasedSearch, PyPI pymapf==0.9.0), in one run, on the same
instances, 60 s each.

The instances follow the MovingAI benchmark's protocol: K scenario files of
random rows per map (distinct starts, distinct goals, all in the map's
largest 4-connected region, drawn with a fixed seed), and for each agent
count N the first N rows of each file. The maps are MovingAI's empty-8-8
and random-32-32-10, read from ../shared/data/movingai. For a solver, the
counts stop after the first count at which it solved none of the K files.

Both solvers are optimal, so where both solve an instance their sums of
costs must agree: the script checks it (and scen's every plan is judged by
its referee). Prints a Markdown table for BENCHMARKS.md.

All three are optimal, so where two solve an instance their sums of costs
must agree: the script checks it.

CBSH2-RTC is not built here: CBSH2RTC=PATH names its `cbs` binary
(default target/peers/CBSH2-RTC/cbs; BENCHMARKS.md says how it was built).

Usage: scripts/bench_cbs_success.py [--instances K] [--limit SECONDS] [--map NAME]
       [--python PYTHON] (a Python with pymapf installed; default: builds
       target/peers/pymapf-venv); SCEN=PATH runs another scen binary
"""

import argparse
import json
import os
import random
import subprocess
import sys
import tempfile
from collections import deque
from pathlib import Path

HERE = Path(__file__).resolve().parent.parent
DATA = Path(os.environ.get("MOVINGAI", HERE.parent / "shared" / "data" / "movingai"))
SCEN = Path(os.environ.get("SCEN", HERE / "target" / "release" / "scen"))
CBSH2RTC = Path(os.environ.get("CBSH2RTC", HERE / "target" / "peers" / "CBSH2-RTC" / "cbs"))
MAPS = [
    ("empty-8-8", DATA / "mapf" / "empty-8-8.map", [4, 8, 12, 16, 20, 24, 28, 32]),
    ("random-32-32-10", DATA / "random-32-32-10.map", [10, 20, 30, 40, 50, 60, 70, 80, 90, 100, 110, 120]),
]
SOLVERS = ("scen", "cbsh2rtc", "pymapf")

PYMAPF_RUN = r"""
import json, sys, time
import pymapf
from pymapf.algorithms.cbs import ConflictBasedSearch
rows, starts, goals, limit = json.load(sys.stdin)
grid = pymapf.GridMap(rows)
agents = [pymapf.Agent("a%d" % k, start=tuple(s), goal=tuple(g)) for k, (s, g) in enumerate(zip(starts, goals))]
problem = pymapf.MAPFProblem(grid, agents)
t = time.perf_counter()
solution = ConflictBasedSearch(max_expansions=10**12, time_limit=limit).solve(problem)
ms = (time.perf_counter() - t) * 1e3
if solution is None:
    print(json.dumps({"found": False, "ms": ms}))
else:
    print(json.dumps({"found": True, "ms": ms, "soc": solution.sum_of_costs, "valid": solution.is_valid()}))
"""


def read_map(path):
    lines = path.read_text().split("\n")
    h = int(lines[1].split()[1])
    w = int(lines[2].split()[1])
    cells = [lines[4 + r][:w] for r in range(h)]
    return w, h, [[c not in ".G" for c in row] for row in cells]


def largest_region(w, h, blocked):
    seen = [[False] * w for _ in range(h)]
    best = []
    for r0 in range(h):
        for c0 in range(w):
            if blocked[r0][c0] or seen[r0][c0]:
                continue
            region, todo = [], deque([(r0, c0)])
            seen[r0][c0] = True
            while todo:
                r, c = todo.popleft()
                region.append((r, c))
                for dr, dc in ((1, 0), (-1, 0), (0, 1), (0, -1)):
                    rr, cc = r + dr, c + dc
                    if 0 <= rr < h and 0 <= cc < w and not blocked[rr][cc] and not seen[rr][cc]:
                        seen[rr][cc] = True
                        todo.append((rr, cc))
            if len(region) > len(best):
                best = region
    return best


def bfs(w, h, blocked, start):
    dist = {start: 0}
    todo = deque([start])
    while todo:
        r, c = todo.popleft()
        for dr, dc in ((1, 0), (-1, 0), (0, 1), (0, -1)):
            n = (r + dr, c + dc)
            if 0 <= n[0] < h and 0 <= n[1] < w and not blocked[n[0]][n[1]] and n not in dist:
                dist[n] = dist[(r, c)] + 1
                todo.append(n)
    return dist


def write_scen(path, map_name, w, h, blocked, region, n, rng):
    cells = rng.sample(region, 2 * n)
    starts, goals = cells[:n], cells[n:]
    lines = ["version 1"]
    for (sr, sc), (gr, gc) in zip(starts, goals):
        d = bfs(w, h, blocked, (sr, sc))[(gr, gc)]
        lines.append(f"0\t{map_name}\t{w}\t{h}\t{sc}\t{sr}\t{gc}\t{gr}\t{d}")
    path.write_text("\n".join(lines) + "\n")
    return starts, goals


def run_scen(work, map_file, w, h, scen_file, n, limit):
    (work / "b.scen").write_text(
        f'world {{ bounds (0, 0) ({w}, {h}) grid G "{map_file.name}" cell 1 }}\n'
        f'team T point from "{scen_file.name}" agents {n}\n'
        f"plan p cbs T {{ limit time {limit}s }}\n"
    )
    out = subprocess.run([str(SCEN), "run", str(work / "b.scen"), "--json"], capture_output=True, text=True)
    m = json.loads(out.stdout)["plans"]["p"]["metrics"]
    return {
        "found": bool(m["found"]),
        "ms": m["time_ms"],
        "soc": m["sum_of_costs"] if m["found"] else None,
        "valid": m["collision_free"],
    }


def run_cbsh2rtc(work, map_file, scen_file, n, limit):
    out = subprocess.run(
        [str(CBSH2RTC), "-m", str(work / map_file.name), "-a", str(scen_file), "-k", str(n),
         "-t", str(limit), "-o", str(work / "cbsh2rtc.csv"), "-s", "1"],
        capture_output=True, text=True, timeout=limit * 3 + 60)
    if out.returncode != 0:
        raise SystemExit(f"CBSH2-RTC failed: {out.stderr}")
    # The last line: "<variant> : <status>,<cost>,<seconds>,...".
    status, cost, seconds = out.stdout.strip().split("\n")[-1].split(":")[-1].split(",")[:3]
    found = status.strip() == "Optimal"
    return {"found": found, "ms": float(seconds) * 1e3, "soc": int(cost) if found else None}


def run_pymapf(python, blocked, starts, goals, limit):
    rows = [[1 if b else 0 for b in row] for row in blocked]
    payload = json.dumps([rows, starts, goals, limit])
    out = subprocess.run([python, "-c", PYMAPF_RUN], input=payload, capture_output=True, text=True,
                         timeout=limit * 3 + 60)
    if out.returncode != 0:
        raise SystemExit(f"pymapf failed: {out.stderr}")
    return json.loads(out.stdout)


def pymapf_python():
    venv = HERE / "target" / "peers" / "pymapf-venv"
    python = venv / "bin" / "python"
    if not python.exists():
        subprocess.run([sys.executable, "-m", "venv", str(venv)], check=True)
        subprocess.run([str(venv / "bin" / "pip"), "install", "--quiet", "pymapf==0.9.0"], check=True)
    return str(python)


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--instances", type=int, default=5)
    ap.add_argument("--limit", type=float, default=60.0)
    ap.add_argument("--python", default=None)
    ap.add_argument("--map", action="append", help="run only this map (empty-8-8, random-32-32-10); repeatable")
    args = ap.parse_args()
    python = args.python or pymapf_python()
    if not SCEN.exists():
        raise SystemExit(f"{SCEN} is missing: build it with `cargo build --release`")
    if not CBSH2RTC.exists():
        raise SystemExit(f"{CBSH2RTC} is missing: build CBSH2-RTC there (BENCHMARKS.md) or set CBSH2RTC")
    rows = []
    with tempfile.TemporaryDirectory() as tmp:
        work = Path(tmp)
        for name, map_path, counts in MAPS:
            if args.map and name not in args.map:
                continue
            w, h, blocked = read_map(map_path)
            (work / map_path.name).write_bytes(map_path.read_bytes())
            region = largest_region(w, h, blocked)
            rng = random.Random(20261207)
            files = []
            for k in range(args.instances):
                f = work / f"{name}-random-{k + 1}.scen"
                starts, goals = write_scen(f, map_path.name, w, h, blocked, region, max(counts), rng)
                files.append((f, starts, goals))
            alive = {solver: True for solver in SOLVERS}
            for n in counts:
                if not any(alive.values()):
                    break
                result = {solver: [] for solver in SOLVERS}
                for f, starts, goals in files:
                    got = {}
                    if alive["scen"]:
                        got["scen"] = run_scen(work, map_path, w, h, f, n, args.limit)
                        assert not got["scen"]["found"] or got["scen"]["valid"], f"scen's referee refused {f.name} n={n}"
                    if alive["cbsh2rtc"]:
                        got["cbsh2rtc"] = run_cbsh2rtc(work, map_path, f, n, args.limit)
                    if alive["pymapf"]:
                        cells = lambda cs: [[r, c] for r, c in cs[:n]]
                        got["pymapf"] = run_pymapf(python, blocked, cells(starts), cells(goals), args.limit)
                        assert not got["pymapf"]["found"] or got["pymapf"]["valid"], f"pymapf's solution is invalid on {f.name} n={n}"
                    costs = {s: r["soc"] for s, r in got.items() if r["found"]}
                    assert len(set(costs.values())) <= 1, f"{f.name} n={n}: sums of costs differ: {costs}"
                    for solver, r in got.items():
                        result[solver].append(r)
                    print(f"{name} n={n} {f.name}: {got}", file=sys.stderr, flush=True)
                row = [name, n]
                for solver in SOLVERS:
                    rs = result[solver]
                    if not alive[solver]:
                        row += ["—", "—"]
                        continue
                    solved = [r for r in rs if r["found"]]
                    times = sorted(r["ms"] for r in solved)
                    median = times[len(times) // 2] if times else None
                    row += [f"{len(solved)}/{len(rs)}", f"{median:.1f}" if median is not None else "—"]
                    if not solved:
                        alive[solver] = False
                rows.append(row)
    print("| map | agents | scen `cbs` solved | median ms | CBSH2-RTC solved | median ms | pymapf CBS solved | median ms |")
    print("|---|---|---|---|---|---|---|---|")
    for r in rows:
        print("| " + " | ".join(str(x) for x in r) + " |")


if __name__ == "__main__":
    main()
