#!/usr/bin/env bash
# SymPy (KanesMethod) derivation time vs autosim compile time for chain-spatial-n.
#
#   bench/sympy/run.sh              n = 1 2 3 5 (SymPy) ; autosim for the same n
#   SYMPY_N="1 2 3 5 10" bench/sympy/run.sh      also n = 10 (SymPy derivation ~2-3 min,
#                                                lambdify + check several more minutes)
#
# Writes bench/sympy/sympy.jsonl, autosim_phases.txt and results.md. Uses the default cargo
# target dir unless CARGO_TARGET_DIR is set. Everything runs under nice -n 10. SymPy runs once
# per n (fresh interpreter); the autosim phases example runs PHASE_REPS times (default 7) per
# model and the fastest run is reported.
set -euo pipefail
source "$(dirname "${BASH_SOURCE[0]}")/../common.sh"   # HERE, REPO, NICE, PY

SYMPY_N="${SYMPY_N:-1 2 3 5}"
AUTOSIM_N="${AUTOSIM_N:-1 2 3 5 7 10 20}"
PHASE_REPS="${PHASE_REPS:-7}"

$PY -c "import sympy, numpy" 2>/dev/null || $PY -m pip install sympy numpy >&2

# --- SymPy --------------------------------------------------------------------------------
echo "== SymPy KanesMethod: n = $SYMPY_N" >&2
: > "$HERE/sympy.jsonl"
for n in $SYMPY_N; do
  $NICE $PY "$HERE/kane_chain.py" "$n" | tee -a "$HERE/sympy.jsonl" >&2
done

# --- autosim ------------------------------------------------------------------------------
echo "== building autosim-core phases example" >&2
(cd "$REPO" && $NICE cargo build -q --release -p autosim-core --example phases >&2)
: > "$HERE/autosim_phases.txt"
for n in $AUTOSIM_N; do
  f="examples/models/chain_spatial_$n.sim"
  [ -f "$REPO/$f" ] || continue
  for r in $(seq 1 "$PHASE_REPS"); do
    line="$(cd "$REPO" && $NICE cargo run -q --release -p autosim-core --example phases -- "$f")"
    echo "chain-spatial-$n run $r: $line" | tee -a "$HERE/autosim_phases.txt" >&2
  done
done

# --- results.md ---------------------------------------------------------------------------
export BENCH_CPU="$(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2- | sed 's/^ *//')"
export BENCH_REPS="$PHASE_REPS"
export BENCH_SYMPY_N="$SYMPY_N"
run_report <<'EOF'   # common.sh: adds BENCH_NPROC, _RUSTC, _LOAD, _DATE, _GIT; sys.argv[1] = HERE
import json, os, re, sys
here = sys.argv[1]
env = os.environ
UNIT = {"ns": 1e-9, "µs": 1e-6, "us": 1e-6, "ms": 1e-3, "s": 1.0}
PHASES = ["parse", "resolve", "equations", "program", "emit"]

def dur(text):
    m = re.fullmatch(r"([0-9.]+)(ns|µs|us|ms|s)", text.strip())
    return float(m.group(1)) * UNIT[m.group(2)]

auto = {}  # model -> list of dict(phase -> seconds)
for line in open(os.path.join(here, "autosim_phases.txt"), encoding="utf-8"):
    model, rest = line.split(" run ", 1)
    rest = rest.split(": ", 1)[1]
    ph = {}
    for name in PHASES + ["format"]:
        m = re.search(rf"\b{name} ([0-9.]+(?:ns|µs|us|ms|s))", rest)
        ph[name] = dur(m.group(1))
    m = re.search(r"\((\d+) lines", rest)
    ph["lines"] = int(m.group(1)) if m else None
    auto.setdefault(model, []).append(ph)

def best(model):
    runs = auto.get(model)
    if not runs:
        return None
    return min(runs, key=lambda r: sum(r[p] for p in PHASES))

sym = [json.loads(l) for l in open(os.path.join(here, "sympy.jsonl")) if l.strip()]

def s_fmt(x):
    if x is None:
        return "n/a"
    if x >= 1:
        return f"{x:.2f} s"
    if x >= 1e-3:
        return f"{x * 1e3:.1f} ms"
    return f"{x * 1e6:.0f} µs"

rows = ["| model | SymPy derive (setup + kanes_equations + M, f) | SymPy lambdify | "
        "reference JSON derivation_s | autosim parse..emit | ratio SymPy derive / autosim | "
        "SymPy check vs reference |",
        "|---|---:|---:|---:|---:|---:|---|"]
for r in sym:
    b = best(r["model"])
    a = sum(b[p] for p in PHASES) if b else None
    chk = r.get("check")
    chk = f"{chk['status']} ({chk['max_rel_err_du']:.1e}, {chk['samples']} samples)" \
        if isinstance(chk, dict) else (chk or "not run")
    ratio = f"{r['derive_s'] / a:,.0f}x" if a else "n/a"
    rows.append(f"| {r['model']} | {s_fmt(r['derive_s'])} | {s_fmt(r.get('lambdify_s'))} | "
                f"{s_fmt(r.get('reference_derivation_s'))} | {s_fmt(a)} | {ratio} | {chk} |")
main = "\n".join(rows)

arows = ["| model | " + " | ".join(PHASES) + " | sum parse..emit | format | lines | runs (sum) |",
         "|---|" + "---:|" * (len(PHASES) + 3) + "---|"]
for model in auto:
    b = best(model)
    runs = ", ".join(s_fmt(sum(r[p] for p in PHASES)) for r in auto[model])
    arows.append(f"| {model} | " + " | ".join(s_fmt(b[p]) for p in PHASES) +
                 f" | {s_fmt(sum(b[p] for p in PHASES))} | {s_fmt(b['format'])} | "
                 f"{b['lines']} | {runs} |")
phase_table = "\n".join(arows)

srows = ["| model | setup | kanes_equations | mass_matrix + forcing | derive total |",
         "|---|---:|---:|---:|---:|"]
for r in sym:
    srows.append(f"| {r['model']} | {s_fmt(r['setup_s'])} | {s_fmt(r['kanes_equations_s'])} | "
                 f"{s_fmt(r['mass_matrix_forcing_s'])} | {s_fmt(r['derive_s'])} |")
sympy_table = "\n".join(srows)

print(main)
print()
print(phase_table)
ver = sym[0] if sym else {}
md = f"""# SymPy (Kane's method) derivation vs autosim compile time: chain-spatial-n

Generated by `bench/sympy/run.sh` on {env['BENCH_DATE']}.

- SymPy {ver.get('sympy', '?')} on CPython {ver.get('python', '?')}:
  `bench/sympy/kane_chain.py` builds chain-spatial-n of shared/reference-models.md with
  `sympy.physics.mechanics.KanesMethod` (symbolic parameters, `orient_axis`,
  `v2pt_theory`, `RigidBody`, gravity forces, spring-damper torque pairs) and times the
  derivation: model setup + `kanes_equations` + `mass_matrix`/`forcing`. Each n runs in a
  fresh interpreter. "lambdify" (substituting the parameters, `lambdify(..., cse=True)`) is
  timed separately and then used to check du = M^-1 f against every sample of
  `shared/reference/chain-spatial-n.json`.
- autosim: `cargo run --release -p autosim-core --example phases -- examples/models/chain_spatial_n.sim`;
  "parse..emit" = parse + resolve + equations + program + emit (model text to generated Rust
  token stream; `format` = pretty-printing the token stream, listed separately). The minimum
  of {env['BENCH_REPS']} runs is reported. This is the compiler library's own time, not rustc compiling the
  generated code (which `autosim::model!` users also pay).
- "reference JSON derivation_s" is the `derivation_s` field recorded by the generator of
  shared/reference (same SymPy version; other machine/run, for orientation only).

## Derivation / compile time

{main}

## SymPy steps

{sympy_table}

## autosim phases (best of {env['BENCH_REPS']} runs)

{phase_table}

## Machine

- autosim measured at {env['BENCH_GIT']} (the phases example is built from the working tree)
- nproc: {env['BENCH_NPROC']}; CPU: {env['BENCH_CPU']}; {env['BENCH_RUSTC']}
- /proc/loadavg at the end: {env['BENCH_LOAD']}

The machine was shared with other jobs (Rust compiles on the same 2 cores); everything ran
under `nice -n 10`. autosim numbers are the minimum over {env['BENCH_REPS']} runs; SymPy derivations
(seconds to minutes) were run once each, so they carry the load of the moment (perhaps
+-30 %); the ratios are orders of magnitude, which that noise does not change.

## Commands

```
export CARGO_TARGET_DIR=/work/target-bench   # optional
SYMPY_N="{env['BENCH_SYMPY_N']}" bench/sympy/run.sh
```

which runs, under `nice -n 10`:

```
python3 bench/sympy/kane_chain.py <n>          # for each n in SYMPY_N, once
cargo run -q --release -p autosim-core --example phases -- examples/models/chain_spatial_<n>.sim
                                               # for n = 1 2 3 5 7 10 20, {env['BENCH_REPS']} times each
```

Raw data: `sympy.jsonl`, `autosim_phases.txt`.
"""
with open(os.path.join(here, "results.md"), "w") as f:
    f.write(md)
print(f"\nwrote {os.path.join(here, 'results.md')}")
EOF
