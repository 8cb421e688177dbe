#!/usr/bin/env python3
"""Nothing else moves (issue 40 item 5): every scenario's `scen run --json`
is the same under two builds of scen, timings aside.

    python3 scripts/json_identity.py OLD_SCEN NEW_SCEN [--sample K] [FILE.scen...]

Default files: every scenario under scenarios/ (the `_` includes left out). Timings are
the metrics whose names end in `_ms`. Prints each scenario that differs
with the first differing place; exits 1 when any does.
"""
import json
import subprocess
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent


def strip_times(v):
    if isinstance(v, dict):
        return {k: strip_times(x) for k, x in v.items() if not k.endswith("_ms")}
    if isinstance(v, list):
        return [strip_times(x) for x in v]
    return v


def run(scen, file, extra):
    out = subprocess.run([scen, "run", str(file), "--json", *extra], capture_output=True, text=True)
    try:
        doc = json.loads(out.stdout) if out.stdout.strip() else None
    except json.JSONDecodeError:
        doc = out.stdout
    return out.returncode, strip_times(doc), out.stderr


def first_difference(a, b, where="$"):
    if type(a) is not type(b):
        return f"{where}: {a!r:.80} vs {b!r:.80}"
    if isinstance(a, dict):
        for k in sorted(set(a) | set(b)):
            if k not in a or k not in b:
                return f"{where}.{k}: only in {'new' if k in b else 'old'}"
            d = first_difference(a[k], b[k], f"{where}.{k}")
            if d:
                return d
        return None
    if isinstance(a, list):
        if len(a) != len(b):
            return f"{where}: {len(a)} vs {len(b)} items"
        for i, (x, y) in enumerate(zip(a, b)):
            d = first_difference(x, y, f"{where}[{i}]")
            if d:
                return d
        return None
    return None if a == b else f"{where}: {a!r:.80} vs {b!r:.80}"


def main():
    if len(sys.argv) < 3:
        print(__doc__)
        return 2
    old, new, rest = sys.argv[1], sys.argv[2], sys.argv[3:]
    extra = []
    if rest[:1] == ["--sample"]:
        extra, rest = rest[:2], rest[2:]
    files = [Path(f) for f in rest] or sorted(
        f for f in (ROOT / "scenarios").rglob("*.scen")
        if not f.name.startswith("_")
        # MovingAI's rows of a team (`version 1` ...) are data, not scenarios.
        and f.read_text().split(None, 1)[:1] != ["version"]
    )
    differ = 0
    for f in files:
        a, b = run(old, f, extra), run(new, f, extra)
        d = None
        if a[0] != b[0]:
            d = f"exit {a[0]} vs {b[0]}"
        elif a[1] is None and b[1] is None:
            d = None if a[2] == b[2] else "stderr differs"
        else:
            d = first_difference(a[1], b[1])
        if d:
            differ += 1
            print(f"DIFFERS {f.relative_to(ROOT) if f.is_absolute() else f}: {d}")
    print(f"{len(files) - differ} of {len(files)} scenarios give the same JSON (timings aside)")
    return 1 if differ else 0


if __name__ == "__main__":
    sys.exit(main())
