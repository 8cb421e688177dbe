#!/usr/bin/env bash
# The searches of `scen falsify` on two families, 40 search seeds each: how
# many seeds find a failure within the budget of 1,000, and the median
# number of samples tried (a seed that finds none counts as never).
# - benches/falsify_needle.scen: the failure region is 0.1 % of the draws
#   (the goal within 0.1784 of the start), the margin continuous;
# - benches/falsify_decoy.scen: the same needle beside a decoy, a basin of
#   the margin around another start that goes down to 0 but never fails.
# Figures in BENCHMARKS.md.
set -euo pipefail
cd "$(dirname "$0")/.."
SCEN="${SCEN:-target/release/scen}"
out="$(mktemp -d)"
for family in needle decoy; do
for search in auto cross_entropy halton uniform; do
  for seed in $(seq 0 39); do
    "$SCEN" falsify "benches/falsify_$family.scen" --search "$search" --seed "$seed" \
      --json --out "$out/fail.scen" || true
    echo
  done | python3 -c "
import json, statistics, sys
runs = [json.loads(l) for l in sys.stdin if l.strip()]
found = [r['samples_tried'] for r in runs if r['found']]
median = statistics.median([r['samples_tried'] if r['found'] else float('inf') for r in runs])
print(f'$family, $search: {len(found)}/{len(runs)} seeds found a failure; median samples tried {median}')
"
done
done
rm -rf "$out"
