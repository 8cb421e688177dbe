#!/usr/bin/env bash
# Builds the `scen` wheel: the Python module `scen._scen` (maturin, pyo3,
# crates/python) and the `scen` command in one wheel, as ruff's and uv's
# hold theirs. The command is the release build cargo made before
# (target/release/scen, from `cargo build --release` or `cargo test
# --release`): it goes into the wheel's scripts through the data folder
# (pyproject.toml), so pip puts it on PATH and it is never built twice.
# With `--check` the wheel is installed into a fresh virtual environment
# (with numpy, pytest and distributed from PyPI), the `scen` on PATH runs a scenario,
# and pytest runs tests/python/ against the installed module.
#
#   scripts/wheel.sh            # target/wheels/scen-VERSION-*.whl
#   scripts/wheel.sh --check    # ... then install it in a fresh venv and test it
#
# maturin comes from PATH, or from $MATURIN (`pip install maturin`).
set -euo pipefail
cd "$(dirname "$0")/.."

maturin="${MATURIN:-$(command -v maturin || true)}"
if [ -z "$maturin" ] || [ ! -x "$maturin" ]; then
  echo "error: maturin is not installed; install it with \`pip install maturin\` (or set MATURIN=/path/to/maturin)" >&2
  exit 2
fi
if [ ! -x target/release/scen ]; then
  echo "error: target/release/scen is missing; build it first with \`cargo build --release\`" >&2
  exit 2
fi

rm -rf target/wheels target/wheel-data
mkdir -p target/wheel-data/scripts
cp target/release/scen target/wheel-data/scripts/scen
# The module is an extension: it must not link libpython (pyo3 reads this).
PYO3_BUILD_EXTENSION_MODULE=1 "$maturin" build --release --out target/wheels --compatibility linux --auditwheel skip >&2
wheel=$(ls target/wheels/scen-*.whl)
echo "$wheel"

if [ "${1:-}" = "--check" ]; then
  venv="target/wheel-venv"
  rm -rf "$venv"
  python3 -m venv "$venv"
  # numpy (the module's), pytest, and Dask's distributed for the example
  # that spreads a bench over a local cluster (examples/dask/bench.py).
  "$venv/bin/pip" install --quiet --disable-pip-version-check "numpy>=1.21" "pytest==8.3.4" "distributed==2026.8.0"
  "$venv/bin/pip" install --quiet --disable-pip-version-check --no-index --no-deps "$wheel"
  # The `scen` pip installed, found on PATH as a user would find it.
  found=$(PATH="$PWD/$venv/bin:/usr/bin:/bin" command -v scen)
  [ "$found" = "$PWD/$venv/bin/scen" ] || { echo "error: pip did not put scen on PATH ($found)" >&2; exit 1; }
  version=$(PATH="$PWD/$venv/bin:/usr/bin:/bin" scen --version)
  expected="scen $(sed -n 's/^version = "\(.*\)"/\1/p' Cargo.toml | head -1)"
  [ "$version" = "$expected" ] || { echo "error: the wheel's scen says \`$version\`, expected \`$expected\`" >&2; exit 1; }
  (cd scenarios && PATH="$PWD/../$venv/bin:/usr/bin:/bin" scen run -q apartment_disk.scen)
  echo "ok: $wheel installs \`$version\` on PATH, and it runs scenarios/apartment_disk.scen" >&2
  # The module, as `import scen` from the installed wheel (not the sources:
  # pytest runs from tests/python, where python/ is not on the path).
  (cd tests/python && PATH="$PWD/../../$venv/bin:/usr/bin:/bin" "$PWD/../../$venv/bin/python" -m pytest -q -p no:cacheprovider .)
fi
