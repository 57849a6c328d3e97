#!/usr/bin/env bash
# autosim's generated linearize() against CasADi's `jacobian`, generated as C:
# of its articulated-body algorithm for chain-{planar,spatial}-n
# (casadi_jacobian.py) and of the SymPy KanesMethod equations of the Whipple
# bicycle (casadi_bicycle.py). The same states for both (out/states), the
# results compared first (compare.py: fails the script above TOL), then
# timed in ROUNDS interleaved rounds with the harness of the other peers
# (batches of 1000 calls, JSON lines), pinned to one CPU when taskset exists.
# Both sides compiled for this machine's CPU (gcc -O3 -march=native; rustc
# -C target-cpu=native, AUTOSIM_BENCH_RUSTFLAGS to change it).
#
#   bash bench/jacobian/run.sh                     (from the repository root)
#   NS="1 2 5 10" BICYCLE=0 bash bench/jacobian/run.sh
#
# Needs Python 3 with venv and pip (installs casadi, sympy, numpy and scipy, which
# tests/reference/gen/bicycle_check.py imports, into target/jacobian-venv) and gcc. Writes bench/jacobian/results.md and
# results.jsonl; everything else under bench/jacobian/out.
set -euo pipefail
source "$(dirname "${BASH_SOURCE[0]}")/../common.sh"   # HERE, REPO, NICE, PY
NS="${NS:-1 2 5 10 20}"
BICYCLE="${BICYCLE:-1}"
ROUNDS="${ROUNDS:-5}"
TOL="${TOL:-1e-10}"
RUSTFLAGS_BENCH="${AUTOSIM_BENCH_RUSTFLAGS--C target-cpu=native}"
TARGET="${CARGO_TARGET_DIR:-$REPO/target/jacobian}"
VENV="$REPO/target/jacobian-venv"
OUT="$HERE/out"
PINCPU=(); command -v taskset >/dev/null && PINCPU=(taskset -c 1)

echo "== 1. Python packages in $VENV"
[ -x "$VENV/bin/python" ] || $PY -m venv "$VENV"
"$VENV/bin/pip" install -q casadi==3.8.2 sympy==1.14.0 numpy==2.4.6 scipy==1.17.1
VPY="$VENV/bin/python"
"$VPY" -c "import casadi, sympy, numpy; print('casadi', casadi.__version__, 'sympy', sympy.__version__, 'numpy', numpy.__version__)"

echo "== 2. models (n = $NS; bicycle: $BICYCLE)"
rm -rf "$OUT" && mkdir -p "$HERE/models" "$OUT/gen" "$OUT/states" "$OUT/models"
# shellcheck disable=SC2086
(cd "$REPO" && cargo run -q --release --example gen_chains -- "$OUT/models" $NS)
[ "$BICYCLE" = 1 ] && cp "$REPO/examples/models/bicycle.sim" "$OUT/models/"
# models/ changes only where a model changed: the bench crate (minutes of
# rustc for the 20-link chains) is rebuilt only then.
for f in "$HERE"/models/*.sim; do
  [ -e "$f" ] && { [ -e "$OUT/models/$(basename "$f")" ] || rm "$f"; }
done
for f in "$OUT"/models/*.sim; do
  cmp -s "$f" "$HERE/models/$(basename "$f")" || cp "$f" "$HERE/models/"
done

echo "== 3. CasADi: Jacobians as C"
(cd "$HERE" && $NICE "$VPY" casadi_jacobian.py "$OUT/gen" "$OUT/states" --ns "$(echo $NS | tr ' ' ,)")
if [ "$BICYCLE" = 1 ]; then
  (cd "$HERE" && $NICE "$VPY" casadi_bicycle.py "$OUT/gen" "$OUT/states")
fi
(cd "$HERE" && "$VPY" -c 'import casadi_jacobian as c, sys; c.write_table(sys.argv[1])' "$OUT/gen")

echo "== 4. gcc -O3 -march=native (one file at a time; times in out/gcc.jsonl)"
: > "$OUT/gcc.jsonl"
for src in "$OUT"/gen/*.c; do
  name="$(basename "$src" .c)"
  start=$(date +%s.%N)
  $NICE gcc -O3 -march=native -c "$src" -o "$OUT/gen/$name.o"
  secs=$(printf '%.2f' "$(echo "$(date +%s.%N) - $start" | bc)")
  echo "{\"model\": \"$name\", \"gcc_s\": $secs}" >> "$OUT/gcc.jsonl"
  echo "$name: gcc $secs s"
done
gcc -O3 -march=native -I "$OUT/gen" "$HERE/jac_bench.c" "$OUT"/gen/*.o -o "$OUT/jac_bench" -lm
JAC="$OUT/jac_bench"

echo "== 5. autosim_jacobian_bench (release, RUSTFLAGS='$RUSTFLAGS_BENCH'; one crate, all models)"
start=$(date +%s.%N)
(cd "$HERE" && RUSTFLAGS="$RUSTFLAGS_BENCH" CARGO_TARGET_DIR="$TARGET" $NICE cargo build -q --release)
RUST_S=$(printf '%.1f' "$(echo "$(date +%s.%N) - $start" | bc)")
echo "built in $RUST_S s (the autosim crates' build included if they changed)"
BENCH="$TARGET/release/autosim-jacobian-bench"

echo "== 6. autosim against CasADi at the first 20 states of each model (tolerance $TOL)"
"$VPY" "$HERE/compare.py" "$BENCH" "$JAC" "$OUT/states" "$OUT/compare.json" 20 "$TOL" \
  || { echo "COMPARISON FAILED: no timings"; exit 1; }

echo "== 7. $ROUNDS interleaved rounds (${PINCPU[*]:-unpinned})"
LOAD="$(cut -d' ' -f1-3 /proc/loadavg)"
: > "$OUT/rounds.jsonl"
for r in $(seq 1 "$ROUNDS"); do
  "${PINCPU[@]}" "$JAC" bench 1 "$OUT/states" >> "$OUT/rounds.jsonl"
  "${PINCPU[@]}" "$BENCH" bench 1 "$OUT/states" >> "$OUT/rounds.jsonl"
  echo "round $r/$ROUNDS done"
done
"$BENCH" list > "$OUT/autosim_list.txt"

echo "== 8. tables"
BENCH_GIT="$(bench_git)" ROUNDS="$ROUNDS" BENCH_LOAD="$LOAD" AUTOSIM_RUSTFLAGS="$RUSTFLAGS_BENCH" \
  TOL="$TOL" RUST_S="$RUST_S" BENCH_RUSTC="$(cd "$REPO" && rustc --version)" \
  BENCH_GCC="$(gcc --version | head -n 1)" \
  "$VPY" "$HERE/report.py" "$OUT" "$HERE/results.md" "$HERE/results.jsonl"
