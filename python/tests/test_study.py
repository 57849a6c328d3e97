"""Studies from Python (autosim.Study): the runtime's study of the model,
one call with the GIL released, its results as NumPy arrays and pandas;
failed cases; shards on disk; and the same bits serially, on threads, in
chunks, through a Dask LocalCluster and through a loopback scheduler with
worker processes (which get the model from its wheel, with no compiler).

The reference is the same study run in Rust by ``tests/python.rs``
(serially and on 2 threads) and written to the folder in
``AUTOSIM_STUDY_REFERENCE`` (``cargo test`` sets it)."""

from __future__ import annotations

import os
import pickle
import subprocess
import sys
import time
from pathlib import Path
from typing import Callable

import numpy as np
import pytest
from conftest import install_model_wheel

import autosim

Load = Callable[..., autosim.Model]


def reference_study(model: autosim.Model) -> autosim.Study:
    """The study `reference_study()` of tests/python.rs builds in Rust."""
    cases = (
        autosim.Cases()
        .grid("torque", [0.0, 0.5])
        .random(
            40,
            2026,
            m=autosim.uniform(0.5, 2.0),
            L=autosim.normal(0.7, 0.05),
            q=autosim.uniform(-1.0, 1.0),
        )
    )
    keep = autosim.Keep().final_state().at([1.0], ["height"]).statistic("height", "max").history(["q"])
    return model.study(
        cases, keep, t_end=2.0, h=0.01, output_interval=0.1, method="dopri", rtol=1e-9, atol=1e-12
    )


@pytest.fixture(scope="module")
def study(load_model: Load) -> autosim.Study:
    return reference_study(load_model("examples/models/pendulum.sim"))


@pytest.fixture(scope="module")
def rust_results(study: autosim.Study) -> autosim.StudyResults:
    """The study as Rust ran it (serially; equal to 2 threads there)."""
    folder = os.environ.get("AUTOSIM_STUDY_REFERENCE")
    if not folder:
        pytest.skip("AUTOSIM_STUDY_REFERENCE is not set (cargo test --test python sets it)")
    return study.read(folder)


@pytest.mark.parametrize("method", ["rk4", "abm4", "dopri"])
def test_a_lanes_model_runs_a_parameter_sweep_in_lockstep_with_the_bits_of_one_case_at_a_time(
    load_model: Load, repo: Path, method: str
) -> None:
    """With ``lanes=True`` a study runs four cases per call of the lanes
    function, each lane with its own case's parameters, input and initial
    state (with ABM4 its own derivative history, with Dormand–Prince its
    own steps and time); the results are the bits of the same model without
    lanes, which runs one case at a time."""
    path = "python/tests/models/n_link_pendulum_on_cart_3.sim"
    lanes = autosim.load(repo / path, lanes=True, quiet=True)
    plain = load_model(path)
    cases = autosim.Cases().random(
        22,
        11,
        m1=autosim.uniform(0.3, 1.0),
        l2=autosim.uniform(0.3, 0.7),
        g=autosim.uniform(1.0, 20.0),
        F=autosim.uniform(-1.0, 1.0),
        r1=autosim.uniform(-0.5, 0.5),
    )
    keep = autosim.Keep().final_state().history(["r2"])

    def run(model: autosim.Model) -> autosim.StudyResults:
        return model.study(cases, keep, t_end=0.5, h=0.01, output_interval=0.05, method=method).run(threads=1)

    together, alone = run(lanes), run(plain)
    assert together.failures == 0
    assert together == alone
    # Not vacuous: the cases end apart from one another.
    assert len({tuple(row) for row in together.values}) == 22


def test_a_study_from_python_is_the_rust_study_bit_for_bit(
    study: autosim.Study, rust_results: autosim.StudyResults
) -> None:
    assert len(study) == 80
    assert study.case_columns == ("torque", "m", "L", "q")
    serial = study.run(threads=1)
    assert serial == rust_results
    assert study.run(threads=2) == rust_results
    assert study.run() == rust_results  # every core
    chunks = [study.run((a, b), threads=1) for a, b in [(0, 13), (13, 50), (50, 80)]]
    assert autosim.StudyResults.concat(chunks) == rust_results
    # Equal bits are not a vacuous check: a different seed differs.
    other = study.model.study(
        autosim.Cases()
        .grid("torque", [0.0, 0.5])
        .random(
            40, 2027, m=autosim.uniform(0.5, 2.0), L=autosim.normal(0.7, 0.05), q=autosim.uniform(-1.0, 1.0)
        ),
        study.keep,
        t_end=2.0,
        h=0.01,
        output_interval=0.1,
    )
    assert other.run() != rust_results


def test_results_are_the_model_simulated_case_by_case(study: autosim.Study) -> None:
    results = study.run()
    assert results.failures == 0 and results.ok.all()
    assert results.case_values.shape == (80, 4)
    assert results["history:q"].shape == (80, 21)
    assert np.allclose(study.output_times, np.arange(21) * 0.1, rtol=0, atol=1e-14)
    model = study.model.copy()
    for case in (0, 41, 79):
        torque, m, length, q = results.case_values[case]
        model.parameters.set(m=m, L=length)
        model.inputs["torque"] = torque
        sim = model.simulate(
            2.0, model.state(q=q), method="dopri", rtol=1e-9, atol=1e-12, h=0.01, t_eval=study.output_times
        )
        assert np.allclose(results["history:q"][case], sim["q"], rtol=1e-7, atol=1e-8)
        assert results["final:q"][case] == pytest.approx(sim["q"][-1], rel=1e-7, abs=1e-8)
        assert results["height@1"][case] == pytest.approx(sim["height"][10], rel=1e-7, abs=1e-8)
        assert results["max:height"][case] == pytest.approx(sim["height"].max(), rel=1e-7, abs=1e-8)
        assert results["torque"][case] == torque


def test_pandas_table(study: autosim.Study) -> None:
    pd = pytest.importorskip("pandas")
    frame = study.run((10, 20)).to_pandas()
    assert isinstance(frame, pd.DataFrame)
    assert list(frame.index) == list(range(10, 20)) and frame.index.name == "case"
    assert list(frame.columns[:7]) == ["torque", "m", "L", "q", "final:q", "final:u", "height@1"]
    assert "history:q[20]" in frame.columns and frame["ok"].all()
    assert frame["error"].isna().all()


def test_failed_cases_carry_their_error_and_the_others_are_exact(load_model: Load) -> None:
    model = load_model("examples/models/pendulum.sim")
    rows = np.array([[1.0, 0.5], [0.0, 0.5], [2.0, -0.3], [0.0, 1.0]])  # m = 0: a singular mass matrix
    study = model.study(
        autosim.Cases().rows(["m", "q"], rows), autosim.Keep().final_state(), t_end=1.0, h=0.01, method="rk4"
    )
    results = study.run()
    assert results.failures == 2
    assert list(results.ok) == [True, False, True, False]
    assert results.errors[1] is not None and "mass matrix" in results.errors[1].lower()
    assert np.isnan(results.values[1]).all()
    alone = [
        study.model.study(
            autosim.Cases().rows(["m", "q"], rows[k : k + 1]), study.keep, t_end=1.0, h=0.01, method="rk4"
        ).run()
        for k in (0, 2)
    ]
    assert np.array_equal(results.values[[0, 2]], np.vstack([a.values for a in alone]))
    assert repr(results) == (
        "<StudyResults: cases 0..4 (2 ok, 2 failed); columns m, q; fields final:q, final:u>"
    )


def test_the_repr_of_results_is_one_short_line(study: autosim.Study) -> None:
    shown = repr(study.run((0, 80)))
    assert shown == (
        "<StudyResults: cases 0..80 (80 ok, 0 failed); columns torque, m, L, q; "
        "fields final:q, final:u, height@1, max:height, history:q[21]>"
    )


def test_mistakes_are_value_errors_naming_the_thing(load_model: Load) -> None:
    model = load_model("examples/models/pendulum.sim")
    keep = autosim.Keep().final_state()
    with pytest.raises(ValueError, match="column `mass`"):
        model.study(autosim.Cases().grid("mass", [1.0]), keep, t_end=1.0)
    with pytest.raises(ValueError, match="`speed` is not a state, output or discrete variable"):
        model.study(autosim.Cases(), autosim.Keep().history(["speed"]), t_end=1.0)
    with pytest.raises(ValueError, match="not an output time"):
        model.study(autosim.Cases(), autosim.Keep().at([0.3], ["q"]), t_end=1.0, output_interval=0.25)
    with pytest.raises(ValueError, match="given twice"):
        model.study(autosim.Cases().grid("m", [1.0]).grid("m", [2.0]), keep, t_end=1.0)
    with pytest.raises(ValueError, match="sdirk3"):
        model.study(autosim.Cases(), keep, t_end=1.0, method="sdirk3")
    with pytest.raises(ValueError, match="not all in the table"):
        model.study(autosim.Cases().grid("m", [1.0, 2.0]), keep, t_end=1.0).run((1, 3))
    with pytest.raises(ValueError, match="threads must be None"):
        model.study(autosim.Cases().grid("m", [1.0]), keep, t_end=1.0).run(threads=0)


def test_shards_on_disk_resume_and_read_back(study: autosim.Study, tmp_path: Path) -> None:
    folder = tmp_path / "study"
    summary = study.run_in(folder, shard_size=16)
    assert (summary.cases, summary.ran, summary.skipped, summary.failed) == (80, 80, 0, 0)
    assert sorted(p.name for p in folder.glob("part-*.csv")) == [f"part-{k:06}.csv" for k in range(5)]
    (folder / "part-000003.csv").unlink()  # lost in a crash
    again = study.run_in(folder, shard_size=16)
    assert (again.ran, again.skipped) == (16, 64)
    assert study.read(folder) == study.run()
    other = study.model.study(study.cases, autosim.Keep().final_state(), t_end=2.0)
    with pytest.raises(ValueError, match="different study"):
        other.read(folder)
    # The same study of the model with another parameter set beforehand
    # would mix two gravities: refused.
    moon = study.model.copy()
    moon.parameters["g"] = 1.62
    with pytest.raises(ValueError, match="the model as made: its parameters"):
        reference_study(moon).run_in(folder, shard_size=16)
    with pytest.raises(ValueError, match="the model as made"):
        reference_study(moon).read(folder)


def test_a_study_pickles_as_its_recipe(study: autosim.Study) -> None:
    again = pickle.loads(pickle.dumps(study))
    assert again.describe() == study.describe()
    assert again.run((0, 10)) == study.run((0, 10))


def test_dask_local_cluster_gives_the_same_bits(
    study: autosim.Study, rust_results: autosim.StudyResults
) -> None:
    distributed = pytest.importorskip("distributed")
    with (
        distributed.LocalCluster(
            n_workers=2, threads_per_worker=1, processes=True, host="127.0.0.1", dashboard_address=None
        ) as cluster,
        distributed.Client(cluster) as client,
    ):
        assert len(client.nthreads()) == 2
        assert study.run_dask(client, chunk_size=7) == rust_results
        assert study.run_dask(client) == rust_results  # the default chunks


def _wait_for(path: Path, what: str, seconds: float = 60.0) -> None:
    deadline = time.monotonic() + seconds
    while not path.exists():
        if time.monotonic() > deadline:
            raise TimeoutError(f"{what} did not start within {seconds} s")
        time.sleep(0.2)


def test_loopback_scheduler_and_workers_without_a_compiler_get_the_model_from_its_wheel(
    repo: Path, tmp_path: Path, study: autosim.Study, rust_results: autosim.StudyResults
) -> None:
    distributed = pytest.importorskip("distributed")
    # The model as a wheel, installed where the workers (and this driver) import it.
    _, site = install_model_wheel(repo / "examples/models/pendulum.sim", tmp_path)
    dask = str(Path(sys.executable).parent / "dask")
    env = dict(os.environ)
    env.update(
        PATH=str(tmp_path),
        HOME=str(tmp_path),
        PYTHONPATH=str(site),
        AUTOSIM_CACHE=str(tmp_path / "empty-cache"),
    )
    env.pop("CARGO", None)  # no Rust toolchain on the workers
    scheduler_file = tmp_path / "scheduler.json"
    loopback = ["--host", "127.0.0.1", "--no-dashboard"]
    processes = [
        subprocess.Popen(
            [dask, "scheduler", "--port", "0", "--scheduler-file", str(scheduler_file), *loopback],
            env=env,
            stdout=subprocess.DEVNULL,
            stderr=subprocess.DEVNULL,
        )
    ]
    try:
        _wait_for(scheduler_file, "the scheduler")
        processes.append(
            subprocess.Popen(
                [
                    dask,
                    "worker",
                    "--scheduler-file",
                    str(scheduler_file),
                    "--nworkers",
                    "2",
                    "--nthreads",
                    "1",
                    *loopback,
                ],
                env=env,
                stdout=subprocess.DEVNULL,
                stderr=subprocess.DEVNULL,
            )
        )
        sys.path.insert(0, str(site))
        try:
            import autosim_model_pendulum

            from_wheel = autosim_model_pendulum.load()
        finally:
            sys.path.remove(str(site))
        wheel_study = reference_study(from_wheel)
        assert wheel_study.describe() == study.describe()
        with distributed.Client(scheduler_file=str(scheduler_file), timeout=60) as client:
            client.wait_for_workers(2, timeout=60)
            addresses = list(client.scheduler_info()["workers"])
            assert len(addresses) == 2 and all(a.startswith("tcp://127.0.0.1:") for a in addresses)
            assert wheel_study.run_dask(client, chunk_size=9) == rust_results
        assert not (tmp_path / "empty-cache").exists(), "the workers built nothing"
    finally:
        for p in reversed(processes):
            p.terminate()
        for p in processes:
            try:
                p.wait(timeout=20)
            except subprocess.TimeoutExpired:
                p.kill()


def test_a_study_of_a_model_with_events_sets_and_keeps_its_discrete_variables(load_model: Load) -> None:
    """The bouncing ball from 1 m: in free fall ``h(t) = 1 - g t²/2`` until
    the first bounce at ``t1 = sqrt(2/g) = 0.4515 s``; resting from the
    start it stays at 1 m; with ``v_min`` above the impact speed the first
    bounce leaves it resting (the same cases as the Rust test
    ``a_study_sets_and_keeps_the_discrete_variables``)."""
    ball = load_model("examples/models/bouncing_ball.sim")
    cases = autosim.Cases().grid("resting", [0.0, 1.0]).grid("v_min", [0.01, 10.0])
    keep = autosim.Keep().at([0.3], ["h"]).statistic("resting", "max").history(["resting"])
    results = ball.study(cases, keep, t_end=0.6, output_interval=0.15, rtol=1e-12, atol=1e-12).run()
    assert results.failures == 0
    np.testing.assert_allclose(results["h@0.3"], [1 - 9.81 * 0.09 / 2] * 2 + [1.0] * 2, rtol=0, atol=1e-12)
    assert results["history:resting"].tolist() == [[0.0] * 5, [0.0] * 4 + [1.0], [1.0] * 5, [1.0] * 5]
    assert results["max:resting"].tolist() == [0.0, 1.0, 1.0, 1.0]
    # The event options are the study's: the bounces of e = 0.5 come to
    # rest after about nine, their flights (0.9 s · 0.5^k) closer than
    # 0.1 s from the fourth on: a chain longer than `zeno_events` = 2
    # within `zeno_interval` = 0.1 s fails the case, the defaults do not.
    ball.parameters["e"] = 0.5
    bounces = autosim.Cases().grid("v_min", [0.01])
    rest = autosim.Keep().at([3.0], ["resting"])
    assert ball.study(bounces, rest, t_end=3.0).run()["resting@3"].tolist() == [1.0]
    chatter = ball.study(bounces, rest, t_end=3.0, zeno_events=2, zeno_interval=0.1).run()
    assert chatter.failures == 1 and "Zeno" in str(chatter.errors[0]), chatter.errors
    # A coarse `event_tolerance` places the bounce within its width:
    # elastic, the ball rises at g t1 after t1, slowing by g.
    t1 = np.sqrt(2 / 9.81)
    exact = 9.81 * t1 - 9.81 * (0.5 - t1)
    errors = []
    for tolerance in (0.0, 1e-3):
        elastic = ball.study(
            autosim.Cases().grid("e", [1.0]),
            autosim.Keep().at([0.5], ["v"]),
            t_end=0.5,
            event_tolerance=tolerance,
            rtol=1e-12,
            atol=1e-12,
        ).run()
        errors.append(abs(elastic["v@0.5"][0] - exact))
    assert errors[0] < 1e-9 and 1e-9 < errors[1] < 2 * 9.81 * 1e-3, errors
    with pytest.raises(ValueError, match=r"t_end \(0.0\) must be finite and after t0 \(0.0\)"):
        ball.study(cases, keep, t_end=0.0)
    with pytest.raises(ValueError, match="zeno_events"):
        ball.study(cases, keep, t_end=0.6, zeno_events=0)


def test_a_distribution_that_is_none_is_refused_where_it_is_written() -> None:
    for bad in [lambda: autosim.uniform(0.11, 0.09), lambda: autosim.uniform(0.0, np.inf)]:
        with pytest.raises(ValueError, match="finite with low < high"):
            bad()
    with pytest.raises(ValueError, match="standard deviation finite and at least 0"):
        autosim.normal(0.1, -0.01)
    assert autosim.normal(0.1, 0.0).b == 0.0
