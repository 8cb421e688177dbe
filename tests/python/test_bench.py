"""Benches from Python: `Scenario.bench` is `scen bench`, its shards
(`bench_part`) merge (`scen.bench_merge`) into the same report, and the
Dask example spreads one over a local cluster."""

import contextlib
import json
import os
import subprocess
import sys

import pytest

import scen

from common import ROOT, SCEN, without_timings

BENCH = "scenarios/features/bench_seeds.scen"


# The table's columns without the timings (as tests/examples.rs).
METRICS = ["length", "expanded", "steps", "clearance"]


@pytest.fixture
def at_root():
    with contextlib.chdir(ROOT):
        yield


def test_bench_is_scen_bench_json(at_root):
    sc = scen.load(BENCH)
    assert sc.benches == ["seeds"]
    report = sc.bench()
    cli = subprocess.run([str(SCEN), "bench", "--json", BENCH], capture_output=True, text=True)
    assert cli.returncode == 0, cli.stderr
    assert without_timings(json.loads(report.to_json())) == without_timings(json.loads(cli.stdout))
    runs = report.bench_runs
    assert len(runs) == 40 and {r["bench"] for r in runs} == {"seeds"}
    assert sorted(r["seed"] for r in runs if r["config"] == {"jump": 4}) == list(range(20))
    assert all(r["metrics"]["found"] for r in runs)
    assert report.failed == 0 and report.passed >= 1
    table = report.bench_table()
    assert "seeds" in table and "walk" in table


def test_shards_merge_into_the_unsharded_report(at_root, tmp_path):
    sc = scen.load(BENCH)
    whole = sc.bench()
    files = []
    for k in range(1, 4):
        text = sc.bench_part(k, 3)
        header = json.loads(text.splitlines()[0])
        assert header["k"] == k and header["n"] == 3
        f = tmp_path / f"part-{k}.jsonl"
        f.write_text(text)
        files.append(f)
    merged = scen.bench_merge(files)
    assert without_timings(json.loads(merged.to_json())) == without_timings(json.loads(whole.to_json()))
    # The command merges the module's parts too.
    cli = subprocess.run([str(SCEN), "bench", "merge", "--json", *map(str, files)], capture_output=True, text=True)
    assert cli.returncode == 0, cli.stderr
    assert without_timings(json.loads(cli.stdout)) == without_timings(json.loads(whole.to_json()))
    # A missing part is refused, as by the command.
    with pytest.raises(scen.ScenError) as info:
        scen.bench_merge(files[:2])
    assert info.value.diagnostics[0]["code"] == "scen::python::bad_bench"
    assert "missing" in str(info.value)


def test_bad_benches_raise_scen_error(at_root):
    sc = scen.load(BENCH)
    for call in (
        lambda: sc.bench(["no_such_bench"]),
        lambda: sc.bench_part(0, 3),
        lambda: sc.bench_part(4, 3),
        lambda: sc.bench_part(1, 1000),
        lambda: sc.bench(runs=0),
        lambda: scen.load("scenarios/apartment_disk.scen").bench(),
    ):
        with pytest.raises(scen.ScenError) as info:
            call()
        assert info.value.diagnostics[0]["code"] == "scen::python::bad_bench", str(info.value)


def test_the_dask_example_gives_the_one_machine_table(at_root):
    try:
        import distributed  # noqa: F401
    except ImportError:
        if os.environ.get("CI") == "true":
            pytest.fail("distributed is not installed (scripts/wheel.sh --check installs it)")
        pytest.skip("the Dask example needs `pip install distributed==2026.8.0`")
    out = subprocess.run(
        [sys.executable, "examples/dask/bench.py", BENCH, "4", ",".join(METRICS)],
        capture_output=True,
        text=True,
        timeout=600,
    )
    assert out.returncode == 0, out.stderr
    whole = scen.load(BENCH).bench()
    expected = whole.bench_table(METRICS) + f"{whole.passed} passed, {whole.failed} failed\n"
    assert out.stdout == expected
    # And the command's own table of the same bench.
    cli = subprocess.run([str(SCEN), "bench", BENCH, "--metrics", ",".join(METRICS)], capture_output=True, text=True)
    assert cli.returncode == 0, cli.stderr
    assert cli.stdout == whole.bench_table(METRICS)
