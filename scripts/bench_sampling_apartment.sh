#!/usr/bin/env bash
# The SEEDS §A apartment rod with scen's rrt_connect and prm (each run
# `limit time 30s`, seeds 1..N) and, in the same run, OMPL's RRT, PRM and
# RRTConnect on ../shared/peers/apartment.world (the peer of
# ../shared/peers/README.md, built by ../shared/peers/build.sh).
#
# Usage: scripts/bench_sampling_apartment.sh SCEN [OMPL_SE2] [N] [OMPL_N]
#   SCEN      the scen binary (target/release/scen)
#   OMPL_SE2  the peer binary (target/peers/ompl_se2); omitted: scen only
#   N         seeds for scen (default 20); OMPL_N for OMPL (default 10)
# Prints one line per run and a summary: solved runs and the median time to
# the first solution of the solved ones. Figures: BENCHMARKS.md.
set -euo pipefail
scen="$1"; ompl="${2:-}"; n="${3:-20}"; ompl_n="${4:-10}"
here="$(cd "$(dirname "$0")/.." && pwd)"
world="$here/../shared/peers/apartment.world"
tmp="$(mktemp -d)"; trap 'rm -rf "$tmp"' EXIT
cp "$here/scenarios/_apartment_world.scen" "$tmp/"
results="$tmp/results.txt"; : > "$results"
for seed in $(seq 1 "$n"); do
  cat > "$tmp/run.scen" <<SCEN
include "_apartment_world.scen"
robot rod polygon [(0,0), (8,0), (8,1), (0,1)]
plan rrt_connect rrt_connect rod { start (4, 24, 0deg) goal (4, 8, 0deg) seed $seed limit time 30s }
plan prm prm rod { start (4, 24, 0deg) goal (4, 8, 0deg) seed $seed limit time 30s }
SCEN
  for plan in rrt_connect prm; do
    "$scen" run --json --plan "$plan" "$tmp/run.scen" | python3 -c "
import json, sys
m = json.load(sys.stdin)['plans']['$plan']['metrics']
print('scen_$plan', $seed, int(m['found']), m['time_ms'] / 1000, m['iterations'], m['length'])
" | tee -a "$results"
  done
  if [ -n "$ompl" ] && [ "$seed" -le "$ompl_n" ]; then
    for p in rrt prm rrtconnect; do
      "$ompl" "$world" "$p" "$seed" 30 | python3 -c "
import sys
f = dict(kv.split('=') for kv in sys.stdin.read().split()[1:])
print('ompl_$p', $seed, f['solved'], f['time'], f['checks'], f['xy'])
" | tee -a "$results"
    done
  fi
done
echo "--- planner solved/runs median_time_s (solved runs)"
python3 - "$results" <<'PY'
import sys, statistics
runs = {}
for line in open(sys.argv[1]):
    name, seed, solved, t, *_ = line.split()
    runs.setdefault(name, []).append((int(solved), float(t)))
for name, rs in runs.items():
    ok = [t for s, t in rs if s]
    med = statistics.median(ok) if ok else float('nan')
    print(f"{name} {len(ok)}/{len(rs)} {med:.4f}")
PY
