#!/bin/bash
# The FMU of a model built at --opt-level 0, 1 and 3 (after a warm-up at 2
# that builds the dependencies), each build timed, then FMPy's Model
# Exchange and Co-Simulation runs of the three timed, interleaved
# (opt_level.py). Guide chapter 9 quotes the numbers for chain_spatial_10:
#   bash bench/fmu/opt_level.sh chain_spatial_10 ChainSpatial10
# Needs a Python with fmpy==0.3.32 and numpy as $PYTHON (default python3).
set -euo pipefail
MODEL=${1:-chain_spatial_10}
NAME=${2:-ChainSpatial10}
REPO=$(cd "$(dirname "$0")/../.." && pwd)
WORK=${WORK:-$REPO/target/bench-fmu}
cd "$REPO"
mkdir -p "$WORK"
cargo build -q -p autosim-fmu
cargo run -q -p autosim-fmu -- "examples/models/$MODEL.sim" "$WORK/out" --opt-level 2 >/dev/null
for level in 0 1 3; do
  start=$(date +%s.%N)
  cargo run -q -p autosim-fmu -- "examples/models/$MODEL.sim" "$WORK/out" --opt-level $level >/dev/null
  end=$(date +%s.%N)
  echo "$MODEL --opt-level $level: build $(echo "$end - $start" | bc) s"
  cp "$WORK/out/$NAME.fmu" "$WORK/${NAME}_O$level.fmu"
done
"${PYTHON:-python3}" "$REPO/bench/fmu/opt_level.py" "$WORK" "$NAME"
