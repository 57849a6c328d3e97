"""FMPy run times of one model's FMUs built at --opt-level 0, 1 and 3
(`opt_level.sh` builds them): a 10 s run from q1, q2, q3 = 0.5, -0.4, 0.3,
relative tolerance 1e-6, output every 0.01 s, Model Exchange (CVode) and
Co-Simulation, three interleaved rounds; medians, and whether the levels'
results are bit for bit the same."""

from __future__ import annotations

import statistics
import sys
import time

import numpy as np
from fmpy import extract, simulate_fmu

LEVELS = (0, 1, 3)
KINDS = ("ModelExchange", "CoSimulation")


def main(work: str, name: str) -> None:
    dirs = {level: extract(f"{work}/{name}_O{level}.fmu") for level in LEVELS}
    times: dict[tuple[int, str], list[float]] = {(lv, k): [] for lv in LEVELS for k in KINDS}
    results = {}
    for _ in range(3):
        for level, unzipped in dirs.items():
            for kind in KINDS:
                start = time.perf_counter()
                results[(level, kind)] = simulate_fmu(
                    unzipped, validate=False, fmi_type=kind, stop_time=10.0,
                    output_interval=0.01, relative_tolerance=1e-6,
                    start_values={"q1": 0.5, "q2": -0.4, "q3": 0.3})
                times[(level, kind)].append(time.perf_counter() - start)
    for (level, kind), ts in times.items():
        print(f"{name} --opt-level {level} {kind}: median {statistics.median(ts):.3f} s "
              f"over {len(ts)} runs")
    for kind in KINDS:
        a, b = results[(0, kind)], results[(3, kind)]
        same = all(np.array_equal(a[n], b[n]) for n in a.dtype.names)
        print(f"{kind}: levels 0 and 3 bit for bit the same: {same}")


if __name__ == "__main__":
    main(sys.argv[1], sys.argv[2])
