"""Checks that autosim's derivatives() and SymPy's C agree at every state of
derive.py: for each state, the largest difference of any component of dx,
relative to the state's largest |dx| component (the components share one
scale per state: a rate that is zero by symmetry is compared with the others'
size, not with itself). Fails (exit 1) above TOLERANCE.

    python compare.py OUTDIR SUFFIX...   (autosim dumps dx_autosim_SUFFIX.bin)

Writes OUTDIR/compare.json."""

import json
import os
import sys

import numpy as np

TOLERANCE = 1e-12


def main() -> None:
    out, suffixes = sys.argv[1], sys.argv[2:]
    result, failed = {}, []
    for model in ("four_bar", "rolling_disc", "bicycle"):
        d = os.path.join(out, model)
        nx = len(json.load(open(os.path.join(d, "derive.json")))["state_names"])
        ref = np.fromfile(os.path.join(d, "dx_sympy.bin")).reshape(-1, nx)
        assert np.all(np.isfinite(ref)), f"{model}: SymPy's C gives non-finite dx"
        scale = np.max(np.abs(ref), axis=1)
        variants = [(model, s, f"dx_autosim_{s}.bin") for s in suffixes]
        if model == "rolling_disc":  # and bench/constrained/models/rolling_disc_lean.sim
            variants += [("rolling_disc_lean", s, f"dx_autosim_lean_{s}.bin") for s in suffixes]
        for name, suffix, file in variants:
            dx = np.fromfile(os.path.join(d, file)).reshape(-1, nx)
            assert dx.shape == ref.shape, f"{model}: {dx.shape} states vs {ref.shape}"
            diff = np.max(np.abs(dx - ref), axis=1)
            rel = diff / scale
            worst = int(np.argmax(rel))
            result[f"{name}/{suffix}"] = dict(
                states=len(ref),
                max_rel=float(rel.max()),
                median_rel=float(np.median(rel)),
                max_abs=float(diff.max()),
                worst_state=worst,
            )
            print(
                f"{name} (autosim {suffix}): max relative difference {rel.max():.2e} "
                f"(state {worst}), median {np.median(rel):.2e}, max absolute {diff.max():.2e}"
            )
            if not rel.max() <= TOLERANCE:
                failed.append(f"{name}/{suffix}: {rel.max():.2e} > {TOLERANCE:g} at state {worst}")
    json.dump(result | {"tolerance": TOLERANCE}, open(os.path.join(out, "compare.json"), "w"), indent=1)
    if failed:
        print("FAILED: autosim and SymPy differ:\n  " + "\n  ".join(failed), file=sys.stderr)
        sys.exit(1)


if __name__ == "__main__":
    main()
