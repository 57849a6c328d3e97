# Preamble shared by the bench/*/run.sh scripts; sourced, not run. Each script
# starts with
#
#   set -euo pipefail
#   source "$(dirname "${BASH_SOURCE[0]}")/../common.sh"
#
# and keeps its own settings (counts, paths of its peers, ...) after that line.
#
# Sets:
#   HERE   absolute path of the folder of the script that sources this file
#          (bench/<peer>), where it keeps its inputs and writes its results
#   REPO   absolute path of the repository root
#   NICE   prefix for every compile and timing run: "nice -n 10" (the machine
#          may be shared with other jobs)
#   PY     the Python interpreter: $PYTHON, default python3
# Defines:
#   model_crate  model_crate DIR NAME: the manifest of a one-model binary
#                crate in DIR (package NAME) depending on this autosim by
#                path with `std` only, the macro's build optimized, as a
#                user's crate is (bench/peers' and bench/compile's builds)
#   run_report   runs a script's report writer, a Python program read from
#                stdin (a heredoc), as `$PY - "$HERE"`, so its sys.argv[1] is
#                HERE; first it exports, beside the script's own BENCH_*
#                settings, the machine and the commit measured: BENCH_NPROC,
#                BENCH_RUSTC, BENCH_LOAD and BENCH_DATE (at that moment, after
#                the runs) and BENCH_GIT (bench_git's line).

# BASH_SOURCE[1] is the file that sourced this one.
[ -n "${BASH_SOURCE[1]:-}" ] || { echo "bench/common.sh: source it from a script" >&2; return 1; }
HERE="$(cd "$(dirname "${BASH_SOURCE[1]}")" && pwd)"
REPO="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
NICE="nice -n 10"
PY="${PYTHON:-python3}"

#   bench_git    prints which autosim was measured: the commit, and how many
#                tracked files differ from it (not counting the benchmarks'
#                own results, which runs rewrite)

bench_git() {
  # Read-only git queries (no index refresh); '?' outside a checkout.
  local head_sha dirty
  head_sha="$(git -C "$REPO" rev-parse --short HEAD 2>/dev/null || echo '?')"
  dirty="$(git -C "$REPO" --no-optional-locks status --porcelain --untracked-files=no \
    -- . ':!bench/*/results*' ':!bench/*/*.jsonl' 2>/dev/null | wc -l)"
  echo "commit $head_sha, $dirty tracked files with uncommitted changes in the working tree"
}

run_report() {
  export BENCH_NPROC="$(nproc)"
  export BENCH_RUSTC="$(cd "$REPO" && rustc --version)"
  export BENCH_LOAD="$(cat /proc/loadavg)"
  export BENCH_DATE="$(date -u '+%Y-%m-%d %H:%M UTC')"
  BENCH_GIT="$(bench_git)"
  export BENCH_GIT
  $PY - "$HERE"
}

model_crate() {
  mkdir -p "$1/src"
  cat > "$1/Cargo.toml" <<TOML
[package]
name = "$2"
version = "0.1.0"
edition = "2024"
[workspace]
[dependencies]
autosim = { path = "$REPO", default-features = false, features = ["std"] }
[profile.release.build-override]
opt-level = 3
TOML
}
