"""Tables of bench/jacobian/run.sh: median ns per call of autosim's
linearize() and of CasADi's generated Jacobian over all batches of all
rounds, their ratio, operation counts, gcc's time per file, and the
comparison's errors.

Usage: python report.py OUT_DIR RESULTS_MD RESULTS_JSONL
The environment gives the header's facts: BENCH_GIT, ROUNDS, BENCH_LOAD,
AUTOSIM_RUSTFLAGS, TOL, RUST_S.
"""

import datetime
import json
import os
import statistics
import sys


def jsonl(path: str) -> list[dict]:
    with open(path) as fh:
        return [json.loads(line) for line in fh if line.strip()]


def load(path: str) -> dict:
    with open(path) as fh:
        return json.load(fh)


def cpu_model() -> str:
    with open("/proc/cpuinfo") as fh:
        names = [line.split(":", 1)[1].strip() for line in fh if line.startswith("model name")]
    return names[0] if names else "an unknown CPU"


def build_text() -> str:
    """What run.sh's cargo build cost (RUST_S seconds), in words."""
    secs = float(os.environ.get("RUST_S", "nan"))
    if secs < 10:
        return "already built when this run started (nothing changed)"
    return f"built in {secs:.0f} s of release build (the autosim crates included when they changed)"


def main() -> None:
    out, md_path, jsonl_path = sys.argv[1:4]
    batches: dict[tuple[str, str], list[float]] = {}
    best_round: dict[tuple[str, str], float] = {}
    for r in jsonl(os.path.join(out, "rounds.jsonl")):
        key = (r["model"], r["method"])
        batches.setdefault(key, []).extend(r["batches_ns"])
        best_round[key] = min(best_round.get(key, float("inf")), statistics.median(r["batches_ns"]))
    med = {k: statistics.median(v) for k, v in batches.items()}
    ours_ops = {}
    with open(os.path.join(out, "autosim_list.txt")) as fh:
        for line in fh:
            f = line.split()
            ours_ops[f[0]] = int(f[5])
    gen = {
        m: load(os.path.join(out, "gen", m + ".json"))
        for m in ours_ops
        if os.path.exists(os.path.join(out, "gen", m + ".json"))
    }
    gcc = {g["model"]: g["gcc_s"] for g in jsonl(os.path.join(out, "gcc.jsonl"))}
    errs = {r["model"]: r.get("max_rel_err") for r in load(os.path.join(out, "compare.json"))["results"]}

    def order(m: str) -> tuple:
        parts = m.split("_")
        return (
            m == "bicycle",
            parts[1] if len(parts) > 2 else m,
            int(parts[-1]) if parts[-1].isdigit() else 0,
        )

    table = [
        (
            "| model | matrices | autosim ns | CasADi ns | autosim / CasADi | same, fastest rounds "
            "| autosim ops | CasADi ops | gcc s | max rel. difference |"
        ),
        "|---|---|---:|---:|---:|---:|---:|---:|---:|---:|",
    ]
    summary = []
    for m in sorted(ours_ops, key=order):
        if (m, "autosim") not in med or (m, "casadi") not in med:
            continue
        a, c = med[(m, "autosim")], med[(m, "casadi")]
        fast = best_round[(m, "autosim")] / best_round[(m, "casadi")]
        g = gen[m]
        mats = "A" if g["nw"] == 0 and g["ny"] == 0 else "A, B, C, D"
        dims = f"{mats} ({g['nlin']} states" + (
            f", {g['nw']} inputs, {g['ny']} outputs)" if g["ny"] or g["nw"] else ")"
        )
        name = m.replace("_", "-")
        table.append(
            f"| {name} | {dims} | {a:.1f} | {c:.1f} | {a / c:.2f} | {fast:.2f} | "
            f"{ours_ops[m]} | {g['casadi_ops']} | {gcc.get(m, float('nan')):.1f} | {errs.get(m, float('nan')):.1e} |"
        )
        summary.append(
            {
                "model": name,
                "autosim_ns": a,
                "casadi_ns": c,
                "ratio": a / c,
                "ratio_fastest_rounds": fast,
                "autosim_ops": ours_ops[m],
                "casadi_ops": g["casadi_ops"],
                "gcc_s": gcc.get(m),
                "max_rel_difference": errs.get(m),
                "nlin": g["nlin"],
                "nw": g["nw"],
                "ny": g["ny"],
            }
        )
    env = os.environ.get
    rustflags = env("AUTOSIM_RUSTFLAGS", "-C target-cpu=native")
    flags = f"`RUSTFLAGS={rustflags}`" if rustflags else "default flags (no `RUSTFLAGS`)"
    text = f"""# autosim's `linearize()` against CasADi's `jacobian`, generated C

`bash bench/jacobian/run.sh`, {datetime.datetime.now(datetime.UTC):%Y-%m-%d %H:%M} UTC,
autosim at {env("BENCH_GIT", "an unknown commit")}, {env("ROUNDS", "?")} rounds,
{cpu_model()} ({os.cpu_count()} CPUs), {env("BENCH_RUSTC", "rustc ?")}, {env("BENCH_GCC", "gcc ?")}, load average at the start of the rounds {env("BENCH_LOAD", "?")}.

Median ns per call over every batch (1000 calls, one at each of 1000 states
shared by both programs) of every round; the rounds interleave the two
programs, pinned to one CPU. "Same, fastest rounds" compares each program's
fastest round median instead (timings on this machine are bimodal).
CasADi: `jacobian` of its SX expression graph, `Function(..., {{"cse": True}})`,
`CodeGenerator` C compiled with `gcc -O3 -march=native` (gcc's time per file
in the table); its operations are CasADi's arithmetic instructions (no
inputs, outputs, constants). autosim: the generated `linearize(t, &x)`
(operations: `LINEARIZE_OPS.total()`), compiled with {flags}; the bench
crate with every model {build_text()}. Chains: their state Jacobian A
only (autosim with `outputs = []`; CasADi differentiates its
articulated-body algorithm, `casadi_aba.py`), at q uniform in [-π, π], speeds
in [-1, 1]. Bicycle (if present): A, B, C, D on its constraints (see
`casadi_bicycle.py`). Both programs' matrices agree at the first 20 states of
each model to the last column (largest over states of
max|autosim − CasADi| / max|CasADi|; the script fails above {env("TOL", "?")}).

{chr(10).join(table)}
"""
    with open(md_path, "w") as fh:
        fh.write(text)
    with open(jsonl_path, "w") as fh:
        fh.writelines(json.dumps(s) + "\n" for s in summary)
    print(text)


if __name__ == "__main__":
    main()
