#!/usr/bin/env bash
# Issue 43 item 4: scen's `lacam` beside LaCAM3 (Kei18/lacam3, MIT, pinned
# commit) on the same MovingAI instances, in one run: random-32-32-10 with
# the first 50 and 400 rows of random-1, and warehouse-20-40-10-2-2 with
# the first 1,000 rows of its 10000agents-8 scenario. Each solver runs with
# seeds 1 to 5; prints one line per instance and solver: solved runs, the
# median sum of costs (and the range), the lower bound, the median makespan
# and milliseconds. The benchmark files are read from ../shared/data/movingai
# (copied into a temporary folder beside a scenario that reads them).
#
# LaCAM3 is built from $LACAM3 (a folder with its main.cpp, lacam3/ and
# argparse/include, see ../shared/peers/lacam3.md), default target/peers/lacam3.
# Both run on one thread: LaCAM3 plain (--no-star --no-multi-thread: its
# first solution, with scatter, swap and ten PIBT runs), and vanilla LaCAM
# (--no-all); scen's `lacam` as it comes (vanilla LaCAM) and with LaCAM3's
# techniques (`spread yes swap yes pibt_runs 10`).
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
  {
    echo "world { bounds (0, 0) ($w, $h) grid G \"$map\" cell 1 }"
    echo "team T point from \"$scen\" agents $n"
    for seed in 1 2 3 4 5; do
      echo "plan plain$seed lacam T { seed $seed limit time 60s }"
      echo "plan suo$seed lacam T { spread yes swap yes pibt_runs 10 seed $seed limit time 60s }"
    done
  } > "$work/b.scen"
  "$here/target/release/scen" run "$work/b.scen" --json > "$work/scen.json"
  for flags in "--no-star --no-multi-thread" "--no-all"; do
    for seed in 1 2 3 4 5; do
      "$bin" -m "$work/$map" -i "$work/$scen" -N "$n" -t 60 -s "$seed" -o "$work/r-${flags// /}-$seed.txt" $flags -v 0 > /dev/null
    done
  done
  python3 - "$work" <<'PY'
import glob, json, statistics, sys
work = sys.argv[1]
plans = json.load(open(f"{work}/scen.json"))["plans"]
def line(name, runs):
    solved = [r for r in runs if r["solved"]]
    socs = sorted(r["soc"] for r in solved)
    med = lambda xs: statistics.median(xs) if xs else float("nan")
    print(f"{name:40} solved={len(solved)}/{len(runs)} soc={med(socs):.0f} [{socs[0] if socs else '-'}, {socs[-1] if socs else '-'}] "
          f"soc_lb={runs[0]['lb']} makespan={med([r['makespan'] for r in solved]):.0f} ms={med([r['ms'] for r in runs]):.0f}")
for prefix, name in (("plain", "scen lacam"), ("suo", "scen lacam spread swap pibt_runs 10")):
    runs = []
    for k, v in plans.items():
        if k.rstrip("0123456789") == prefix:
            m = v["metrics"]
            runs.append({"solved": m["found"] and m["collision_free"], "soc": m["sum_of_costs"], "lb": int(m["soc_lower_bound"]),
                         "makespan": m["makespan"], "ms": m["time_ms"]})
    line(name, runs)
for flags, name in (("--no-star--no-multi-thread", "lacam3 --no-star --no-multi-thread"), ("--no-all", "lacam3 --no-all")):
    runs = []
    for f in sorted(glob.glob(f"{work}/r-{flags}-*.txt")):
        r = dict(l.strip().split("=", 1) for l in open(f) if "=" in l and l.split("=")[0] in
                 ("solved", "soc", "soc_lb", "makespan", "comp_time"))
        runs.append({"solved": r["solved"] == "1", "soc": int(r["soc"]), "lb": int(r["soc_lb"]),
                     "makespan": int(r["makespan"]), "ms": float(r["comp_time"])})
    line(name, runs)
PY
}

for n in 50 400; do
  echo "== random-32-32-10, random-1, $n agents"
  run random-32-32-10.map 32 32 random-32-32-10-random-1.scen "$n"
done
echo "== warehouse-20-40-10-2-2, 10000agents-8, 1000 agents"
run warehouse-20-40-10-2-2.map 340 164 warehouse-20-40-10-2-2-10000agents-8.scen 1000
