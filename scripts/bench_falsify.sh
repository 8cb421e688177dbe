#!/usr/bin/env bash
# The searches of `scen falsify`, 40 search seeds each, budget 1,000: how
# many seeds find a failure, the median and the largest number of samples
# tried (a seed that finds none counts as never, `inf`).
# - benches/falsify_needle.scen: the failure region is 0.1 % of the draws
#   (the goal within 0.1784 of the start), the margin continuous;
# - benches/falsify_decoy.scen: the same needle beside a decoy, a basin of
#   the margin around another start that goes down to 0 but never fails;
# - benches/falsify/*.scen: held-out shapes, each 0.1 % of the box: a
#   corner, a thin diagonal band, a band beside a decoy, a narrow range of
#   a product of two params.
# `SEARCHES="auto halton"` chooses the searches (default: all four on the
# needle and the decoy, `auto` on the held-out shapes).
# Figures in BENCHMARKS.md.
set -euo pipefail
cd "$(dirname "$0")/.."
SCEN="${SCEN:-target/release/scen}"
out="$(mktemp -d)"
trap 'rm -rf "$out"' EXIT
bench() {
  local file="$1" search="$2"
  for seed in $(seq 0 39); do
    "$SCEN" falsify "$file" --search "$search" --seed "$seed" \
      --json --out "$out/fail.scen" || true
    echo
  done | python3 -c "
import json, statistics, sys
runs = [json.loads(l) for l in sys.stdin if l.strip()]
tried = [r['samples_tried'] if r['found'] else float('inf') for r in runs]
found = sum(1 for r in runs if r['found'])
print(f'| \`$file\` | \`$search\` | {found} / {len(runs)} | {statistics.median(tried)} | {max(tried)} |')
"
}
echo "| family | search | seeds that found a failure | median samples tried | most samples tried |"
echo "|---|---|---|---|---|"
for family in benches/falsify_needle.scen benches/falsify_decoy.scen; do
  for search in ${SEARCHES:-auto cross_entropy halton uniform}; do
    bench "$family" "$search"
  done
done
for family in benches/falsify/*.scen; do
  for search in ${SEARCHES:-auto}; do
    bench "$family" "$search"
  done
done
