"""Throughput of a study from Python and through Dask, beside the Rust
numbers of `cargo run --release --example study_throughput`.

    target/python-env/bin/python bench/python/study.py [ROUNDS [CASES]]

The study is the Rust example's: the pendulum, CASES (default 10^4)
random draws of angle and mass, RK4 for 2 s at h = 1 ms, keeping the
final state. Measured, interleaved over ROUNDS (default 5) rounds,
medians printed:

- `study.run(threads=1)` and `study.run()` (every core): cases/s from
  Python; the per-case overhead of Python is the difference of the time
  per case against the Rust example's serial time per case (run the
  example in the same session: its numbers are printed beside);
- `study.run_dask(client, chunk_size=c)` on a LocalCluster of 2 worker
  processes of 1 thread each, for several chunk sizes: the overhead per
  chunk is (Dask's time - the all-cores Python time) / chunks.

Every result is checked equal, bit for bit, to the serial one.
"""

from __future__ import annotations

import statistics
import subprocess
import sys
import time
from pathlib import Path

import autosim

REPO = Path(__file__).resolve().parents[2]


def rust_numbers() -> str:
    done = subprocess.run(
        ["cargo", "run", "--release", "-q", "--example", "study_throughput", "--", "3"],
        cwd=REPO,
        capture_output=True,
        text=True,
    )
    return done.stdout.strip() or done.stderr.strip()


def main() -> None:
    rounds = int(sys.argv[1]) if len(sys.argv) > 1 else 5
    count = int(sys.argv[2]) if len(sys.argv) > 2 else 10_000
    from dask.distributed import Client, LocalCluster

    model = autosim.load(REPO / "examples/models/pendulum.sim", quiet=True)
    cases = autosim.Cases().random(count, 3, q=autosim.uniform(-2.0, 2.0), m=autosim.uniform(0.5, 2.0))
    study = model.study(
        cases, autosim.Keep().final_state(), t_end=2.0, h=0.001, output_interval=0.1, method="rk4"
    )
    chunk_sizes = [count // 2, count // 10, count // 100]
    times: dict[str, list[float]] = {}

    def timed(name: str, run) -> autosim.StudyResults:  # type: ignore[no-untyped-def]
        start = time.perf_counter()
        out = run()
        times.setdefault(name, []).append(time.perf_counter() - start)
        return out

    with (
        LocalCluster(n_workers=2, threads_per_worker=1, host="127.0.0.1", dashboard_address=None) as cluster,
        Client(cluster) as client,
    ):
        study.run_dask(client, chunk_size=count)  # warm the workers (model loaded)
        for _ in range(rounds):
            serial = timed("serial", lambda: study.run(threads=1, progress=False))
            assert timed("all cores", lambda: study.run(progress=False)) == serial
            for c in chunk_sizes:
                assert timed(f"dask {c}", lambda: study.run_dask(client, chunk_size=c)) == serial
    median = {k: statistics.median(v) for k, v in times.items()}
    print(f"{count} pendulum cases (RK4, 2000 steps), medians of {rounds} interleaved rounds:")
    for name, seconds in median.items():
        print(f"  {name:>14}: {count / seconds:>9.0f} cases/s ({seconds * 1e3:.0f} ms)")
    for c in chunk_sizes:
        chunks = -(-count // c)
        overhead = (median[f"dask {c}"] - median["all cores"]) / chunks
        print(f"  Dask, {chunks:>4} chunks of {c}: {overhead * 1e3:.2f} ms per chunk over the all-cores call")
    print("Rust (cargo run --release --example study_throughput -- 3):")
    print("  " + rust_numbers().replace("\n", "\n  "))


if __name__ == "__main__":
    main()
