#!/usr/bin/env bash
# RRT* on a point robot among 30 random convex polygons: the cost after
# 50 000 iterations against the exact shortest length (the `roadmap`
# planner's), plain and informed, for world seeds 1..N (default 10).
# Usage: scripts/bench_rrt_star_polygons.sh SCEN [N]. Figures: BENCHMARKS.md.
set -euo pipefail
scen="$1"; n="${2:-10}"
tmp="$(mktemp -d)"; trap 'rm -rf "$tmp"' EXIT
for seed in $(seq 1 "$n"); do
  python3 - "$seed" > "$tmp/w.scen" <<'PY'
import math, random, sys
seed = int(sys.argv[1]); rng = random.Random(seed)
def hull(ps):
    ps = sorted(ps)
    def half(pts):
        h = []
        for p in pts:
            while len(h) >= 2 and (h[-1][0]-h[-2][0])*(p[1]-h[-2][1]) - (h[-1][1]-h[-2][1])*(p[0]-h[-2][0]) <= 0:
                h.pop()
            h.append(p)
        return h
    return half(ps)[:-1] + half(ps[::-1])[:-1]
print(f'scenario "RRT* among 30 random convex polygons, world {seed}"')
print("world {\n  bounds (0, 0) (30, 30)")
made = 0
while made < 30:
    cx, cy, r = rng.uniform(2, 28), rng.uniform(2, 28), rng.uniform(0.8, 2.5)
    if math.hypot(cx - 1, cy - 1) < r + 1.5 or math.hypot(cx - 29, cy - 29) < r + 1.5:
        continue
    pts = [(round(cx + r * math.cos(a), 3), round(cy + r * math.sin(a), 3))
           for a in sorted(rng.uniform(0, 2 * math.pi) for _ in range(6))]
    h = hull(pts)
    if len(h) < 3:
        continue
    print("  polygon [" + ", ".join(f"({x}, {y})" for x, y in h) + "]")
    made += 1
print("}\nrobot dot point")
print("plan exact roadmap dot { start (1, 1) goal (29, 29) }")
print(f"plan star rrt_star dot {{ start (1, 1) goal (29, 29) seed {seed} limit iterations 50000 }}")
print(f"plan informed rrt_star dot {{ start (1, 1) goal (29, 29) seed {seed} limit iterations 50000 informed yes }}")
PY
  "$scen" run --json "$tmp/w.scen" | python3 -c "
import json, sys
p = json.load(sys.stdin)['plans']
exact = p['exact']['metrics']['length']
for name in ('star', 'informed'):
    m = p[name]['metrics']
    print(name, $seed, f'{exact:.4f}', f\"{m['cost']:.4f}\", f\"{(m['cost'] / exact - 1) * 100:.2f}%\", f\"{m['time_ms'] / 1000:.1f}s\")
"
done
