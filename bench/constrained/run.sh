#!/usr/bin/env bash
# autosim against SymPy's KanesMethod on the constrained models (the
# four-bar, the rolling disc, the Whipple bicycle): SymPy derives each with
# its constraints, cse + C printer, gcc -O3 -march=native (derive.py,
# harness.c); autosim's generated derivatives() (src/main.rs) built twice,
# with default flags (its run-time choice of instruction set) and with
# -C target-cpu=native. Both evaluate the same state derivative at the same
# 1000 random consistent states; compare.py fails the run if they differ by
# more than 1e-12 (relative); then ROUNDS (default 5) interleaved rounds,
# pinned to one CPU when taskset exists, and the tables in results.md.
#
#   bash bench/constrained/run.sh   (from the repository root)
#
# Makes a virtual environment with sympy and numpy under target/ on its first
# run (PYTHON: the interpreter that makes it, default python3). The SymPy
# derivation (about 40 s, the bicycle's cse most of it) is kept in
# target/constrained/out and redone with DERIVE=1.
set -euo pipefail
source "$(dirname "${BASH_SOURCE[0]}")/../common.sh"   # HERE, REPO, NICE, PY
ROUNDS="${ROUNDS:-5}"
LOAD="$(cut -d' ' -f1-3 /proc/loadavg)"
TARGET="$REPO/target/constrained"
OUT="$TARGET/out"
VENV="$REPO/target/constrained-env"
MODELS=(four_bar rolling_disc bicycle)
PINCPU=(); command -v taskset >/dev/null && PINCPU=(taskset -c 1)

echo "== 1. SymPy: derive, cse, C (virtual environment $VENV)"
[ -x "$VENV/bin/python" ] || { $PY -m venv "$VENV" && "$VENV/bin/pip" install -q sympy numpy; }
PY="$VENV/bin/python"
for m in "${MODELS[@]}"; do
  if [ "${DERIVE:-0}" = 1 ] || [ ! -f "$OUT/$m/derive.json" ]; then
    $NICE "$PY" "$HERE/derive.py" "$OUT" "$m"
  fi
done

echo "== 2. gcc -O3 -march=native"
for m in "${MODELS[@]}"; do
  read -r nx npar nu < <("$PY" -c 'import json,sys; d=json.load(open(sys.argv[1])); print(len(d["state_names"]), len(d["parameters"]), d["n_speeds"])' "$OUT/$m/derive.json")
  $NICE gcc -O3 -march=native -I"$HERE" -DMODEL="$m" -DRHS="${m}_rhs" -DEVAL="${m}_eval" \
    -DNX="$nx" -DNPAR="$npar" -DNU="$nu" \
    -o "$OUT/$m/sympy_bench" "$HERE/harness.c" "$OUT/$m/rhs.c" -lm
done

echo "== 3. autosim (release; default flags, then -C target-cpu=native; load average $LOAD)"
for flags in default native; do
  rustflags=""; [ "$flags" = native ] && rustflags="-C target-cpu=native"
  (cd "$HERE" && RUSTFLAGS="$rustflags" CARGO_TARGET_DIR="$TARGET/$flags" $NICE cargo build -q --release)
done
BENCH_DEFAULT="$TARGET/default/release/autosim-constrained-bench"
BENCH_NATIVE="$TARGET/native/release/autosim-constrained-bench"

echo "== 4. the same results at every state"
for m in "${MODELS[@]}"; do "$OUT/$m/sympy_bench" dump "$OUT/$m"; done
"$BENCH_DEFAULT" dump "$OUT" default
"$BENCH_NATIVE" dump "$OUT" native
"$PY" "$HERE/compare.py" "$OUT" default native
"$BENCH_DEFAULT" ops "$OUT" > "$OUT/autosim_ops.jsonl"

echo "== 5. $ROUNDS interleaved rounds (${PINCPU[*]:-unpinned})"
: > "$OUT/rounds.jsonl"
for r in $(seq 1 "$ROUNDS"); do
  for m in "${MODELS[@]}"; do "${PINCPU[@]}" "$OUT/$m/sympy_bench" bench "$OUT/$m" >> "$OUT/rounds.jsonl"; done
  "${PINCPU[@]}" "$BENCH_DEFAULT" bench "$OUT" 1 | sed 's/"method": "autosim"/"method": "default"/' >> "$OUT/rounds.jsonl"
  "${PINCPU[@]}" "$BENCH_NATIVE" bench "$OUT" 1 | sed 's/"method": "autosim"/"method": "native"/' >> "$OUT/rounds.jsonl"
  echo "round $r/$ROUNDS done"
done

echo "== 6. tables"
BENCH_GIT="$(bench_git)" ROUNDS="$ROUNDS" BENCH_LOAD="$LOAD" GCC="$(gcc --version | head -1)" \
  BENCH_RUSTC="$(cd "$REPO" && rustc --version)" BENCH_CPU="$(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2- | xargs)" \
  "$PY" "$HERE/report.py" "$OUT" "$HERE/results.md" "$HERE/results.jsonl"
cat "$HERE/results.md"
