#!/usr/bin/env bash
# Issue 23's steering target with OMPL's side in the same run: OMPL 1.5's
# C++ ReedsSheppStateSpace and DubinsStateSpace (Debian's libompl-dev,
# installed with apt-get when missing, as ../shared/peers/build.sh does) on
# benches/steer.rs's 10,000 pairs (scripts/ompl_steer.cpp), then scen's
# `cargo bench --bench steer` lengths on the same pairs. Both sides print the
# lengths of one pass over the pairs, which agree to rounding.
#
# Usage: scripts/bench_ompl_steer.sh [PASSES]   (OMPL's passes, default 100)
# Figures: BENCHMARKS.md, "Steering functions".
set -euo pipefail
here="$(cd "$(dirname "$0")/.." && pwd)"
if ! [ -f /usr/include/ompl-1.5/ompl/base/spaces/ReedsSheppStateSpace.h ]; then
  apt-get update -qq && apt-get install -y -qq libompl-dev g++ >/dev/null
fi
tmp="$(mktemp -d)"; trap 'rm -rf "$tmp"' EXIT
g++ -O2 -std=c++17 -I/usr/include/ompl-1.5 -I/usr/include/eigen3 \
  "$here/scripts/ompl_steer.cpp" -o "$tmp/ompl_steer" -lompl
"$tmp/ompl_steer" "${1:-100}"
cd "$here"
cargo bench --no-default-features --bench steer -- _length
