#!/usr/bin/env bash
# Issue 41 item 4: PythonRobotics' SIPP and space-time A* on their own
# example arrangement beside scen's `sipp`, in one run (see
# scripts/pythonrobotics_sipp.py). Fetches PythonRobotics at the pinned
# commit into target/peers (or uses $PYTHONROBOTICS), numpy and matplotlib
# into a venv there, regenerates scenarios/time_pythonrobotics.scen and
# prints the table of BENCHMARKS.md ("sipp against PythonRobotics").
# Usage: scripts/bench_pythonrobotics_sipp.sh [--no-astar]
set -euo pipefail
here="$(cd "$(dirname "$0")/.." && pwd)"
pinned=b38c510e083d69a5755d98d0680bd50f3d9a91fa
peers="$here/target/peers"
pr="${PYTHONROBOTICS:-$peers/PythonRobotics}"
mkdir -p "$peers"
if ! [ -d "$pr/.git" ]; then
  git clone -q https://github.com/AtsushiSakai/PythonRobotics.git "$pr"
fi
git -C "$pr" checkout -q "$pinned"
if ! [ -x "$peers/venv/bin/python" ]; then
  python3 -m venv "$peers/venv"
  "$peers/venv/bin/pip" install -q numpy matplotlib
fi
cd "$here"
cargo build --release -q
"$peers/venv/bin/python" scripts/pythonrobotics_sipp.py --pythonrobotics "$pr" \
  --write scenarios/time_pythonrobotics.scen --scen target/release/scen "$@"
