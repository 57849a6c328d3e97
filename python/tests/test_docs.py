"""The tutorial, docs/python.md: every ``python`` block runs, in order, in
one namespace, from the repository root (as a reader would)."""

from __future__ import annotations

import os
import re
import shutil
from pathlib import Path


def test_every_python_block_of_the_tutorial_runs(repo: Path, monkeypatch) -> None:  # type: ignore[no-untyped-def]
    text = (repo / "docs" / "python.md").read_text()
    blocks = re.findall(r"```python\n(.*?)```", text, flags=re.S)
    assert len(blocks) >= 10
    monkeypatch.chdir(repo)
    os.makedirs("target", exist_ok=True)
    # A study folder left by an earlier run of the page holds results of
    # that run's build of the model, which a resume refuses: start afresh.
    for folder in re.findall(r'run_in\("([^"]+)"', text):
        shutil.rmtree(folder, ignore_errors=True)
    namespace: dict = {}
    for k, block in enumerate(blocks):
        code = compile(block, f"docs/python.md block {k + 1}", "exec")
        exec(code, namespace)
    shown = re.search(r"```text\n(bad\.sim:.*?)```", text, flags=re.S)
    assert shown is not None
    try:
        namespace["autosim"].loads("model Bad;\nbody B { rotat: 3, mass: 1 }\n", path="bad.sim", quiet=True)
    except namespace["autosim"].CompileError as error:
        assert str(error) == shown.group(1).rstrip(), "the page shows the real diagnostic"
    sim = namespace["sim"]
    assert sim.x.shape == (1001, 2)
    assert abs(namespace["run"]["loop_n2"]).max() < 1e-9


def test_the_readme_python_example_runs(repo: Path, monkeypatch) -> None:  # type: ignore[no-untyped-def]
    blocks = re.findall(r"```python\n(.*?)```", (repo / "README.md").read_text(), flags=re.S)
    assert blocks, "the README shows Python"
    monkeypatch.chdir(repo)
    namespace: dict = {}
    for k, block in enumerate(blocks):
        exec(compile(block, f"README.md python block {k + 1}", "exec"), namespace)
    assert namespace["rates"].shape == (100_000, 2)
