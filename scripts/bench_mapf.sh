#!/usr/bin/env bash
# Issue 43 item 4: scen's `lacam` beside LaCAM3 (Kei18/lacam3, MIT, pinned
# commit) on the same MovingAI instances, in one run: random-32-32-10 with
# the first 50 and 400 rows of random-1, and warehouse-20-40-10-2-2 with
# the first 1,000 rows of its 10000agents-8 scenario. Prints one line per
# instance and solver: solved, sum of costs, its lower bound, makespan and
# milliseconds. The benchmark files are read from ../shared/data/movingai
# (copied into a temporary folder beside a scenario that reads them).
#
# LaCAM3 is built from $LACAM3 (a folder with its main.cpp, lacam3/ and
# argparse/include, see ../shared/peers/lacam3.md), default target/peers/lacam3.
# Both run on one thread: LaCAM3 plain (--no-star --no-multi-thread), and
# vanilla LaCAM (--no-all), the algorithm `lacam` implements.
# Usage: scripts/bench_mapf.sh
set -euo pipefail
here="$(cd "$(dirname "$0")/.." && pwd)"
data="${MOVINGAI:-$here/../shared/data/movingai}"
src="${LACAM3:-$here/target/peers/lacam3}"
bin="$src/lacam3-main"
if ! [ -x "$bin" ]; then
  (cd "$src" && g++ -O3 -std=c++17 -Ilacam3/include -Iargparse/include main.cpp lacam3/src/*.cpp -o lacam3-main -lpthread)
fi
cd "$here"
cargo build --release -q --bin scen
work="$(mktemp -d)"
trap 'rm -rf "$work"' EXIT
cp "$data/random-32-32-10.map" "$data/random-32-32-10-random-1.scen" \
  "$data/mapf/warehouse-20-40-10-2-2.map" "$data/mapf/warehouse-20-40-10-2-2-10000agents-8.scen" "$work/"

run() { # map width height scen agents
  local map=$1 w=$2 h=$3 scen=$4 n=$5
  cat > "$work/b.scen" <<EOF
world { bounds (0, 0) ($w, $h) grid G "$map" cell 1 }
team T point from "$scen" agents $n
plan p lacam T { limit time 60s }
EOF
  "$here/target/release/scen" run "$work/b.scen" --json | python3 -c '
import json, sys
m = json.load(sys.stdin)["plans"]["p"]["metrics"]
print("scen lacam                           solved=%d soc=%d soc_lb=%d makespan=%d ms=%.0f" % (
    m["found"], m["sum_of_costs"], m["soc_lower_bound"], m["makespan"], m["time_ms"]))'
  for flags in "--no-star --no-multi-thread" "--no-all"; do
    "$bin" -m "$work/$map" -i "$work/$scen" -N "$n" -t 60 -o "$work/r.txt" $flags -v 0 > /dev/null
    python3 - "$work/r.txt" "$flags" <<'PY'
import sys
r = dict(l.strip().split("=", 1) for l in open(sys.argv[1]) if "=" in l and l.split("=")[0] in
         ("solved", "soc", "soc_lb", "makespan", "comp_time"))
print(f"lacam3 {sys.argv[2]:28} solved={r['solved']} soc={r['soc']} soc_lb={r['soc_lb']} makespan={r['makespan']} ms={r['comp_time']}")
PY
  done
}

for n in 50 400; do
  echo "== random-32-32-10, random-1, $n agents"
  run random-32-32-10.map 32 32 random-32-32-10-random-1.scen "$n"
done
echo "== warehouse-20-40-10-2-2, 10000agents-8, 1000 agents"
run warehouse-20-40-10-2-2.map 340 164 warehouse-20-40-10-2-2-10000agents-8.scen 1000
