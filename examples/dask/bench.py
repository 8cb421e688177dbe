"""A bench spread over a Dask cluster: each task runs one shard of the
bench in its worker (the `scen` Python module, the GIL released while it
plans), returns the part's text, and the merge here gives the table one
machine would have printed.

    pip install scen-*.whl "distributed==2026.8.0"
    python examples/dask/bench.py [SCENARIO] [N] [METRICS]

With no arguments it runs scenarios/features/bench_seeds.scen in 4 shards
on a local cluster of 2 worker processes; METRICS (`length,expanded`)
chooses the table's columns, as `scen bench --metrics` does. On a real cluster, give
`Client` the scheduler's address instead of a `LocalCluster`; the workers
need the scenario file at the same path (a shared folder, or the same
checkout) and the wheel installed.
"""

import sys
import tempfile
from pathlib import Path

from dask.distributed import Client, LocalCluster

import scen


def shard(path, k, n):
    """Shard k of n of the scenario's benches, in a worker: the part's text."""
    return scen.load(path).bench_part(k, n)


def main():
    path = sys.argv[1] if len(sys.argv) > 1 else "scenarios/features/bench_seeds.scen"
    n = int(sys.argv[2]) if len(sys.argv) > 2 else 4
    metrics = sys.argv[3].split(",") if len(sys.argv) > 3 else None
    with LocalCluster(n_workers=2, threads_per_worker=1, processes=True, dashboard_address=None) as cluster:
        with Client(cluster) as client:
            futures = [client.submit(shard, path, k, n, pure=False) for k in range(1, n + 1)]
            texts = client.gather(futures)
    with tempfile.TemporaryDirectory() as parts:
        files = []
        for k, text in enumerate(texts, start=1):
            part = Path(parts) / f"part-{k}.jsonl"
            part.write_text(text)
            files.append(part)
        report = scen.bench_merge(files)
    print(report.bench_table(metrics), end="")
    print(f"{report.passed} passed, {report.failed} failed")
    return 0 if report.failed == 0 else 1


if __name__ == "__main__":
    sys.exit(main())
