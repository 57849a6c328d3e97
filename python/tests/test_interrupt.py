"""Ctrl-C (SIGINT) during native work: a simulation, a study run in memory
and a study run into a folder stop soon after the signal and raise
``KeyboardInterrupt``; a study folder keeps only whole shards, and the
study resumed there equals the study run without a stop."""

from __future__ import annotations

import os
import signal
import threading
import time
from collections.abc import Iterator
from pathlib import Path
from typing import Callable

import pytest

import autosim

Load = Callable[..., autosim.Model]
PENDULUM = "examples/models/pendulum.sim"


@pytest.fixture(autouse=True)
def python_handler() -> Iterator[None]:
    """Python's own SIGINT handler (raises ``KeyboardInterrupt``), as in a
    script or a notebook, whatever the test runner set."""
    before = signal.signal(signal.SIGINT, signal.default_int_handler)
    yield
    signal.signal(signal.SIGINT, before)


def interrupt_when(ready: Callable[[], bool], sent: list[float]) -> threading.Thread:
    """A thread that sends this process SIGINT (what Ctrl-C sends) once
    ``ready()`` says so, noting the time in ``sent``."""

    def send() -> None:
        deadline = time.monotonic() + 60
        while not ready() and time.monotonic() < deadline:
            time.sleep(0.01)
        sent.append(time.monotonic())
        os.kill(os.getpid(), signal.SIGINT)

    thread = threading.Thread(target=send, daemon=True)
    thread.start()
    return thread


def after(seconds: float) -> Callable[[], bool]:
    start = time.monotonic()
    return lambda: time.monotonic() - start >= seconds


def slow_study(model: autosim.Model, cases: int) -> autosim.Study:
    """``cases`` pendulum runs of about 20 ms each (RK4, 5 s at 20 µs)."""
    table = autosim.Cases().random(cases, seed=11, q=autosim.uniform(-1.0, 1.0), m=autosim.uniform(0.5, 2.0))
    keep = autosim.Keep().final_state().statistic("height", "max")
    return model.study(table, keep, t_end=5.0, h=2e-5, method="rk4")


def test_ctrl_c_stops_a_long_simulation(load_model: Load) -> None:
    model = load_model(PENDULUM)
    sent: list[float] = []
    interrupt_when(after(0.3), sent)
    with pytest.raises(KeyboardInterrupt):
        # 1e10 steps: hours, were it not stopped.
        model.simulate(1e5, method="rk4", h=1e-5, t_eval=[0.0, 1e5], max_steps=10**12)
    assert sent and time.monotonic() - sent[0] < 1.0, "stopped within a second of the signal"
    assert model.simulate(1.0, method="rk4", h=1e-3).t[-1] == 1.0, "the model runs again"


def test_ctrl_c_stops_a_long_study_run(load_model: Load) -> None:
    study = slow_study(load_model(PENDULUM), 20_000)  # minutes on every core
    sent: list[float] = []
    interrupt_when(after(0.3), sent)
    with pytest.raises(KeyboardInterrupt):
        study.run(progress=False)
    assert sent and time.monotonic() - sent[0] < 1.0, "stopped within a second of the signal"


def test_ctrl_c_stops_run_in_between_shards_and_the_study_resumes(load_model: Load, tmp_path: Path) -> None:
    study = slow_study(load_model(PENDULUM), 120)
    folder = tmp_path / "study"

    def shards() -> list[Path]:
        return sorted(folder.glob("part-*.csv"))

    sent: list[float] = []
    interrupt_when(lambda: len(shards()) >= 1, sent)
    with pytest.raises(KeyboardInterrupt):
        study.run_in(folder, shard_size=10, threads=1, progress=False)
    assert sent and time.monotonic() - sent[0] < 1.0, "stopped within a second of the signal"
    written = len(shards())
    assert 1 <= written < 12, f"{written} shards: the run stopped between the first and the last"
    assert not list(folder.glob("*.tmp")), "no shard half written"
    summary = study.run_in(folder, shard_size=10, progress=False)
    assert (summary.skipped, summary.ran) == (10 * written, 120 - 10 * written)
    assert study.read(folder) == study.run(progress=False)
