"""Tables of bench/constrained/run.sh: median ns per call over every batch of
every round, autosim (default flags and -C target-cpu=native) against SymPy's
C, with the operation counts, the agreement and the generation times.

    python report.py OUTDIR RESULTS.md RESULTS.jsonl

The environment gives BENCH_GIT, ROUNDS, BENCH_LOAD, GCC, BENCH_RUSTC and
BENCH_CPU for the header."""

import datetime
import json
import os
import statistics
import sys

MODELS = ("four_bar", "rolling_disc", "bicycle")


def main() -> None:
    out, md_path, jsonl_path = sys.argv[1:4]
    batches = {}
    for line in open(os.path.join(out, "rounds.jsonl")):
        r = json.loads(line)
        batches.setdefault((r["kind"], r["method"]), []).extend(r["batches_ns"])
    med = {k: statistics.median(v) for k, v in batches.items()}
    ops = {o["kind"]: o for o in map(json.loads, open(os.path.join(out, "autosim_ops.jsonl")))}
    agree = json.load(open(os.path.join(out, "compare.json")))
    info = {m: json.load(open(os.path.join(out, m, "derive.json"))) for m in MODELS}
    time_rows = [
        "| model | state (coordinates + independent speeds; all speeds) | SymPy C (ns) | of which M, f, dq/dt (ns) "
        "| autosim, default flags (ns) | ratio | autosim, native (ns) | ratio "
        "| SymPy ops (cse'd + LU) | autosim ops | largest difference |",
        "|---|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|",
    ]
    gen_rows = [
        "| model | KanesMethod (s) | cse (s) | states (s) | whole script (s) | C lines | ops before cse | pow calls |",
        "|---|---:|---:|---:|---:|---:|---:|---:|",
    ]
    summary = []
    # (row, SymPy's model, autosim's model): the last is autosim's variant of
    # the disc (models/rolling_disc_lean.sim) against the same SymPy C
    for label, m, k in [(m, m, m) for m in MODELS] + [
        ("rolling_disc, contact along the lean axis", "rolling_disc", "rolling_disc_lean")
    ]:
        d = info[m]
        s, a, n = med[(m, "sympy_lu")], med[(k, "default")], med[(k, "native")]
        ev = med[(m, "sympy_eval")]
        so, ao = d["ops"], ops[k]
        worst = max(agree[f"{k}/default"]["max_rel"], agree[f"{k}/native"]["max_rel"])
        n_ind = d["n_speeds"] - len(d["dependent_speeds"])
        state = f"{len(d['state_names']) - n_ind} + {n_ind}; {d['n_speeds']}"
        time_rows.append(
            f"| {label} | {state} | {s:.1f} | {ev:.1f} | {a:.1f} | {a / s:.2f} | {n:.1f} | {n / s:.2f} "
            f"| {so['after_cse']} + {so['lu_solve']} = {so['total']} | {ao['total']} | {worst:.1e} |"
        )
        t = d["times"]
        if k == m:
            gen_rows.append(
                f"| {m} | {t['kanes_equations_s']:.1f} | {t['cse_s']:.1f} | {t['states_s']:.1f} "
                f"| {t['total_s']:.1f} | {d['c_lines']} | {so['before_cse']} | {so['pow_calls']} |"
            )
        summary.append(
            dict(
                model=label,
                sympy_model=m,
                autosim_model=k,
                sympy_ns=s,
                autosim_default_ns=a,
                autosim_native_ns=n,
                ratio_default=a / s,
                ratio_native=n / s,
                sympy_ops=so,
                autosim_ops=ao,
                max_rel_difference=worst,
                generation=t,
                nq_plus_nu=state,
            )
        )
    sympy_version = info["bicycle"]["sympy"]
    numpy_version = info["bicycle"]["numpy"]
    text = f"""# autosim against SymPy's KanesMethod on the constrained models

`bash bench/constrained/run.sh`,
{datetime.datetime.now(datetime.timezone.utc):%Y-%m-%d %H:%M} UTC, autosim at
{os.environ.get("BENCH_GIT", "an unknown commit")}; {os.environ.get("ROUNDS", "?")} interleaved rounds
pinned to one CPU; {os.environ.get("BENCH_CPU", "?")}, {os.cpu_count()} CPUs, load average at the
start {os.environ.get("BENCH_LOAD", "?")}. SymPy {sympy_version}, NumPy {numpy_version};
{os.environ.get("GCC", "gcc")} with `-O3 -march=native`; {os.environ.get("BENCH_RUSTC", "rustc")}.

Median ns per call of the state derivative over every batch (1000 calls at
1000 random consistent states) of every round. Both sides compute the same
thing from the same state, autosim's `derivatives()`: the state holds every
coordinate and the independent speeds; the dependent speeds are solved from
the velocity constraints inside the call, and the result is dq/dt of every
coordinate and du/dt of the independent speeds. SymPy's side (derive.py):
KanesMethod's dependent-speed solution and its mass matrix and forcing (the
dynamical equations stacked on the acceleration constraints, n x n), one
`sympy.cse` over them and the kinematic equations, SymPy's C printer, then
an LU solve of M du/dt = f (lu.h) for every speed; the next column times
the same C without the solve (M, f and dq/dt only). Parameters are run-time
values on both sides. Ratio = autosim / SymPy (below 1: autosim faster).
Operations: SymPy's `count_ops` of the cse'd expressions plus the LU's
arithmetic; autosim's `DERIVATIVE_OPS.total()` (adds, multiplies, divides
and function calls). Largest difference: over the 1000 states and both
autosim builds, the largest |autosim - SymPy| of any component relative to
the state's largest |dx| (compare.py; the run fails above 1e-12). The last
row is autosim's model of the disc with its contact vector written along the
lean axis (models/rolling_disc_lean.sim), as SymPy's model has it, instead
of examples/models/rolling_disc.sim's `-r*dir(n3 - dot(n3, D.2)*D.2)`.

{chr(10).join(time_rows)}

SymPy's generation (derive.py, this machine, one core; "states" draws and
assembles the 1000 states with NumPy):

{chr(10).join(gen_rows)}
"""
    open(md_path, "w").write(text)
    with open(jsonl_path, "w") as f:
        for row in summary:
            f.write(json.dumps(row) + "\n")


if __name__ == "__main__":
    main()
