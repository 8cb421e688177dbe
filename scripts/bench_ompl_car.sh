#!/usr/bin/env bash
# Issue 23's comparison with OMPL on the parking problem, both sides in one
# run: scen's rrt_connect and rrt_star (`stop first`) on
# benches/car_parking_ompl.scen, seeds 1..N, one thread; then OMPL's
# RRTConnect and RRTstar (pip `ompl` 2.0.1, ReedsSheppStateSpace, the
# validity checker of scripts/ompl_car.py), seeds 1..N.
#
# Usage: scripts/bench_ompl_car.sh SCEN PYTHON [N]
#   SCEN    the scen binary (target/release/scen)
#   PYTHON  a Python with `ompl` (target/rerun-venv/bin/python)
#   N       seeds per side (default 20)
# Prints one line per run, then per planner the runs solved, the median time
# to the first solution (s) and OMPL's median over scen's. Figures:
# BENCHMARKS.md.
set -euo pipefail
scen="$1"; py="$2"; n="${3:-20}"
here="$(cd "$(dirname "$0")/.." && pwd)"
tmp="$(mktemp -d)"; trap 'rm -rf "$tmp"' EXIT
results="$tmp/results.txt"; : > "$results"
# scen: the bench's seeds are 1..N (`seed 1`, run k gets seed 1 + k).
RAYON_NUM_THREADS=1 "$scen" bench -q --json --runs "$n" "$here/benches/car_parking_ompl.scen" \
  | python3 -c "
import json, sys
doc = json.load(sys.stdin)
for r in doc['benches'][0]['results']:
    m = r['metrics']
    print('scen', r['plan'], r['seed'], int(m['found']), m['time_ms'] / 1000, m['length'])
" | tee -a "$results"
for planner in rrt_connect rrt_star; do
  for seed in $(seq 1 "$n"); do
    "$py" "$here/scripts/ompl_car.py" "$planner" "$seed" 60 \
      | awk '{print "ompl", $1, $2, $3, $4, $5}' | tee -a "$results"
  done
done
python3 - "$results" <<'PY'
import statistics, sys
rows = [l.split() for l in open(sys.argv[1])]
print()
print("| planner | scen solved | scen median (s) | OMPL solved | OMPL median (s) | OMPL / scen |")
print("|---|---|---|---|---|---|")
for planner in ("rrt_connect", "rrt_star"):
    plan = {"rrt_connect": "connect", "rrt_star": "star"}[planner]
    def side(who, name):
        runs = [r for r in rows if r[0] == who and r[1] == name]
        solved = [float(r[4]) for r in runs if r[3] == "1"]
        return len(solved), len(runs), statistics.median(solved) if solved else float("nan")
    s_ok, s_n, s_med = side("scen", plan)
    o_ok, o_n, o_med = side("ompl", planner)
    print(f"| {planner} | {s_ok} / {s_n} | {s_med:.4f} | {o_ok} / {o_n} | {o_med:.4f} | {o_med / s_med:.1f}× |")
PY
