#!/usr/bin/env python3
"""Import circles between the crate's modules (issue 40: at most one, the
parser's own).

Each file under src/ and crates/*/src/ is a module of its crate; an edge A -> B when A names a path into B
(`use crate::x::y`, `crate::x::y::f(..)`, `super::y`). A module naming its
own ancestor or descendant is nesting, not an import, and is left out; so
is an inline `#[cfg(test)] mod tests`, a child module of its own.
Prints each circle (a strongly connected component of more than one module)
and exits 1 when there are more than `--allow` of them.
"""
import argparse
import re
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
SRC = ROOT / "src"


def module_of(src: Path, path: Path) -> tuple:
    """A module as (crate, its path...): `crate::` paths resolve within
    their own crate."""
    rel = path.relative_to(src).with_suffix("")
    parts = list(rel.parts)
    if parts[-1] in ("mod", "lib", "main"):
        parts = parts[:-1]
    crate = "scen" if src == SRC else src.parent.name
    return (crate, *parts)


def strip_comments(text: str) -> str:
    text = re.sub(r"/\*.*?\*/", "", text, flags=re.S)
    return "\n".join(re.sub(r"//.*", "", line) for line in text.splitlines())


def strip_test_modules(text: str) -> str:
    """An inline `#[cfg(test)] mod NAME { ... }` is a child module of its
    own: what it imports is not the file's module's import."""
    lines = text.splitlines()
    out, skip = [], False
    for i, line in enumerate(lines):
        if skip:
            if line == "}":
                skip = False
            continue
        if re.match(r"^mod \w+ \{$", line) and i > 0 and lines[i - 1].strip() == "#[cfg(test)]":
            skip = True
            continue
        out.append(line)
    return "\n".join(out)


def paths_in(text: str):
    """Every `crate::a::b` and `super::a` path, with `use` groups expanded
    one level (`use crate::a::{b, c::d}`)."""
    for m in re.finditer(r"\b(crate|super(?:::super)*)((?:::[A-Za-z_][A-Za-z0-9_]*)*)(::\{([^}]*)\})?", text):
        head, tail, group = m.group(1), m.group(2), m.group(4)
        base = [head] + [p for p in tail.split("::") if p]
        if group is None:
            yield base
        else:
            for item in group.split(","):
                item = item.strip().split(" as ")[0]
                if item:
                    yield base + [p for p in item.split("::") if p]


def main() -> int:
    ap = argparse.ArgumentParser()
    ap.add_argument("--allow", type=int, default=1)
    args = ap.parse_args()
    roots = [SRC, *sorted((ROOT / "crates").glob("*/src"))]
    files = {module_of(src, p): p for src in roots for p in src.rglob("*.rs")}
    modules = set(files)
    edges = {m: set() for m in modules}
    for m, p in files.items():
        # A file `a/b.rs` or `a/b/mod.rs` is module (a, b); `super` is (a,).
        for path in paths_in(strip_test_modules(strip_comments(p.read_text()))):
            if path[0] == "crate":
                resolved = [m[0]]
                rest = path[1:]
            else:
                ups = path[0].count("super")
                if ups > len(m) - 1:
                    continue
                resolved = list(m[: len(m) - ups])
                rest = path[1:]
            # The longest prefix naming a module.
            target = tuple(resolved)
            for part in rest:
                if target + (part,) in modules:
                    target = target + (part,)
                else:
                    break
            if target == m or len(target) <= 1 or m[: len(target)] == target or target[: len(m)] == m:
                continue
            edges[m].add(target)
    # Tarjan's strongly connected components.
    index, low, stack, on, sccs = {}, {}, [], set(), []
    counter = [0]

    def visit(v):
        index[v] = low[v] = counter[0]
        counter[0] += 1
        stack.append(v)
        on.add(v)
        for w in sorted(edges[v]):
            if w not in index:
                visit(w)
                low[v] = min(low[v], low[w])
            elif w in on:
                low[v] = min(low[v], index[w])
        if low[v] == index[v]:
            comp = []
            while True:
                w = stack.pop()
                on.discard(w)
                comp.append(w)
                if w == v:
                    break
            if len(comp) > 1:
                sccs.append(sorted(comp))

    sys.setrecursionlimit(10000)
    for v in sorted(modules):
        if v not in index:
            visit(v)
    for comp in sccs:
        print("circle: " + " <-> ".join("::".join(c[1:]) + f" ({c[0]})" for c in comp))
    print(f"{len(sccs)} circle(s), {args.allow} allowed")
    return 1 if len(sccs) > args.allow else 0


if __name__ == "__main__":
    sys.exit(main())
