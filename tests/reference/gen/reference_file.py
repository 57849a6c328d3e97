"""Writing a reference file: `tests/reference/<name>.json`, one space of
indent and a final newline, its path reported on standard error. Shared by
the generator scripts that need nothing but the standard library to write
(`pendulum_end_stop.py`, `quarter_car_bump_stop.py`)."""

import json
import os
import sys


def write_reference(doc: dict, filename: str) -> None:
    """Writes `doc` as `tests/reference/<filename>`."""
    path = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", filename)
    with open(path, "w") as f:
        json.dump(doc, f, indent=1)
        f.write("\n")
    print(f"wrote {path}", file=sys.stderr)
