#!/usr/bin/env bash
# Builds the `scen` wheel (maturin, `bindings = "bin"`: the wheel holds the
# `scen` executable, as ruff's and uv's do) from the release build, and with
# `--check` installs it into a fresh virtual environment and runs the `scen`
# that pip put on PATH.
#
#   scripts/wheel.sh            # target/wheels/scen-VERSION-*.whl
#   scripts/wheel.sh --check    # ... then pip install it in a fresh venv and try it
#
# maturin comes from PATH, or from $MATURIN (`pip install maturin`). The
# wheel is built with the same profile and features as `cargo build
# --release`, so after that build (or `cargo test --release`) maturin finds
# the crate up to date and only packages it.
set -euo pipefail
cd "$(dirname "$0")/.."

maturin="${MATURIN:-$(command -v maturin || true)}"
if [ -z "$maturin" ] || [ ! -x "$maturin" ]; then
  echo "error: maturin is not installed; install it with \`pip install maturin\` (or set MATURIN=/path/to/maturin)" >&2
  exit 2
fi

rm -rf target/wheels
"$maturin" build --release --out target/wheels --compatibility linux --auditwheel skip >&2
wheel=$(ls target/wheels/scen-*.whl)
echo "$wheel"

if [ "${1:-}" = "--check" ]; then
  venv="target/wheel-venv"
  rm -rf "$venv"
  python3 -m venv "$venv"
  "$venv/bin/pip" install --quiet --disable-pip-version-check --no-index "$wheel"
  # The `scen` pip installed, found on PATH as a user would find it.
  found=$(PATH="$PWD/$venv/bin:/usr/bin:/bin" command -v scen)
  [ "$found" = "$PWD/$venv/bin/scen" ] || { echo "error: pip did not put scen on PATH ($found)" >&2; exit 1; }
  version=$(PATH="$PWD/$venv/bin:/usr/bin:/bin" scen --version)
  expected="scen $(sed -n 's/^version = "\(.*\)"/\1/p' Cargo.toml | head -1)"
  [ "$version" = "$expected" ] || { echo "error: the wheel's scen says \`$version\`, expected \`$expected\`" >&2; exit 1; }
  (cd scenarios && PATH="$PWD/../$venv/bin:/usr/bin:/bin" scen run -q apartment_disk.scen)
  echo "ok: $wheel installs \`$version\` on PATH, and it runs scenarios/apartment_disk.scen" >&2
fi
