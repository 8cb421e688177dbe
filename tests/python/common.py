"""What the Python tests share: where the repository and the installed
`scen` command are, and how two documents of the same input compare."""

import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]
SCENARIOS = ROOT / "scenarios"
# The `scen` command pip installed beside this Python.
SCEN = Path(sys.executable).parent / "scen"

# What varies between two runs of the same input: the timings.
TIMINGS = {"time_ms", "simplify_ms"}


def without_timings(v):
    """A JSON document without its timings (metrics, and the values checks
    read of them), for comparing two runs."""
    if isinstance(v, dict):
        return {k: without_timings(x) for k, x in v.items() if k not in TIMINGS and not k.endswith(".time_ms")}
    if isinstance(v, list):
        return [without_timings(x) for x in v]
    return v
