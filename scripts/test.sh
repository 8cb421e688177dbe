#!/usr/bin/env bash
# Runs the whole test suite on a fresh machine: installs the Rerun viewer
# (rerun-sdk==0.36.3, whose `rerun` binary the .rrd tests use), OMPL's
# Python package (ompl==2.0.1, for its benchmark statistics script) and
# maturin (the wheel) into a virtual environment under target/, then runs
# `cargo test --release` (every crate but the Python module's, whose tests
# are pytest's), builds the wheel (the module, and the `scen` that release
# build made) and installs it into a fresh venv with numpy and pytest, where
# tests/python/ runs (scripts/wheel.sh --check), then the editor support's
# tests (editors/test.sh: Node.js; npm installs the pinned test tools into
# editors/node_modules).
set -euo pipefail
cd "$(dirname "$0")/.."

venv="target/rerun-venv"
if [ ! -x "$venv/bin/rerun" ] || [ ! -x "$venv/bin/ompl_benchmark_statistics" ] || [ ! -x "$venv/bin/maturin" ]; then
  mkdir -p target
  python3 -m venv "$venv"
  # The Rerun viewer (for the .rrd tests) and OMPL's Python package, whose
  # ompl_benchmark_statistics turns `scen bench --ompl-log` into the
  # database Planner Arena reads (tests/bench.rs).
  # maturin builds the wheel: the Python module and the `scen` binary
  # (scripts/wheel.sh).
  "$venv/bin/pip" install --quiet --disable-pip-version-check "rerun-sdk==0.36.3" "ompl==2.0.1" "maturin==1.16.0"
fi
"$venv/bin/rerun" analytics disable >/dev/null 2>&1 || true
export PATH="$PWD/$venv/bin:$PATH"
export SCEN_RERUN="$PWD/$venv/bin/rerun"
export SCEN_OMPL_STATS="$PWD/$venv/bin/ompl_benchmark_statistics"

# Property tests draw from a fixed seed here, so that a CI run is
# reproducible; unset PROPTEST_RNG_SEED (or set another) to explore new cases.
export PROPTEST_RNG_SEED="${PROPTEST_RNG_SEED:-20261122}"

cargo test --release --workspace --exclude scen-python --no-fail-fast "$@"

# The wheel: maturin builds the module (crates/python: on scen-runner, without
# the viewer, so no Rerun SDK is built again) and packages the `scen` that
# cargo test just built; installed into a fresh venv, the `scen` pip puts on
# PATH must run a scenario, and pytest runs tests/python/ on `import scen`.
MATURIN="$PWD/$venv/bin/maturin" bash scripts/wheel.sh --check

# The VS Code grammar and the Vim syntax (after cargo test, which built
# target/release/scen for the problem matcher's test).
SCEN="$PWD/target/release/scen" bash editors/test.sh

# The committed scenarios (the suite, the benches', the manual's examples,
# the falsified regression files) are in the canonical layout (`scen fmt`;
# prints the files that would change).
"$PWD/target/release/scen" fmt --check scenarios/ benches/ docs/examples/ tests/falsified/ examples/

# The scenario suite as a user runs it (also run inside the tests above);
# it ends with the line `N passed, M failed`. The binary cargo test built:
# `cargo run` would build the dependencies again without the features the
# dev-dependencies unify into them.
"$PWD/target/release/scen" test scenarios/
