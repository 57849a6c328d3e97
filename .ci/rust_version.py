#!/usr/bin/env python3
"""The minimum Rust the project declares is what its dependencies need.

Reads `cargo metadata --format-version 1 --locked` on stdin. Fails when a
workspace crate's `rust-version` is below the highest `rust-version` of the
locked dependencies (a user with the declared toolchain could not build),
or when the README's "Rust toolchain (X or newer)" differs from the
declared version. A declared version above the dependencies' is allowed
(the project's own code may need it: `File::lock` is 1.89) and printed.
"""

import json
import re
import sys
from pathlib import Path


def version_key(text: str) -> tuple[int, ...]:
    parts = [int(p) for p in text.split(".")]
    return tuple(parts + [0] * (3 - len(parts)))


def main() -> int:
    metadata = json.load(sys.stdin)
    members = set(metadata["workspace_members"])
    packages = metadata["packages"]
    declared = {p["name"]: p.get("rust_version") for p in packages if p["id"] in members}
    needs = [
        (p["rust_version"], p["name"], p["version"])
        for p in packages
        if p["id"] not in members and p.get("rust_version")
    ]
    highest = max(needs, key=lambda n: version_key(n[0]))
    failed = False
    for name, version in sorted(declared.items()):
        if version is None:
            print(f"rust-version: {name} declares none")
            failed = True
        elif version_key(version) < version_key(highest[0]):
            print(
                f"rust-version: {name} declares {version}, but {highest[1]} {highest[2]} "
                f"needs {highest[0]}"
            )
            failed = True
    root = Path(__file__).resolve().parent.parent
    readme = (root / "README.md").read_text()
    stated = re.search(r"Rust toolchain \((\d+\.\d+) or newer\)", readme)
    ours = {v for v in declared.values() if v}
    if stated is None or {stated.group(1)} != ours:
        found = stated.group(1) if stated else "nothing"
        print(f"rust-version: the README states {found}, the crates declare {sorted(ours)}")
        failed = True
    if not failed:
        print(
            f"rust-version: {sorted(ours)} declared; the dependencies need "
            f"{highest[0]} ({highest[1]} {highest[2]})"
        )
    return 1 if failed else 0


if __name__ == "__main__":
    sys.exit(main())
