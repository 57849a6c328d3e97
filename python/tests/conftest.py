"""Shared fixtures: the repository's folders and loaded models (built once
per cache; the cache folder is the environment's ``AUTOSIM_CACHE``, which
the Rust test that runs this suite points into ``target/``)."""

from __future__ import annotations

import subprocess
import sys
from pathlib import Path
from typing import Callable

import pytest

import autosim

HERE = Path(__file__).resolve().parent
REPO = HERE.parent.parent


@pytest.fixture(scope="session")
def repo() -> Path:
    """The repository root."""
    return REPO


@pytest.fixture(scope="session")
def load_model() -> Callable[..., autosim.Model]:
    """``load_model(relative_path, **options)``: a fresh copy of a model of
    the repository (each file is loaded once per session)."""
    loaded: dict[tuple, autosim.Model] = {}

    def load(relative: str, **options: object) -> autosim.Model:
        key = (relative, tuple(sorted(options.items())))
        if key not in loaded:
            loaded[key] = autosim.load(REPO / relative, quiet=True, **options)
        return loaded[key].copy()

    return load


def install_model_wheel(model: Path, folder: Path) -> tuple[Path, Path]:
    """Builds the wheel of ``model`` with ``python -m autosim wheel`` into
    ``folder/dist`` and installs it (alone) into ``folder/site``; returns
    the wheel and the site folder (to put on ``PYTHONPATH``)."""
    made = subprocess.run(
        [sys.executable, "-m", "autosim", "wheel", str(model), "-o", str(folder / "dist")],
        capture_output=True,
        text=True,
        check=True,
    )
    wheel = Path(made.stdout.strip())
    site = folder / "site"
    subprocess.run(
        [
            sys.executable,
            "-m",
            "pip",
            "install",
            "--quiet",
            "--no-deps",
            "--disable-pip-version-check",
            "--target",
            str(site),
            str(wheel),
        ],
        check=True,
    )
    return wheel, site
