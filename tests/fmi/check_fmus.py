"""Checks autosim's FMUs with FMPy, an independent FMI importer.

Run by `tests/fmi.rs` (which builds the FMUs and computes autosim's own
trajectories) as `python check_fmus.py MANIFEST.json`. For every FMU of the
manifest:

- FMPy's `validate_fmu` finds no problem;
- `nm -D` shows all 44 functions of `fmi2Functions.h`;
- Model Exchange (FMPy's CVode) and Co-Simulation runs agree with
  autosim's own run (`reference`) to the stated bounds;
- the directional derivatives equal central finite differences through
  FMPy's low-level `FMU2Model` calls;
- the `ModelStructure` dependencies of derivatives and outputs equal the
  ones found numerically (perturbing each state and input), except the
  manifest's `invariant` pairs, read by the equations but cancelled by
  the mathematics (the manifest's `identities` check the formula that
  shows it where there is one);
- an FMU that declares no directional derivatives answers
  `fmi2GetDirectionalDerivative` with fmi2Error;

and, once, for the FMU named `sequence_checks`: two instances interleaved
with different parameters give their separate answers, a call the
standard forbids in the instance's state returns fmi2Error (not a crash),
`fmi2Reset` recovers, and FMU states survive serialization; for an FMU
with `events` (a bouncing ball: the hand-written one of `ball_fmu` and the
language's `bouncing_ball.sim`): Model Exchange with CVode locating the
impacts and Co-Simulation locating them inside its steps both follow the
analytic bounces (impact times, heights and speeds; where the FMU has
them, the discrete impact count, the terminal event's time, and a saved
FMU state bringing the discrete variable back).

Prints one line per check and exits with 1 if any failed.
"""

from __future__ import annotations

import json
import os
import shutil
import subprocess
import sys
import tempfile
import zipfile
from typing import Any

from ctypes import POINTER, c_double, c_int, c_void_p

import numpy as np
from fmpy import extract, read_model_description, simulate_fmu
from fmpy.fmi1 import FMICallException
from fmpy.fmi2 import FMU2Model, FMU2Slave
from fmpy.validation import validate_fmu

# Every function of fmi2Functions.h (FMI 2.0): common, Model Exchange,
# Co-Simulation.
FMI2_FUNCTIONS = """
fmi2GetTypesPlatform fmi2GetVersion fmi2SetDebugLogging fmi2Instantiate
fmi2FreeInstance fmi2SetupExperiment fmi2EnterInitializationMode
fmi2ExitInitializationMode fmi2Terminate fmi2Reset fmi2GetReal fmi2GetInteger
fmi2GetBoolean fmi2GetString fmi2SetReal fmi2SetInteger fmi2SetBoolean
fmi2SetString fmi2GetFMUstate fmi2SetFMUstate fmi2FreeFMUstate
fmi2SerializedFMUstateSize fmi2SerializeFMUstate fmi2DeSerializeFMUstate
fmi2GetDirectionalDerivative
fmi2EnterEventMode fmi2NewDiscreteStates fmi2EnterContinuousTimeMode
fmi2CompletedIntegratorStep fmi2SetTime fmi2SetContinuousStates
fmi2GetDerivatives fmi2GetEventIndicators fmi2GetContinuousStates
fmi2GetNominalsOfContinuousStates
fmi2SetRealInputDerivatives fmi2GetRealOutputDerivatives fmi2DoStep
fmi2CancelStep fmi2GetStatus fmi2GetRealStatus fmi2GetIntegerStatus
fmi2GetBooleanStatus fmi2GetStringStatus
""".split()

FAILURES: list[str] = []


def report(name: str, check: str, ok: bool, detail: str) -> None:
    print(f"{'ok  ' if ok else 'FAIL'} {name:<18} {check:<28} {detail}")
    if not ok:
        FAILURES.append(f"{name}: {check}: {detail}")


def check_symbols(name: str, fmu: str) -> None:
    nm = shutil.which("nm")
    if nm is None:
        print(f"SKIPPED: {name}: nm -D (no nm on this machine)")
        return
    md = read_model_description(fmu)
    identifier = md.coSimulation.modelIdentifier
    with tempfile.TemporaryDirectory() as tmp, zipfile.ZipFile(fmu) as z:
        lib = z.extract(f"binaries/linux64/{identifier}.so", tmp)
        out = subprocess.run(
            [nm, "-D", "--defined-only", lib], capture_output=True, text=True, check=True
        ).stdout
    exported = {line.split()[-1] for line in out.splitlines() if " T " in line}
    missing = [f for f in FMI2_FUNCTIONS if f not in exported]
    report(name, "nm -D: fmi2 functions", not missing,
           f"{len(FMI2_FUNCTIONS) - len(missing)}/{len(FMI2_FUNCTIONS)} exported"
           + (f", missing {missing}" if missing else ""))


def input_signal(spec: dict[str, Any] | None) -> np.ndarray | None:
    if spec is None:
        return None
    names = ["time"] + [k for k in spec if k != "time"]
    rows = list(zip(*(spec[n] for n in names)))
    return np.array(rows, dtype=[(n, np.float64) for n in names])


def compare(name: str, check: str, result: np.ndarray, reference: dict[str, list[float]],
            bound: float) -> None:
    """The largest difference at the reference's times (an event time FMPy
    recorded twice counts with its last row), scaled by 1 + max |ref|."""
    times = np.asarray(reference["time"])
    rows = []
    for t in times:
        hits = np.nonzero(np.isclose(result["time"], t, rtol=0.0, atol=1e-9))[0]
        if len(hits) == 0:
            report(name, check, False, f"no result at t = {t}")
            return
        rows.append(hits[-1])
    worst, where = 0.0, ""
    for var, ref in reference.items():
        if var == "time":
            continue
        ref = np.asarray(ref)
        got = np.asarray(result[var])[rows]
        err = float(np.max(np.abs(got - ref)) / (1.0 + np.max(np.abs(ref))))
        if not err <= worst:
            worst, where = err, var
    report(name, check, worst <= bound, f"max error {worst:.2e} ({where}), bound {bound:.0e}")


def check_runs(name: str, fmu: str, spec: dict[str, Any]) -> None:
    signal = input_signal(spec.get("input"))
    common = dict(stop_time=spec["stop"], output_interval=spec["interval"], input=signal,
                  start_values=spec.get("start", {}))
    reference = spec.get("reference")
    if reference is None:
        # No autosim reference: both interfaces run to the end.
        for kind in ("ModelExchange", "CoSimulation"):
            r = simulate_fmu(fmu, fmi_type=kind, **common)
            ok = np.isclose(r["time"][-1], spec["stop"]) and all(
                np.all(np.isfinite(r[v])) for v in r.dtype.names)
            report(name, f"{kind} run", ok, f"to t = {r['time'][-1]}")
        return
    names = [v for v in reference if v != "time"]
    me = simulate_fmu(fmu, fmi_type="ModelExchange", relative_tolerance=spec["me_tolerance"],
                      output=names, **common)
    compare(name, "ME (CVode) vs autosim", me, reference, spec["me_bound"])
    cs = simulate_fmu(fmu, fmi_type="CoSimulation", relative_tolerance=spec["cs_tolerance"],
                      output=names, **common)
    compare(name, "CS (dormand_prince) vs autosim", cs, reference, spec["cs_bound"])


class Model:
    """One Model Exchange instance through FMPy's low-level calls."""

    def __init__(self, fmu: str, unzipdir: str, name: str = "instance"):
        self.md = read_model_description(fmu)
        self.fmu = FMU2Model(guid=self.md.guid, unzipDirectory=unzipdir,
                             modelIdentifier=self.md.modelExchange.modelIdentifier,
                             instanceName=name)
        self.fmu.instantiate()
        self.fmu.setupExperiment(startTime=0.0)
        self.fmu.enterInitializationMode()
        self.fmu.exitInitializationMode()
        self.fmu.newDiscreteStates()
        self.fmu.enterContinuousTimeMode()
        vars_ = self.md.modelVariables
        self.states = [d.variable.derivative for d in self.md.derivatives]
        self.derivs = [d.variable for d in self.md.derivatives]
        self.outputs = [v for v in vars_ if v.causality == "output"]
        self.inputs = [v for v in vars_ if v.causality == "input"]
        self.nx = len(self.states)

    def set_point(self, x: np.ndarray, w: np.ndarray) -> None:
        self.fmu.setContinuousStates(pointer(np.ascontiguousarray(x)), self.nx)
        if len(self.inputs):
            self.fmu.setReal([v.valueReference for v in self.inputs], list(w))

    def unknowns(self, x: np.ndarray, w: np.ndarray) -> np.ndarray:
        """Derivatives, then outputs, at (x, w)."""
        self.set_point(x, w)
        dx = np.zeros(self.nx)
        self.fmu.getDerivatives(pointer(dx), self.nx)
        y = self.fmu.getReal([v.valueReference for v in self.outputs]) if self.outputs else []
        return np.concatenate([dx, np.asarray(y, dtype=float)])

    def free(self) -> None:
        self.fmu.terminate()
        self.fmu.freeInstance()


def finite_differences(m: Model, x: np.ndarray, w: np.ndarray, knowns) -> np.ndarray:
    """Partial derivatives of the unknowns (rows) by the knowns (columns) at
    (x, w): central differences with one Richardson extrapolation."""

    def central(kind: str, i: int, h: float) -> np.ndarray:
        base = x if kind == "x" else w
        plus, minus = base.copy(), base.copy()
        plus[i] += h
        minus[i] -= h
        if kind == "x":
            return (m.unknowns(plus, w) - m.unknowns(minus, w)) / (2.0 * h)
        return (m.unknowns(x, plus) - m.unknowns(x, minus)) / (2.0 * h)

    columns = []
    for _, kind, i in knowns:
        h = 1e-3 * (1.0 + abs((x if kind == "x" else w)[i]))
        columns.append((4.0 * central(kind, i, h / 2) - central(kind, i, h)) / 3.0)
    return np.array(columns).T


def check_jacobian(name: str, fmu: str, unzipdir: str, spec: dict[str, Any]) -> None:
    m = Model(fmu, unzipdir)
    rng = np.random.default_rng(7)
    x0 = np.zeros(m.nx)
    m.fmu.getContinuousStates(pointer(x0), m.nx)
    w0 = np.array([float(v.start) for v in m.inputs])
    knowns = [(v, "x", i) for i, v in enumerate(m.states)] + [(v, "w", i) for i, v in enumerate(m.inputs)]
    unknown_vars = m.derivs + m.outputs
    # Three points off the initial one (nonzero speeds, angles off their
    # zeros); an entry depends numerically if it moves beyond rounding (and
    # the rounding of a constrained model's Newton solve, about 1e-11
    # here) at any of them.
    numeric = None
    for _ in range(3):
        x = x0 + spec.get("spread", 0.1) * rng.uniform(-1.0, 1.0, m.nx)
        w = w0 + 0.01 * rng.uniform(-1.0, 1.0, len(m.inputs))
        f0 = m.unknowns(x, w)
        fd = finite_differences(m, x, w, knowns)
        moves = np.abs(fd) > 1e-9 * (1.0 + np.abs(f0))[:, None]
        numeric = moves if numeric is None else numeric | moves
    m.set_point(x, w)
    index = {v: k + 1 for k, v in enumerate(m.md.modelVariables)}
    known_index = [index[v] for v, _, _ in knowns]
    declared = np.zeros_like(numeric)
    structure = list(m.md.derivatives) + list(m.md.outputs)
    for r, unknown in enumerate(structure):
        deps = unknown.dependencies
        for d in (deps if deps is not None else [v for v, _, _ in knowns]):
            declared[r, known_index.index(index[d])] = True
    # Pairs the equations read but whose value the mathematics makes
    # independent of the known (named in the manifest with the reason).
    invariant = {tuple(p) for p in spec.get("invariant", [])}
    wrong = [(unknown_vars[r].name, knowns[c][0].name,
              "declared only" if declared[r, c] else f"numeric only ({fd[r, c]:.1e})")
             for r, c in zip(*np.nonzero(declared != numeric))]
    allowed = [w for w in wrong if w[2] == "declared only" and w[:2] in invariant]
    wrong = [w for w in wrong if w not in allowed]
    report(name, "ModelStructure vs numeric", not wrong,
           f"{int(declared.sum())} dependencies of {declared.size} pairs"
           + (f", {len(allowed)} declared and invariant {allowed}" if allowed else "")
           + (f"; differ at {wrong}" if wrong else ""))
    for identity in spec.get("identities", []):
        check_identity(name, m, identity)
    if m.md.modelExchange.providesDirectionalDerivative:
        dd = np.zeros_like(fd)
        unknown_refs = [v.valueReference for v in unknown_vars]
        for c, (v, _, _) in enumerate(knowns):
            dd[:, c] = m.fmu.getDirectionalDerivative(unknown_refs, [v.valueReference], [1.0])
        err = float(np.max(np.abs(dd - fd) / (1.0 + np.abs(fd)))) if fd.size else 0.0
        report(name, "directional derivative vs FD", err <= 1e-7,
               f"max error {err:.2e} over {fd.size} entries, bound 1e-7")
        m.free()
    else:
        refs = [unknown_vars[0].valueReference], [knowns[0][0].valueReference]
        got = expect_error(m.fmu.getDirectionalDerivative, *refs, [1.0])
        report(name, "directional derivative", got == "error",
               f"declared false; fmi2GetDirectionalDerivative answers {got}")
        # The error leaves the instance in the Error state, which only
        # fmi2Reset and fmi2FreeInstance may leave.
        m.fmu.freeInstance()


def check_identity(name: str, m: Model, identity: dict[str, Any]) -> None:
    """An unknown equal to a coefficient times a product of states, the
    reason a declared dependency does not move (the manifest's
    `invariant`): checked at 200 random states, entries uniform in [-2, 2]
    (the model's small variables, `small`, in [-2e-3, 2e-3]), random
    inputs."""
    rng = np.random.default_rng(11)
    state = {v.name: k for k, v in enumerate(m.states)}
    row = [v.name for v in m.derivs + m.outputs].index(identity["unknown"])
    scale = np.array([1e-3 if v.name in identity.get("small", []) else 1.0 for v in m.states])
    worst = 0.0
    for _ in range(200):
        x = scale * rng.uniform(-2.0, 2.0, m.nx)
        w = rng.uniform(-1.0, 1.0, len(m.inputs))
        want = identity["coefficient"] * np.prod([x[state[f]] for f in identity["factors"]])
        got = m.unknowns(x, w)[row]
        worst = max(worst, abs(got - want) / (1.0 + abs(want)))
    formula = f"{identity['coefficient']:g} " + " ".join(identity["factors"])
    report(name, f"{identity['unknown']} = {formula}", worst <= 1e-12,
           f"max error {worst:.1e} at 200 random states, bound 1e-12")


def pointer(a: np.ndarray):
    """A C pointer to an array of doubles."""
    return a.ctypes.data_as(POINTER(c_double))


def do_step_status(m: FMU2Model) -> int:
    """fmi2DoStep called on a Model Exchange instance (bypassing FMPy's
    bindings, which have none for it): the status returned."""
    do_step = m.dll.fmi2DoStep
    do_step.argtypes = [c_void_p, c_double, c_double, c_int]
    do_step.restype = c_int
    return do_step(m.component, 0.0, 0.1, 1)


def expect_error(call, *args) -> str:
    """Runs a call that must return fmi2Error; the status, or why not."""
    try:
        call(*args)
    except FMICallException as e:
        return "error" if e.status == 3 else f"status {e.status}"
    return "fmi2OK"


def check_sequences(name: str, fmu: str, unzipdir: str, spec: dict[str, Any]) -> None:
    md = read_model_description(fmu)
    ident = md.coSimulation.modelIdentifier
    vr = {v.name: v.valueReference for v in md.modelVariables}
    param, (p1, p2) = spec["parameter"], spec["values"]
    watch = vr[spec["watch"]]

    # Two instances of one library, interleaved, different parameters.
    def slave(instance: str, value: float) -> FMU2Slave:
        s = FMU2Slave(guid=md.guid, unzipDirectory=unzipdir, modelIdentifier=ident,
                      instanceName=instance)
        s.instantiate()
        s.setupExperiment(startTime=0.0, tolerance=1e-10)
        s.setReal([vr[param]], [value])
        s.enterInitializationMode()
        s.exitInitializationMode()
        return s

    a, b = slave("a", p1), slave("b", p2)
    h, n = 0.01, 100
    for k in range(n):
        a.doStep(k * h, h)
        b.doStep(k * h, h)
    ya, yb = a.getReal([watch])[0], b.getReal([watch])[0]
    for s in (a, b):
        s.terminate()
        s.freeInstance()
    alone = [float(simulate_fmu(fmu, fmi_type="CoSimulation", stop_time=n * h, output_interval=h,
                                relative_tolerance=1e-10, start_values={param: p},
                                output=[spec["watch"]])[spec["watch"]][-1]) for p in (p1, p2)]
    same = [abs(y - y0) <= 1e-12 * (1.0 + abs(y0)) for y, y0 in zip((ya, yb), alone)]
    ok = all(same) and ya != yb
    report(name, "two instances interleaved", ok,
           f"{spec['watch']} = {ya:.9g} ({param} = {p1}) and {yb:.9g} ({param} = {p2}); "
           f"each alone {alone[0]:.9g}, {alone[1]:.9g}")

    # Calls in states where the standard forbids them.
    m = FMU2Model(guid=md.guid, unzipDirectory=unzipdir, modelIdentifier=ident, instanceName="seq")
    m.instantiate()
    got = {
        "fmi2GetReal before initialization": expect_error(m.getReal, [watch]),
    }
    m.reset()
    status = do_step_status(m)
    got["fmi2DoStep on a Model Exchange instance"] = "error" if status == 3 else f"status {status}"
    m.reset()
    zeros = np.zeros(len(md.derivatives))
    got["fmi2SetContinuousStates before initialization"] = expect_error(
        m.setContinuousStates, pointer(zeros), len(zeros))
    m.reset()
    m.setupExperiment(startTime=0.0)
    m.enterInitializationMode()
    m.exitInitializationMode()
    got[f"fmi2SetReal of parameter {param} after initialization"] = expect_error(m.setReal, [vr[param]], [p2])
    m.reset()
    got["fmi2ExitInitializationMode before entering it"] = expect_error(m.exitInitializationMode)
    m.reset()
    m.setupExperiment(startTime=0.0)
    m.enterInitializationMode()
    m.exitInitializationMode()
    got["fmi2SetReal of an output"] = expect_error(m.setReal, [vr[spec["output"]]], [1.0])
    m.reset()
    ok = all(v == "error" for v in got.values())
    report(name, "bad call sequences", ok, "; ".join(f"{k}: {v}" for k, v in got.items()))
    m.freeInstance()

    # FMU states: save, serialize, run on, restore from the bytes, run again.
    s = slave("state", p1)
    for k in range(10):
        s.doStep(k * h, h)
    state = s.getFMUstate()
    data = s.serializeFMUstate(state)
    s.freeFMUstate(state)
    for k in range(10, 20):
        s.doStep(k * h, h)
    first = s.getReal([watch])[0]
    restored = s.deSerializeFMUstate(data)
    s.setFMUstate(restored)
    s.freeFMUstate(restored)
    for k in range(10, 20):
        s.doStep(k * h, h)
    again = s.getReal([watch])[0]
    s.terminate()
    s.freeInstance()
    report(name, "FMU state serialized", first == again,
           f"{len(data)} bytes; {spec['watch']} at t = 0.2: {first:.12g} and after restoring {again:.12g}")


def bouncing_ball(t: float, g: float, e: float, h0: float) -> tuple[float, float, int]:
    """The analytic ball dropped from rest at h0: height, speed and impacts
    so far at time t (impact n at t1 + sum_{i<n} 2 e^i v1 / g, each
    rebound at e times the impact speed)."""
    t1 = np.sqrt(2.0 * h0 / g)
    if t < t1:
        return h0 - 0.5 * g * t * t, -g * t, 0
    start, speed, n = t1, e * g * t1, 1
    while t >= start + 2.0 * speed / g:
        start, speed, n = start + 2.0 * speed / g, e * speed, n + 1
    s = t - start
    return speed * s - 0.5 * g * s * s, speed - g * s, n


def impact_times(g: float, e: float, h0: float, until: float) -> list[float]:
    t1 = np.sqrt(2.0 * h0 / g)
    times, speed = [t1], e * g * t1
    while times[-1] + 2.0 * speed / g < until:
        times.append(times[-1] + 2.0 * speed / g)
        speed *= e
    return times


def trajectory_error(result: np.ndarray, ev: dict[str, Any]) -> tuple[float, int]:
    """Largest |z - z_exact| + |v - v_exact|/g over the result's rows away
    from impacts (where the exact state jumps), and the rows compared."""
    g, e, h0 = ev["g"], ev["restitution"], ev["h0"]
    impacts = impact_times(g, e, h0, ev["stop"])
    worst, rows = 0.0, 0
    for t, z, v in zip(result["time"], result[ev["height"]], result[ev["speed"]]):
        if min(abs(t - ti) for ti in impacts) < 1e-6:
            continue
        ze, ve, _ = bouncing_ball(float(t), g, e, h0)
        worst = max(worst, abs(z - ze), abs(v - ve) / g)
        rows += 1
    return worst, rows


def found_impacts(result: np.ndarray, ev: dict[str, Any]) -> list[float]:
    """The impacts of a Model Exchange run with its events recorded: where
    the impact counter steps up (an FMU with one, ``counter``), or else the
    event rows where the speed jumps from falling to rising."""
    if "counter" in ev:
        jumps = np.nonzero(np.diff(result[ev["counter"]]) > 0)[0] + 1
    else:
        t, v = result["time"], result[ev["speed"]]
        jumps = [i for i in range(1, len(t)) if t[i] == t[i - 1] and v[i - 1] < 0.0 < v[i]]
    return [float(result["time"][i]) for i in jumps]


def check_events(name: str, fmu: str, unzipdir: str, ev: dict[str, Any]) -> None:
    """The ball's runs against the analytic bounces: Model Exchange (CVode
    locating the indicators' zero crossings) and Co-Simulation (the run
    driver inside each step); with a terminal event (``stop_event``) its
    time, with an impact counter (``counter``) the counts and a saved FMU
    state bringing the counter back."""
    g, e, h0 = ev["g"], ev["restitution"], ev["h0"]
    until = ev.get("stop_event", ev["stop"])
    exact = impact_times(g, e, h0, until)
    counter = ev.get("counter")
    md = read_model_description(fmu)
    report(name, "numberOfEventIndicators", md.numberOfEventIndicators == ev["indicators"],
           f"{md.numberOfEventIndicators} declared, model has {ev['indicators']}")
    outputs = [ev["height"], ev["speed"]] + ([counter] if counter else [])
    common = dict(stop_time=ev["stop"], output_interval=ev["interval"], output=outputs)

    me = simulate_fmu(fmu, fmi_type="ModelExchange", relative_tolerance=ev["me_tolerance"],
                      record_events=True, **common)
    found = found_impacts(me, ev)
    ok = len(found) == len(exact) and (counter is None or me[counter][-1] == len(exact))
    err = max((abs(a - b) for a, b in zip(found, exact)), default=np.inf) if ok else np.inf
    report(name, "ME impacts vs analytic", ok and err <= ev["me_time_bound"],
           f"{len(found)} impacts (analytic {len(exact)} before the stop), "
           f"max time error {err:.1e}, bound {ev['me_time_bound']:.0e}")
    worst, rows = trajectory_error(me, ev)
    report(name, "ME trajectory vs analytic", worst <= ev["me_bound"],
           f"max error {worst:.1e} over {rows} rows, bound {ev['me_bound']:.0e}")
    if "stop_event" in ev:
        end = float(me["time"][-1])
        report(name, "ME terminal event", abs(end - until) <= ev["me_time_bound"],
               f"ends at t = {end:.12g}, event at {until}")

    cs = simulate_fmu(fmu, fmi_type="CoSimulation", relative_tolerance=ev["cs_tolerance"], **common)
    worst, rows = trajectory_error(cs, ev)
    report(name, "CS trajectory vs analytic", worst <= ev["cs_bound"],
           f"max error {worst:.1e} over {rows} communication points, bound {ev['cs_bound']:.0e}")
    if "stop_event" in ev:
        end = float(cs["time"][-1])
        ok = abs(end - until) <= ev["cs_time_bound"] and (counter is None or cs[counter][-1] == len(exact))
        count = f" after {cs[counter][-1]:.0f} impacts" if counter else ""
        report(name, "CS terminal event", ok, f"ends at t = {end:.12g} (event at {until}){count}")
    if counter:
        check_saved_discrete(name, md, unzipdir, ev, counter)


def pressed_impacts(p: dict[str, Any], until: float) -> list[float]:
    """The impact instants of the pressed cart (``tests/fmi/pressed_cart.sim``)
    in closed form: harmonic motion about ``x_rest`` between impacts; from
    rest at ``x0`` (``D = x_rest - x0``) the stop is reached after ``acos(d/D)/w`` at speed
    ``w sqrt(D^2 - d^2)``, and a bounce leaving at speed ``s`` returns
    after ``(2/w) atan(s/(w d))``, leaving again at ``e s``."""
    w = np.sqrt(p["k"] / p["M"])
    big_d, d = p["x_rest"] - p["x0"], p["x_rest"] - p["x_stop"]
    times = [float(np.arccos(d / big_d) / w)]
    speed = p["e"] * w * np.sqrt(big_d**2 - d**2)
    while len(times) < 1000:
        t = times[-1] + 2.0 / w * float(np.arctan(speed / (w * d)))
        if t >= until:
            return times
        times.append(t)
        speed *= p["e"]
    raise ValueError(f"the impacts accumulate before {until} s: choose an earlier stop")


def check_pressed(name: str, fmu: str, spec: dict[str, Any]) -> None:
    """The pressed cart as Model Exchange at two tolerances: its impacts
    (event rows where the speed turns from rising to falling) against the
    closed form, and never past the stop (each bounce's return comes
    right after an impact that left the indicator at zero, which CVode
    does not report again: the FMU keeps the side it heads to)."""
    md = read_model_description(fmu)
    x = next(v for v in md.modelVariables if v.name == "x")
    initial = next((u for u in md.initialUnknowns if u.variable is x), None)
    report(name, "x computed from x0: calculated, no start, an initial unknown on x0",
           x.initial == "calculated" and x.start is None and initial is not None
           and [d.name for d in initial.dependencies] == ["x0"],
           f"initial={x.initial} start={x.start} "
           f"dependencies={None if initial is None else [d.name for d in initial.dependencies]}")
    for start, (tolerance, bound) in zip(spec["starts"], spec["me_bounds"]):
        parameters = dict(spec["parameters"], x0=start)
        exact = pressed_impacts(parameters, spec["stop"])
        me = simulate_fmu(fmu, fmi_type="ModelExchange", relative_tolerance=tolerance,
                          stop_time=spec["stop"], output_interval=spec["interval"],
                          output=["x", "v", "past_stop"], record_events=True,
                          start_values={"x0": start})
        report(name, f"ME starts where x0 = {start} says", me["x"][0] == start, f"x(0) = {me['x'][0]}")
        t, v = me["time"], me["v"]
        found = [float(t[i]) for i in range(1, len(t)) if t[i] == t[i - 1] and v[i - 1] > 0.0 > v[i]]
        ok = len(found) == len(exact)
        err = max((abs(a - b) for a, b in zip(found, exact)), default=np.inf) if ok else np.inf
        past = float(np.max(me["past_stop"]))
        report(name, f"ME impacts vs closed form, rtol {tolerance:.0e}",
               ok and err <= bound and past <= spec["past_bound"],
               f"x0 = {start}: {len(found)} impacts (closed form {len(exact)}), max time error {err:.1e}, "
               f"bound {bound:.0e}; furthest past the stop {past:.1e} m")


def check_saved_discrete(name: str, md: Any, unzipdir: str, ev: dict[str, Any], counter: str) -> None:
    """The discrete variable ``counter`` in a saved, serialized FMU state."""
    vr = {v.name: v.valueReference for v in md.modelVariables}
    z, bounces = vr[ev["height"]], vr[counter]
    s = FMU2Slave(guid=md.guid, unzipDirectory=unzipdir,
                  modelIdentifier=md.coSimulation.modelIdentifier, instanceName="events")
    s.instantiate()
    s.setupExperiment(startTime=0.0, tolerance=ev["cs_tolerance"])
    s.enterInitializationMode()
    s.exitInitializationMode()
    h = ev["interval"]
    saved_at, until = 150, 230
    for k in range(saved_at):
        s.doStep(k * h, h)
    state = s.getFMUstate()
    saved = s.serializeFMUstate(state)
    s.freeFMUstate(state)
    before = s.getReal([bounces])[0]
    for k in range(saved_at, until):
        s.doStep(k * h, h)
    first = s.getReal([z, bounces])
    state = s.deSerializeFMUstate(saved)
    s.setFMUstate(state)
    s.freeFMUstate(state)
    restored = s.getReal([bounces])[0]
    for k in range(saved_at, until):
        s.doStep(k * h, h)
    again = s.getReal([z, bounces])
    s.terminate()
    s.freeInstance()
    ok = restored == before and first == again and first[1] > before
    report(name, "discrete in FMU state", ok,
           f"{counter} {before:.0f} saved at t = {saved_at * h:g}, {first[1]:.0f} at t = {until * h:g}, "
           f"restored {restored:.0f}, again {again[1]:.0f}; {ev['height']} {first[0]:.12g} and {again[0]:.12g}")


def main() -> int:
    with open(sys.argv[1]) as f:
        manifest = json.load(f)
    for spec in manifest["fmus"]:
        fmu, name = spec["fmu"], spec["name"]
        problems = validate_fmu(fmu)
        report(name, "FMPy validate_fmu", not problems, f"{len(problems)} problems {problems[:3]}")
        check_symbols(name, fmu)
        unzipdir = extract(fmu)
        try:
            if "events" in spec:
                check_events(name, fmu, unzipdir, spec["events"])
            elif "pressed" in spec:
                check_pressed(name, fmu, spec["pressed"])
            else:
                check_runs(name, fmu, spec)
            check_jacobian(name, fmu, unzipdir, spec)
            if "sequence_checks" in spec:
                check_sequences(name, fmu, unzipdir, spec["sequence_checks"])
        finally:
            shutil.rmtree(unzipdir, ignore_errors=True)
    if FAILURES:
        print(f"{len(FAILURES)} checks failed:", *FAILURES, sep="\n  ")
        return 1
    print("all FMU checks passed")
    return 0


if __name__ == "__main__":
    os.environ.setdefault("PYTHONHASHSEED", "0")
    sys.exit(main())
