#!/usr/bin/env bash
# Pinocchio vs autosim on the chain models of shared/reference-models.md.
#
#   bench/pinocchio/run.sh            (from anywhere; uses the default cargo target dir
#                                      unless CARGO_TARGET_DIR is set)
#
# 1. installs Pinocchio + Eigen headers from PyPI (pip install pin cmeel-eigen) if missing;
# 2. compiles chain_aba.cpp in three builds (binaries in bench/pinocchio/build/):
#      native    header-only templates, g++ -O3 -DNDEBUG -march=native   (the headline numbers)
#      portable  header-only templates, g++ -O3 -DNDEBUG (baseline x86-64, as the Rust build's baseline copy)
#      lib       PINOCCHIO_ENABLE_TEMPLATE_INSTANTIATION, no -march=native: aba, crba,
#                nonLinearEffects and cholesky::decompose run the pip wheel's precompiled
#                libpinocchio_default.so (cholesky::solve on a vector block is compiled locally)
#    (set PIN_BUILDS="native" to build/run only some of them);
# 3. runs each build: correctness checks against shared/reference/*.json (all samples, 1e-9
#    relative to the sample's largest |du|), then timings -> results.jsonl, checks.jsonl;
# 4. runs `cargo run --release --example perf` REPS times (default 5) -> autosim_perf.jsonl;
# 5. prints the table and writes results.md.
#
# The machine may be shared: every compile and timing run is niced (nice -n 10); each
# timing is a median over 201 rounds x 512 random states, repeated REPS times (Pinocchio: the
# repetition is the outer loop over all cases in one process; autosim: REPS separate perf runs)
# and the median of the medians is reported (a typical run, not the best one).
set -euo pipefail
source "$(dirname "${BASH_SOURCE[0]}")/../common.sh"   # HERE, REPO, NICE, PY

REF_DIR="${REF_DIR:-$REPO/tests/reference}"
REPS="${REPS:-5}"
PIN_BUILDS="${PIN_BUILDS:-native portable lib}"
export BENCH_LOAD_START="$(cat /proc/loadavg)"

# --- 1. dependencies ----------------------------------------------------------------------
SITE="$($PY -c "import site; print(site.getsitepackages()[0])")"
PREFIX="$SITE/cmeel.prefix"
if [ ! -f "$PREFIX/include/pinocchio/algorithm/aba.hpp" ] || [ ! -d "$PREFIX/lib" ]; then
  echo "== installing pin" >&2
  $PY -m pip install pin >&2
fi
if [ ! -f "$PREFIX/include/eigen3/Eigen/Core" ]; then
  echo "== installing cmeel-eigen" >&2
  $PY -m pip install cmeel-eigen >&2
fi

# --- 2. compile ---------------------------------------------------------------------------
mkdir -p "$HERE/build"
# Definitions of the pinocchio::pinocchio_headers CMake target (lib/cmake/pinocchio).
DEFS="-DBOOST_MPL_LIMIT_LIST_SIZE=30 -DBOOST_MPL_LIMIT_VECTOR_SIZE=30
      -DBOOST_MPL_CFG_NO_PREPROCESSED_HEADERS -DBOOST_FUSION_INVOKE_MAX_ARITY=12"
INCS="-I$PREFIX/include -I$PREFIX/include/eigen3"
LIBS="-L$PREFIX/lib -Wl,-rpath,$PREFIX/lib"
# GCC 12 false positive inside Eigen's AVX-512 code paths.
WARN="-Wno-stringop-overread"
flags_for() {
  case "$1" in
    native)   echo "-O3 -DNDEBUG -march=native" ;;
    portable) echo "-O3 -DNDEBUG" ;;
    # No -march=native here: the wheel's library is built for baseline x86-64, and Eigen's
    # alignment (EIGEN_MAX_ALIGN_BYTES) follows the ISA, so mixing the two breaks the ABI
    # of Model/Data (observed: "double free or corruption").
    lib)      echo "-O3 -DNDEBUG -DPINOCCHIO_ENABLE_TEMPLATE_INSTANTIATION" ;;
    *) echo "unknown build $1" >&2; exit 2 ;;
  esac
}
libs_for() {
  case "$1" in
    lib) echo "-lpinocchio_default" ;;
    *) echo "" ;;
  esac
}
for b in $PIN_BUILDS; do
  bin="$HERE/build/chain_aba_$b"
  flags="$(flags_for "$b")"
  cmd="g++ -std=c++17 $flags $WARN $DEFS $INCS $HERE/chain_aba.cpp -o $bin $LIBS $(libs_for "$b")"
  stamp="$bin.cmd"
  if [ ! -x "$bin" ] || [ "$HERE/chain_aba.cpp" -nt "$bin" ] || [ "$(cat "$stamp" 2>/dev/null)" != "$cmd" ]; then
    echo "== compiling $b: $(echo $cmd | sed "s|$PREFIX|\$PREFIX|g")" >&2
    $NICE $cmd
    echo "$cmd" > "$stamp"
  fi
done

# --- 3. Pinocchio checks + timings --------------------------------------------------------
: > "$HERE/results.jsonl"
: > "$HERE/checks.jsonl"
for b in $PIN_BUILDS; do
  echo "== running chain_aba ($b)" >&2
  out="$($NICE "$HERE/build/chain_aba_$b" --ref-dir "$REF_DIR" --reps "$REPS" --build "$b")" || {
    echo "$out"; echo "chain_aba ($b) failed" >&2; exit 1; }
  echo "$out" | grep '"check"' | tee -a "$HERE/checks.jsonl" >&2
  echo "$out" | grep '"ns_per_call"' >> "$HERE/results.jsonl"
done

# --- 4. autosim perf ----------------------------------------------------------------------
echo "== building autosim perf (target dir: ${CARGO_TARGET_DIR:-default})" >&2
(cd "$REPO" && $NICE cargo build --release --example perf >&2)
: > "$HERE/autosim_perf.jsonl"
for r in $(seq 1 "$REPS"); do
  echo "== cargo run --release --example perf ($r/$REPS)" >&2
  (cd "$REPO" && $NICE cargo run -q --release --example perf) |
    sed "s/}\$/, \"run\": $r}/" >> "$HERE/autosim_perf.jsonl"
done

# --- 5. table + results.md ----------------------------------------------------------------
cpuinfo() { grep -m1 "^$1" /proc/cpuinfo | cut -d: -f2- | sed 's/^ *//'; }
CPU="$(cpuinfo 'model name'), family $(cpuinfo 'cpu family') model $(cpuinfo 'model') stepping $(cpuinfo 'stepping'), $(cpuinfo 'cpu MHz') MHz, cache $(cpuinfo 'cache size')"
FLAGS_AVX="$(grep -m1 '^flags' /proc/cpuinfo | tr ' ' '\n' | grep -E '^(avx2|avx512f|fma)$' | paste -sd, -)"
export BENCH_CPU="$CPU (cpu flags incl. $FLAGS_AVX)"
export BENCH_GXX="$(g++ --version | head -1)"
export BENCH_CARGO="$(cd "$REPO" && cargo --version)"
export BENCH_PIN="$($PY -c 'import pinocchio; print(pinocchio.__version__)' 2>/dev/null || echo '?')"
export BENCH_EIGEN="$($PY -m pip show cmeel-eigen 2>/dev/null | awk '/^Version/{print $2}')"
export BENCH_REPS="$REPS"
export BENCH_BUILDS="$PIN_BUILDS"
export BENCH_TARGET="${CARGO_TARGET_DIR:-default}"
export BENCH_PREFIX="$PREFIX"
run_report <<'EOF'   # common.sh: adds BENCH_NPROC, _RUSTC, _LOAD, _DATE, _GIT; sys.argv[1] = HERE
import json, os, statistics, sys
here = sys.argv[1]
env = os.environ

def lines(name):
    with open(os.path.join(here, name)) as f:
        return [json.loads(l) for l in f if l.strip()]

auto = {}
for r in lines("autosim_perf.jsonl"):
    if "ns_per_call" in r:  # the perf example also prints linearization lines
        auto.setdefault(r["model"], []).append(r["ns_per_call"])
pin = {}
for r in lines("results.jsonl"):
    pin[(r["model"], r["algorithm"], r["build"])] = r
checks = lines("checks.jsonl")

models = ["chain-spatial-1", "chain-spatial-2", "chain-spatial-3", "chain-spatial-5",
          "chain-spatial-7", "chain-spatial-10", "chain-spatial-20", "chain-planar-10"]
builds = env["BENCH_BUILDS"].split()
head = builds[0]

def ns(model, alg, build):
    # The median of the repetitions' medians (a typical run, not the best).
    r = pin.get((model, alg, build))
    return statistics.median(r["medians"]) if r else None

def fmt(x, spec=".1f"):
    return "n/a" if x is None else format(x, spec)

out = []
out.append("| model | n_states | autosim ns/call | Pinocchio ABA ns/call | ratio ABA/autosim "
           "| Pinocchio CRBA+NLE+Cholesky ns/call | ratio CRBA/autosim |")
out.append("|---|---:|---:|---:|---:|---:|---:|")
for m in models:
    a = statistics.median(auto[m]) if m in auto else None
    p = ns(m, "aba", head)
    c = ns(m, "crba-chol", head)
    n_states = pin.get((m, "aba", head), {}).get("n_states", "")
    out.append(f"| {m} | {n_states} | {fmt(a)} | {fmt(p)} | "
               f"{fmt(p / a if a and p else None, '.1f')}x | {fmt(c)} | "
               f"{fmt(c / a if a and c else None, '.1f')}x |")
main_table = "\n".join(out)
print(f"\nautosim vs Pinocchio ({head} build), median of {env['BENCH_REPS']} medians:\n")
print(main_table)

var = []
if len(builds) > 1:
    hdr = "| model | autosim | " + " | ".join(f"ABA {b}" for b in builds) + " | " + \
          " | ".join(f"CRBA-chol {b}" for b in builds) + " |"
    var.append(hdr)
    var.append("|---|" + "---:|" * (1 + 2 * len(builds)))
    for m in models:
        a = statistics.median(auto[m]) if m in auto else None
        cells = [fmt(ns(m, "aba", b)) for b in builds] + [fmt(ns(m, "crba-chol", b)) for b in builds]
        var.append(f"| {m} | {fmt(a)} | " + " | ".join(cells) + " |")
    print("\nAll Pinocchio builds (ns/call):\n")
    print("\n".join(var))

spread = ["| model | autosim medians (one per perf run) | Pinocchio ABA medians | Pinocchio CRBA-chol medians |",
          "|---|---|---|---|"]
for m in models:
    pa = pin.get((m, "aba", head), {}).get("medians", [])
    pc = pin.get((m, "crba-chol", head), {}).get("medians", [])
    spread.append(f"| {m} | {', '.join(fmt(x) for x in auto.get(m, []))} | "
                  f"{', '.join(fmt(x) for x in pa)} | {', '.join(fmt(x) for x in pc)} |")

chk = ["| model | algorithm | build | samples | max rel. error of du | status |",
       "|---|---|---|---:|---:|---|"]
for c in checks:
    if c.get("build") != head:
        continue
    chk.append(f"| {c['check']} | {c.get('algorithm', '')} | {c.get('build', '')} | "
               f"{c.get('samples', '')} | {c.get('max_rel_err_du', 0):.2e} | {c['status']} |")
n_pass = sum(c["status"] == "pass" for c in checks)
other = []
for b in builds[1:]:
    cb = [c for c in checks if c.get("build") == b]
    if cb:
        other.append(f"- build `{b}`: {sum(c['status'] == 'pass' for c in cb)}/{len(cb)} pass, "
                     f"worst {max(c.get('max_rel_err_du', 0) for c in cb):.2e}")
print(f"\nCorrectness: {n_pass}/{len(checks)} checks pass "
      f"(worst {max(c.get('max_rel_err_du', 0) for c in checks):.2e}, tolerance 1e-9)")

md = f"""# Pinocchio vs autosim: forward dynamics of the chain models

Generated by `bench/pinocchio/run.sh` on {env['BENCH_DATE']}.

Each number is the median ns per call of one full state-derivative evaluation at 512 random
states (q uniform in [-pi, pi], v uniform in [-2, 2]), 201 timed rounds over all 512 states
after a warm-up. Pinocchio's call includes the joint torque tau = -k q - c v and writes
xdot = [v; ddq], like autosim's generated `derivatives()`. "ratio" = Pinocchio ns / autosim ns
(how many times faster the generated code is).

- autosim: `cargo run --release --example perf` (examples/perf.rs), default release profile
  (no `-C target-cpu=native`: the x86-64 baseline, with the x86-64-v3 or x86-64-v4 copy of
  `derivatives` chosen at run time where the processor has it; README, "At default flags").
- Pinocchio {env['BENCH_PIN']} (PyPI `pin`, headers and libs from the cmeel prefix), Eigen
  {env['BENCH_EIGEN']} (PyPI `cmeel-eigen`), `bench/pinocchio/chain_aba.cpp`:
  - `aba`: `pinocchio::aba(model, data, q, v, tau)` (articulated-body algorithm, O(n),
    LOCAL convention, the default);
  - `crba-chol`: `pinocchio::crba` + `pinocchio::nonLinearEffects` +
    `pinocchio::cholesky::decompose/solve` (M(q) ddq = tau - b(q, v), the formulation autosim
    uses);
  - builds: `native` = header-only templates compiled into the benchmark with
    `g++ -std=c++17 -O3 -DNDEBUG -march=native` (the headline numbers); `portable` = the same
    without `-march=native`; `lib` = `-DPINOCCHIO_ENABLE_TEMPLATE_INSTANTIATION`
    (no `-march=native`, which would break Eigen's ABI against the wheel), so `aba`, `crba`,
    `nonLinearEffects` and `cholesky::decompose` run the wheel's precompiled
    `libpinocchio_default.so` (arguments passed as `Eigen::Ref<const VectorXd>`, the
    instantiated type; `cholesky::solve` on a vector block is still compiled locally).
  - Models use Pinocchio's generic `JointModel` (variant) with `JointModelRX/RY/RZ`, as
    a user building a model programmatically or from URDF would.

## autosim vs Pinocchio ({head} build)

{main_table}

## All Pinocchio builds (ns/call)

{chr(10).join(var) if var else '(only one build run)'}

## Spread of the repeated medians (the tables report their median)

{chr(10).join(spread)}

## Correctness (before timing)

Pinocchio's ddq against the SymPy/Kane reference samples in `shared/reference/<model>.json`
(every sample of every chain file present, 20 per file), error = max |ddq - du| / max |du|
per sample; the parameters in each file are also compared with the ones the program computes
from reference-models.md (all equal). {n_pass}/{len(checks)} checks pass over all builds;
table for the `{head}` build:

{chr(10).join(chk)}

{chr(10).join(other)}

## Machine

- autosim measured at {env['BENCH_GIT']} (perf is built from the working tree)
- nproc: {env['BENCH_NPROC']}
- CPU: {env['BENCH_CPU']}
- {env['BENCH_GXX']}
- {env['BENCH_RUSTC']}; {env['BENCH_CARGO']} (CARGO_TARGET_DIR: {env['BENCH_TARGET']})
- Python {sys.version.split()[0]}; cmeel prefix `{env['BENCH_PREFIX']}`
- /proc/loadavg at the start of the run: {env['BENCH_LOAD_START']}; at the end: {env['BENCH_LOAD']}

The machine was shared: other jobs (Rust compiles) were running on the same 2 cores during
the measurement, so absolute times are noisy and probably inflated for both sides. Mitigation:
all runs niced equally (`nice -n 10`); each measurement is a median over 201 rounds (robust to
preemption of single rounds); every measurement was repeated {env['BENCH_REPS']} times, spread over the
run ({env['BENCH_REPS']} passes over all cases in one Pinocchio process per build; {env['BENCH_REPS']} separate `perf`
runs for autosim), and the median of the medians is reported (spread above). Ratios compare numbers taken minutes apart
under possibly different load; treat differences below ~20 % as noise.

## Commands

```
export CARGO_TARGET_DIR=/work/target-bench   # optional; the script uses cargo's default otherwise
bench/pinocchio/run.sh                        # REPS=5 PIN_BUILDS="native portable lib" by default
```

which runs (PREFIX = the cmeel prefix above, everything under `nice -n 10`):

```
g++ -std=c++17 -O3 -DNDEBUG -march=native -Wno-stringop-overread \\
    -DBOOST_MPL_LIMIT_LIST_SIZE=30 -DBOOST_MPL_LIMIT_VECTOR_SIZE=30 \\
    -DBOOST_MPL_CFG_NO_PREPROCESSED_HEADERS -DBOOST_FUSION_INVOKE_MAX_ARITY=12 \\
    -I$PREFIX/include -I$PREFIX/include/eigen3 bench/pinocchio/chain_aba.cpp \\
    -o bench/pinocchio/build/chain_aba_native -L$PREFIX/lib -Wl,-rpath,$PREFIX/lib
    # portable: without -march=native; lib: without -march=native,
    # with -DPINOCCHIO_ENABLE_TEMPLATE_INSTANTIATION and -lpinocchio_default
bench/pinocchio/build/chain_aba_<build> --ref-dir /work/shared/reference --reps {env['BENCH_REPS']} --build <build>
cargo build --release --example perf
cargo run -q --release --example perf        # {env['BENCH_REPS']} times
```

Raw data: `results.jsonl` (Pinocchio timings), `checks.jsonl`, `autosim_perf.jsonl`.
"""
with open(os.path.join(here, "results.md"), "w") as f:
    f.write(md)
print(f"\nwrote {os.path.join(here, 'results.md')}")
EOF
