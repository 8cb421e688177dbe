#!/usr/bin/env python3
"""Paired wall time of two scen binaries on the SEEDS §A apartment rod.

Each seed's plan is run by the two binaries one after the other (the order
alternating between rounds), and the result is the geometric mean of the
per-seed ratios NEW/OLD of `time_ms`: this machine's speed drifts by ±15 %
between runs, and a pair run seconds apart sees the same drift.

Usage: python3 scripts/paired_apartment.py OLD NEW [PLANNER] [SEEDS] [ROUNDS]
  PLANNER  prm (default) or rrt_connect; SEEDS 20; ROUNDS 2.
Figures: BENCHMARKS.md (issue 22).
"""
import json
import math
import os
import shutil
import statistics
import subprocess
import sys
import tempfile

old, new = sys.argv[1], sys.argv[2]
planner = sys.argv[3] if len(sys.argv) > 3 else "prm"
seeds = int(sys.argv[4]) if len(sys.argv) > 4 else 20
rounds = int(sys.argv[5]) if len(sys.argv) > 5 else 2
here = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
tmp = tempfile.mkdtemp()
try:
    shutil.copy(os.path.join(here, "scenarios", "_apartment_world.scen"), tmp)
    scenario = os.path.join(tmp, "run.scen")
    with open(scenario, "w") as f:
        f.write('include "_apartment_world.scen"\n')
        f.write("robot rod polygon [(0,0), (8,0), (8,1), (0,1)]\n")
        for s in range(1, seeds + 1):
            f.write(f"plan p{s} {planner} rod {{ start (4, 24, 0deg) goal (4, 8, 0deg) seed {s} limit time 30s }}\n")
    env = dict(os.environ, RAYON_NUM_THREADS="1")

    def time_ms(binary, plan):
        out = subprocess.run([binary, "run", "--json", "--plan", plan, scenario],
                             capture_output=True, text=True, env=env, check=False).stdout
        return json.loads(out)["plans"][plan]["metrics"]["time_ms"]

    logs, a, b = [], [], []
    for r in range(rounds):
        for s in range(1, seeds + 1):
            plan = f"p{s}"
            first, second = (old, new) if r % 2 == 0 else (new, old)
            t = {first: time_ms(first, plan), second: time_ms(second, plan)}
            a.append(t[old])
            b.append(t[new])
            logs.append(math.log(t[new] / t[old]))
    print(f"{planner}: OLD median {statistics.median(a):.2f} ms, NEW median {statistics.median(b):.2f} ms, "
          f"NEW/OLD geometric mean of the per-seed ratios {math.exp(statistics.mean(logs)):.3f} "
          f"(median ratio {math.exp(statistics.median(logs)):.3f}, {len(logs)} pairs)")
finally:
    shutil.rmtree(tmp)
