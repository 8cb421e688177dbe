#!/usr/bin/env bash
# Instructions per sampling iteration (issue 22's measure): the whole
# `scen run` process under callgrind, one thread, the apartment rod
# (SEEDS §A) with rrt_connect and prm on seed 1, divided by the run's
# `iterations`.
#
# Usage: scripts/instructions_apartment.sh SCEN [SCEN...]
#   each SCEN a scen binary (e.g. an older build and target/release/scen)
# Needs valgrind. Figures: BENCHMARKS.md.
set -euo pipefail
here="$(cd "$(dirname "$0")/.." && pwd)"
tmp="$(mktemp -d)"; trap 'rm -rf "$tmp"' EXIT
cp "$here/scenarios/_apartment_world.scen" "$tmp/"
for planner in rrt_connect prm; do
  cat > "$tmp/$planner.scen" <<SCEN
include "_apartment_world.scen"
robot rod polygon [(0,0), (8,0), (8,1), (0,1)]
plan p $planner rod { start (4, 24, 0deg) goal (4, 8, 0deg) seed 1 }
SCEN
done
for scen in "$@"; do
  for planner in rrt_connect prm; do
    total=$(RAYON_NUM_THREADS=1 valgrind --tool=callgrind --callgrind-out-file="$tmp/cg.out" \
      "$scen" run --json "$tmp/$planner.scen" 2>&1 >/dev/null | sed -n 's/.*Collected : //p')
    iterations=$("$scen" run --json "$tmp/$planner.scen" \
      | python3 -c "import json, sys; print(int(json.load(sys.stdin)['plans']['p']['metrics']['iterations']))")
    echo "$scen $planner instructions=$total iterations=$iterations per_iteration=$((total / iterations))"
  done
done
