#!/usr/bin/env bash
# What a model costs a user's release build at default flags: for each case
# below, a new binary crate that depends on autosim (by path) and calls the
# model's `derivatives` and `derivatives_batch` (and `linearize_into` where
# the case asks for it), so that every hot function is compiled; its
# dependencies built first, then the crate rebuilt ROUNDS times after an
# edit of its main.rs, each timed (wall, the whole `cargo build --release`:
# the macro, rustc's front end and LLVM). A model nothing calls costs much
# less (rustc compiles only what is reachable), which is why the crate
# calls it.
#
#   bash bench/compile/run.sh          (from the repository root; ~5 min)
#
# Writes bench/compile/results.md and results.jsonl.
set -euo pipefail
source "$(dirname "${BASH_SOURCE[0]}")/../common.sh"   # HERE, REPO, NICE, PY
ROUNDS="${ROUNDS:-2}"
TARGET="${CARGO_TARGET_DIR:-$REPO/target/compile-cost}"
WORK="$TARGET/crates"
LOAD="$(cut -d' ' -f1-3 /proc/loadavg)"
OUT="$HERE/out"; mkdir -p "$OUT" "$WORK"
: > "$OUT/rounds.jsonl"

echo "== models"
CHAINS="$WORK/chains"; mkdir -p "$CHAINS"
(cd "$REPO" && cargo run -q --release --example gen_chains -- "$CHAINS" 10 20 50)

# case NAME MODEL_FILE SETTINGS: SETTINGS (e.g. `linearize: true`) go into a
# `settings { }` line appended to the model (none of these models has one).
case_() {
  local name=$1 file=$2 opts=$3
  local crate="$WORK/$name"
  model_crate "$crate" "compile-$name"
  cp "$file" "$crate/model.sim"
  [ -z "$opts" ] || printf '\nsettings { %s }\n' "$opts" >> "$crate/model.sim"
  # The satellite calls user code: a thruster law and fixed commands.
  local new="bench::Bench::new()" user=""
  if grep -q "^ *extern " "$crate/model.sim"; then
    new="bench::Bench::new(User)"
    user="struct User;
impl bench::Externs for User {
    fn thrust(&mut self, _: f64, axis: f64, error: f64) -> f64 { -axis * error.signum() }
    fn cmd(&mut self, _: f64) -> [f64; 2] { [0.1, 0.2] }
}"
  fi
  local lin=""
  case "$opts" in *linearize*) lin="linearized(&mut model);" ;; esac
  cat > "$crate/src/main.rs" <<RS
autosim::model!(file = "model.sim", name = Bench);
use autosim::runtime::{Float, Linearize, Model, StateArray};
$user
fn evaluate<M: Model>(model: &mut M) {
    let t = M::Float::from_f64(0.0);
    let x = std::hint::black_box(model.initial_state());
    let mut dx = M::State::zeros();
    let _ = model.derivatives(t, &x, &mut dx);
    let (xs, mut dxs, mut status) = (vec![x; 8], vec![dx; 8], vec![Ok(()); 8]);
    model.derivatives_batch(t, &xs, &mut dxs, &mut status);
    std::hint::black_box((dx, dxs, status));
}
#[allow(dead_code)]
fn linearized<M: Linearize>(model: &mut M) {
    let zero = M::Float::from_f64(0.0);
    let x = std::hint::black_box(model.initial_state());
    let n = M::LINEAR_STATES.len();
    let (mut a, mut b, mut c, mut d) = (vec![zero; n * n], vec![zero; 64], vec![zero; 64], vec![zero; 64]);
    let _ = model.linearize_into(zero, &x, &mut a, &mut b, &mut c, &mut d);
    std::hint::black_box((a, b, c, d));
}
fn main() {
    let mut model = $new;
    evaluate(&mut model);
    $lin
}
RS
  (cd "$crate" && CARGO_TARGET_DIR="$TARGET" $NICE cargo build -q --release)  # dependencies
  local lines
  lines=$(cd "$REPO" && cargo run -q --release -p autosim-core --example emit -- "$crate/model.sim" | wc -l)
  for round in $(seq "$ROUNDS"); do
    echo "// edit $round" >> "$crate/src/main.rs"
    local start end
    start=$(date +%s.%N)
    (cd "$crate" && CARGO_TARGET_DIR="$TARGET" $NICE cargo build -q --release)
    end=$(date +%s.%N)
    local secs; secs=$(printf '%.2f' "$(echo "$end - $start" | bc)")
    echo "{\"case\": \"$name\", \"settings\": \"$opts\", \"lines\": $lines, \"round\": $round, \"seconds\": $secs}" \
      | tee -a "$OUT/rounds.jsonl"
  done
}

echo "== builds (load average $LOAD)"
M="$REPO/examples/models"
case_ chain-spatial-10 "$CHAINS/chain_spatial_10.sim" ""
case_ chain-spatial-20 "$CHAINS/chain_spatial_20.sim" ""
case_ chain-spatial-50 "$CHAINS/chain_spatial_50.sim" ""
case_ chain-planar-50 "$CHAINS/chain_planar_50.sim" ""
case_ four-bar "$M/four_bar.sim" ""
case_ satellite "$M/satellite.sim" ""
case_ bicycle "$M/bicycle.sim" ""
case_ bicycle-linearize "$M/bicycle.sim" "linearize: true"
case_ chain-spatial-10-lanes "$CHAINS/chain_spatial_10.sim" "lanes: true"
case_ satellite-lanes "$M/satellite.sim" "lanes: true"

echo "== tables"
BENCH_GIT="$(bench_git)" BENCH_LOAD="$LOAD" ROUNDS="$ROUNDS" $PY - "$OUT" "$HERE" <<'PY'
import json, os, statistics, sys
out, here = sys.argv[1], sys.argv[2]
rows = [json.loads(l) for l in open(os.path.join(out, "rounds.jsonl"))]
cases = []
for r in rows:
    if r["case"] not in [c["case"] for c in cases]:
        cases.append({k: r[k] for k in ("case", "settings", "lines")})
for c in cases:
    c["seconds"] = [r["seconds"] for r in rows if r["case"] == c["case"]]
    c["median_s"] = statistics.median(c["seconds"])
with open(os.path.join(here, "results.jsonl"), "w") as f:
    for c in cases:
        f.write(json.dumps(c) + "\n")
lines = [
    "# What a model costs a release build",
    "",
    f"`bash bench/compile/run.sh`, autosim at {os.environ['BENCH_GIT']}, "
    f"rebuilds per case: {os.environ['ROUNDS']}, load average at the start "
    f"{os.environ['BENCH_LOAD']}, {os.cpu_count()} cores. Each case is a new binary crate "
    "calling the model's `derivatives` and `derivatives_batch` (and "
    "`linearize_into` with `linearize: true`), rebuilt at default flags "
    "(`cargo build --release`, no `RUSTFLAGS`) after an edit, its "
    "dependencies built: wall seconds, median of the rebuilds.",
    "",
    "| model | settings | generated lines | release build [s] |",
    "|---|---|---:|---:|",
]
for c in cases:
    lines.append(f"| {c['case']} | {c['settings'] or '—'} | {c['lines']} | {c['median_s']:.2f} |")
open(os.path.join(here, "results.md"), "w").write("\n".join(lines) + "\n")
print("\n".join(lines))
PY
