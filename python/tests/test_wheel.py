"""The ahead-of-time path: ``python -m autosim wheel`` builds a wheel of
one model that works where no Rust toolchain and no cache are."""

from __future__ import annotations

import os
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest
from conftest import install_model_wheel


def test_a_model_wheel_works_without_cargo_or_cache(repo: Path, tmp_path: Path) -> None:
    wheel, site = install_model_wheel(repo / "examples/models/pendulum.sim", tmp_path)
    assert (
        wheel.name.startswith("autosim_model_pendulum-0.1.0+")
        and wheel.name.endswith("-cp39-abi3-linux_x86_64.whl")
        or sys.platform != "linux"
    )
    env = dict(os.environ)
    env["PATH"] = str(tmp_path)  # no cargo anywhere
    env["HOME"] = str(tmp_path)
    env.pop("CARGO", None)
    env["AUTOSIM_CACHE"] = str(tmp_path / "empty-cache")
    env["PYTHONPATH"] = str(site)
    script = (
        "import autosim_model_pendulum as p, numpy as np\n"
        "m = p.load()\n"
        "m.parameters['L'] = 1.0\n"
        "import pickle\n"
        "m = pickle.loads(pickle.dumps(m))\n"
        "print(repr(float(m.derivatives(0.0, [0.5, 0.0])[1])))\n"
    )
    run = subprocess.run([sys.executable, "-c", script], env=env, capture_output=True, text=True)
    assert run.returncode == 0, run.stderr
    assert float(run.stdout) == pytest.approx(-9.81 * np.sin(0.5), rel=1e-15)
    assert not (tmp_path / "empty-cache").exists(), "nothing was built or cached"
