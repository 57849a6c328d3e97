"""autosim's linearize() against CasADi's Jacobian at the first states of
every model both harnesses have; fails (exit 1, saying where) above the
tolerance.

Usage: python compare.py AUTOSIM_BENCH JAC_BENCH STATES_DIR OUT_JSON [STATES=20] [TOL=1e-10]

Both programs print A, B, C, D (row-major, empty ones skipped) per state
(their `dump` mode). Error per model: the largest over states of
max|autosim - casadi| / max|casadi|, the matrices of one state together.
"""

import json
import os
import subprocess
import sys
import tempfile

import numpy as np


def listing(exe: str) -> dict[str, tuple[int, ...]]:
    """{model: (nx, nw, nlin, ny)} of a harness's `list`."""
    out = subprocess.run([exe, "list"], capture_output=True, text=True, check=True).stdout
    return {f[0]: tuple(int(v) for v in f[1:5]) for f in (l.split() for l in out.splitlines())}


def dump(exe: str, model: str, states_file: str) -> np.ndarray:
    out = subprocess.run([exe, "dump", model, states_file], capture_output=True, text=True, check=True).stdout
    return np.array([[float(v) for v in line.split()] for line in out.splitlines()])


def main() -> None:
    ours, peer, states_dir, out_json = sys.argv[1:5]
    nstates = int(sys.argv[5]) if len(sys.argv) > 5 else 20
    tol = float(sys.argv[6]) if len(sys.argv) > 6 else 1e-10
    a, c = listing(ours), listing(peer)
    results = []
    for model in sorted(set(a) & set(c)):
        if a[model][:4] != c[model]:
            results.append({"model": model, "ok": False, "why": f"sizes {a[model][:4]} vs {c[model]}"})
            continue
        with open(os.path.join(states_dir, model + ".txt")) as fh:
            first = fh.readlines()[:nstates]
        with tempfile.NamedTemporaryFile("w", suffix=".txt") as tmp:
            tmp.writelines(first)
            tmp.flush()
            got, ref = dump(ours, model, tmp.name), dump(peer, model, tmp.name)
        if got.shape != ref.shape or not np.all(np.isfinite(got)) or not np.all(np.isfinite(ref)):
            err = float("inf")
        else:
            err = float(np.max(np.max(np.abs(got - ref), axis=1) / np.max(np.abs(ref), axis=1)))
        results.append({"model": model, "states": len(first), "max_rel_err": err, "ok": bool(err <= tol)})
        print(
            f"  {model:18s} {len(first)} states  max|autosim - casadi|/max|casadi| = {err:.2e}"
            f"{'' if err <= tol else '   <-- FAIL'}",
            flush=True,
        )
    only = sorted(set(a) ^ set(c))
    with open(out_json, "w") as fh:
        json.dump({"tol": tol, "results": results, "in_one_harness_only": only}, fh, indent=1)
    bad = [r["model"] for r in results if not r["ok"]]
    if bad or not results:
        print(
            f"COMPARISON FAILED (tolerance {tol:g}): {bad or 'no model in both harnesses'}", file=sys.stderr
        )
        sys.exit(1)
    print(
        f"comparison passed: {len(results)} models, worst "
        f"{max(r['max_rel_err'] for r in results):.2e} <= {tol:g}"
        + (f"; in one harness only: {only}" if only else "")
    )


if __name__ == "__main__":
    main()
