#!/usr/bin/env bash
# autosim against the peers of ../shared/bench on the chain models (and the
# satellite, which only autosim has), in one interleaved run: Pinocchio (ABA, CRBA variants; pin_bench), CasADi-generated
# C of the articulated-body and CRBA algorithms (cas_bench), SymPy + cse C
# where it exists, and autosim's generated derivatives() (autosim_bench,
# this crate), all timed the same way (1000 random states, batches of 1000
# calls, the same JSON lines), one round of each program in turn. Everything
# is compiled for this machine's CPU (gcc -O3 -march=native for the peers,
# rustc -C target-cpu=native for autosim).
#
#   bash bench/peers/run.sh        (from the repository root)
#   AUTOSIM_BENCH_RUSTFLAGS= RESULTS=results-default COMPILE_COST=0 bash bench/peers/run.sh
#                                  (autosim at default flags, its run-time
#                                  dispatch; tables in results-default.*)
#
# Needs the peers built by their own scripts first (each installs what it
# needs; about 30 minutes together):
#   NS_SYMPY="1 2 3 5" bash ../shared/bench/perf/run.sh    # -> /tmp/anchors
#   bash ../shared/bench/casadi/run.sh   # -> /tmp/casadi (ABA and CRBA; 4 min here)
# Then this script (about 10 minutes): generates chain-{planar,spatial}-n for
# n = 1, 2, 3, 5, 7, 10, 20, 50, builds autosim_bench, runs ROUNDS (default 5)
# interleaved rounds pinned to one CPU when taskset exists, measures the
# compile cost (generated lines, rustc time) for n = 10, 20, 50, and writes
# bench/peers/results.md and results.jsonl.
set -euo pipefail
source "$(dirname "${BASH_SOURCE[0]}")/../common.sh"   # HERE, REPO, NICE, PY
AROOT="${ANCHORS_ROOT:-/tmp/anchors}"
CROOT="${CASADI_ROOT:-/tmp/casadi}"
ROUNDS="${ROUNDS:-5}"
RESULTS="${RESULTS:-results}"           # tables: $RESULTS.md, $RESULTS.jsonl
COMPILE_COST="${COMPILE_COST:-1}"      # 0 skips step 4
RUSTFLAGS_BENCH="${AUTOSIM_BENCH_RUSTFLAGS--C target-cpu=native}"
LOAD="$(cut -d' ' -f1-3 /proc/loadavg)"
TARGET="${CARGO_TARGET_DIR:-$REPO/target/peers}"
PIN="$AROOT/build/pin_bench"
CAS="$CROOT/build/cas_bench"
[ -x "$PIN" ] || { echo "no $PIN: run ../shared/bench/perf/run.sh first"; exit 1; }
[ -x "$CAS" ] || { echo "no $CAS: run ../shared/bench/casadi/run.sh first"; exit 1; }
PINCPU=(); command -v taskset >/dev/null && PINCPU=(taskset -c 1)

echo "== 1. models"
rm -rf "$HERE/models" && mkdir -p "$HERE/models"
(cd "$REPO" && cargo run -q --release --example gen_chains -- "$HERE/models" 1 2 3 5 7 10 20 50)
cp "$REPO/examples/models/satellite.sim" "$HERE/models/"

echo "== 2. autosim_bench (release, RUSTFLAGS='$RUSTFLAGS_BENCH'; load average $LOAD)"
# The peers' C and C++ are compiled for this machine's CPU (-march=native);
# the generated Rust gets the same (AUTOSIM_BENCH_RUSTFLAGS to change it).
(cd "$HERE" && RUSTFLAGS="$RUSTFLAGS_BENCH" \
  CARGO_TARGET_DIR="$TARGET" cargo build -q --release)
BENCH="$TARGET/release/autosim-peer-bench"

echo "== 3. $ROUNDS interleaved rounds (${PINCPU[*]:-unpinned})"
OUT="$HERE/out"; mkdir -p "$OUT"
: > "$OUT/rounds.jsonl"
# SymPy + cse C: one binary per derived model (work/<kind>_<n>_bench), the
# model's parameter values on its command line; it prints no kind, so add it.
SYM=()
for exe in "$AROOT"/work/*_bench; do [ -x "$exe" ] && SYM+=("$exe"); done
sym_round() {  # sym_round EXE
  local base kind params
  base="$(basename "$1" _bench)"; kind="${base%_*}"
  params="$($PY -c 'import json,sys; print(" ".join(repr(v) for v in json.load(open(sys.argv[1]))["param_values"]))' "$AROOT/work/$base.json")"
  # shellcheck disable=SC2086
  "${PINCPU[@]}" "$1" bench $params 2>/dev/null \
    | sed "s/^{/{\"tool\": \"sympy\", \"kind\": \"$kind\", /"
}
for r in $(seq 1 "$ROUNDS"); do
  "${PINCPU[@]}" "$PIN" bench 1 2>/dev/null | sed 's/"method": "/"tool": "pinocchio", "method": "/' >> "$OUT/rounds.jsonl"
  "${PINCPU[@]}" "$CAS" bench 1 | sed 's/"method": "/"tool": "casadi", "method": "/' >> "$OUT/rounds.jsonl"
  for exe in "${SYM[@]}"; do sym_round "$exe" >> "$OUT/rounds.jsonl"; done
  "${PINCPU[@]}" "$BENCH" bench 1 | sed 's/"method": "/"tool": "autosim", "method": "/' >> "$OUT/rounds.jsonl"
  echo "round $r/$ROUNDS done"
done

echo "== 4. compile cost (one model per crate, release, dependencies built)"
: > "$OUT/compile.jsonl"
[ "$COMPILE_COST" = 1 ] || echo "skipped (COMPILE_COST=$COMPILE_COST)"
[ "$COMPILE_COST" = 1 ] && for kind in spatial planar; do
  for n in 10 20 50; do
    CRATE="$TARGET/compile-$kind-$n"
    model_crate "$CRATE" "compile-$kind-$n"
    cp "$HERE/models/chain_${kind}_$n.sim" "$CRATE/model.sim"
    # The program calls `derivatives`: rustc compiles only what is reachable,
    # and a model nothing calls would cost a fraction of what it costs a user.
    cat > "$CRATE/src/main.rs" <<'RS'
autosim::model!(file = "model.sim", name = Bench);
use autosim::runtime::{Model, StateArray};
fn main() {
    let mut model = bench::Bench::new();
    let x = std::hint::black_box(model.initial_state());
    let mut dx = <bench::Bench as Model>::State::zeros();
    let _ = model.derivatives(0.0, &x, &mut dx);
    std::hint::black_box(dx);
}
RS
    (cd "$CRATE" && CARGO_TARGET_DIR="$TARGET" cargo build -q --release)  # dependencies
    touch "$CRATE/src/main.rs"
    start=$(date +%s.%N)
    (cd "$CRATE" && CARGO_TARGET_DIR="$TARGET" cargo build -q --release)
    end=$(date +%s.%N)
    lines=$(cd "$REPO" && cargo run -q --release -p autosim-core --example emit -- "$HERE/models/chain_${kind}_$n.sim" | wc -l)
    secs=$(printf '%.3f' "$(echo "$end - $start" | bc)")
    echo "{\"kind\": \"$kind\", \"n\": $n, \"lines\": $lines, \"rustc_s\": $secs}" >> "$OUT/compile.jsonl"
    echo "$kind-$n: $lines lines, $secs s"
  done
done

echo "== 5. tables"
CPU="$(grep -m1 'model name' /proc/cpuinfo 2>/dev/null | cut -d: -f2 | xargs || true)"
BENCH_GIT="$(bench_git)" ROUNDS="$ROUNDS" BENCH_LOAD="$LOAD" AUTOSIM_RUSTFLAGS="$RUSTFLAGS_BENCH" BENCH_CPU="${CPU:-an unrecorded CPU}" \
  $PY "$HERE/report.py" "$OUT" "$HERE/$RESULTS.md" "$HERE/$RESULTS.jsonl"
