"""Tables of bench/peers/run.sh: median ns per call of every (tool, method)
over all batches of all rounds, autosim against the fastest peer. The
environment gives BENCH_GIT (bench/common.sh's bench_git) and ROUNDS for the
header."""
import json, statistics, sys, datetime, os

out, md_path, jsonl_path = sys.argv[1], sys.argv[2], sys.argv[3]
rows = [json.loads(l) for l in open(os.path.join(out, "rounds.jsonl")) if l.strip()]
batches = {}
for r in rows:
    batches.setdefault((r["kind"], r["n"], r["tool"], r["method"]), []).extend(r["batches_ns"])
# Forward dynamics only: Pinocchio's RNEA (inverse dynamics) and SymPy's bare
# mass-matrix evaluation (no solve) do a different job.
NOT_FORWARD = {"rnea", "sympy_eval_M_f"}
med = {k: statistics.median(v) for k, v in batches.items() if k[3] not in NOT_FORWARD}
# This machine's timings are bimodal (the same binary's round medians jump
# by up to 1.4x between rounds), so also the fastest round's median of each
# program: the ratio of those compares both in their fast mode.
best_round = {}
for r in rows:
    k = (r["kind"], r["n"], r["tool"], r["method"])
    if k in med:
        best_round[k] = min(best_round.get(k, float("inf")), statistics.median(r["batches_ns"]))
# the chains, then the satellite (autosim only)
cases = sorted({(k[0], k[1]) for k in med}, key=lambda c: (c[0] == "satellite", c[0], c[1]))
table = ["| model | autosim | Pinocchio (best method) | CasADi (best method) | SymPy C | autosim / fastest peer | same, fastest rounds |",
         "|---|---:|---:|---:|---:|---:|---:|"]
summary = []
for kind, n in cases:
    def best(tool):
        v = [(t, m) for (k, nn, tt, m), t in med.items() if k == kind and nn == n and tt == tool]
        return min(v) if v else None
    a = best("autosim"); p = best("pinocchio"); c = best("casadi"); s = best("sympy")
    if not a:
        continue  # a peer's model without autosim's (not in this run)
    peers = [x[0] for x in (p, c, s) if x]
    ratio = a[0] / min(peers) if a and peers else None
    fast_a = [t for (k, nn, tt, m), t in best_round.items() if k == kind and nn == n and tt == "autosim"]
    fast_p = [t for (k, nn, tt, m), t in best_round.items() if k == kind and nn == n and tt != "autosim"]
    fast_ratio = min(fast_a) / min(fast_p) if fast_a and fast_p else None
    fmt = lambda x: f"{x[0]:.1f} ({x[1]})" if x else "—"
    name = f"chain-{kind}-{n}" if kind in ("planar", "spatial") else kind
    table.append(f"| {name} | {a[0]:.1f} | {fmt(p)} | {fmt(c)} | {fmt(s)} | "
                 + (f"{ratio:.2f}" if ratio else "—") + " | "
                 + (f"{fast_ratio:.2f}" if fast_ratio else "—") + " |")
    summary.append({"model": name, "autosim_ns": a[0],
                    "pinocchio": p, "casadi": c, "sympy": s, "ratio_to_fastest_peer": ratio,
                    "ratio_fastest_rounds": fast_ratio})
comp = [json.loads(l) for l in open(os.path.join(out, "compile.jsonl")) if l.strip()] \
    if os.path.exists(os.path.join(out, "compile.jsonl")) else []
ctab = ["| model | generated lines | rustc (release, s) |", "|---|---:|---:|"]
for c in comp:
    ctab.append(f"| chain-{c['kind']}-{c['n']} | {c['lines']} | {c['rustc_s']:.1f} |")
rustflags = os.environ.get("AUTOSIM_RUSTFLAGS", "-C target-cpu=native")
flags = f"`RUSTFLAGS={rustflags}`" if rustflags else "default flags (no `RUSTFLAGS`: the x86-64 baseline, with the x86-64-v3 or x86-64-v4 copy of `derivatives` chosen at run time)"
compile_text = "" if not comp else f"""Compile cost of the generated module (one model per crate, its program
calling `derivatives`, dependencies built, `cargo build --release` with
default flags after touching the source; the model compiler itself runs
in the macro; more models and settings: `bench/compile`):

{chr(10).join(ctab)}
"""
text = f"""# autosim against the peers on the chain models, and the satellite

`bash bench/peers/run.sh` (after the peers' own scripts in `../shared/bench`),
{datetime.datetime.now(datetime.timezone.utc):%Y-%m-%d %H:%M} UTC, autosim at
{os.environ.get("BENCH_GIT", "an unknown commit")}, {os.environ.get("ROUNDS", "?")} rounds, on
{os.environ.get("BENCH_CPU", "an unrecorded CPU")} (`/proc/cpuinfo`).
Median ns per forward-dynamics call over
every batch (1000 calls over 1000 random states) of every round; the rounds
interleave the programs, so load hits all alike. The best method of each
peer is shown with its name. The last column compares the fastest round's
median of each program instead (timings here are bimodal). Everything is
compiled for this machine's CPU: the peers with gcc/g++ `-O3 -march=native`,
autosim's generated Rust with {flags}. Load average
at the start: {os.environ.get("BENCH_LOAD", "?")}. The satellite (the
paper's spacecraft; no peer has it) is timed the same way.

{chr(10).join(table)}

{compile_text}"""
open(md_path, "w").write(text)
with open(jsonl_path, "w") as f:
    for s in summary:
        f.write(json.dumps(s) + "\n")
print(text)
