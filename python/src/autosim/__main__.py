"""``python -m autosim``: build a model ahead of time.

    python -m autosim build MODEL.sim            # compile into the cache, print its folder
    python -m autosim wheel MODEL.sim [-o DIR]   # a wheel of the model (default DIR: dist)
    python -m autosim cache                      # print the cache folder

Options of :func:`autosim.load`: ``--name``, ``--no-linearize``,
``--lanes``, ``--formulation``, ``--small A,B``, ``--lock A,B``, ``--outputs a,b``,
``--threshold N``.
"""

from __future__ import annotations

import argparse
import sys
from pathlib import Path
from typing import Any


def _options(args: argparse.Namespace) -> dict[str, Any]:
    from . import _options

    def names(text: str | None) -> list[str] | None:
        return None if text is None else [n for n in text.split(",") if n]

    return _options(
        args.name,
        not args.no_linearize,
        True if args.lanes else None,
        args.formulation,
        names(args.small),
        names(args.lock),
        names(args.outputs),
        args.threshold,
    )


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(prog="python -m autosim", description=__doc__.split("\n\n")[0])
    commands = parser.add_subparsers(dest="command", required=True)
    for command in ("build", "wheel"):
        sub = commands.add_parser(command)
        sub.add_argument("model", type=Path)
        sub.add_argument("--name")
        sub.add_argument("--no-linearize", action="store_true")
        sub.add_argument("--lanes", action="store_true")
        sub.add_argument("--formulation")
        sub.add_argument("--small")
        sub.add_argument("--lock")
        sub.add_argument("--outputs")
        sub.add_argument("--threshold", type=int)
        if command == "wheel":
            sub.add_argument("-o", "--out", type=Path, default=Path("dist"))
    commands.add_parser("cache")
    args = parser.parse_args(argv)
    from .errors import AutosimError

    try:
        if args.command == "cache":
            from ._build import cache_dir

            print(cache_dir())
        elif args.command == "build":
            from ._build import build

            _, folder = build(args.model.read_text(encoding="utf-8"), str(args.model), _options(args))
            print(folder)
        else:
            from ._wheel import build_wheel

            print(build_wheel(args.model, args.out, _options(args)))
    except (AutosimError, OSError) as e:
        print(e, file=sys.stderr)
        return 1
    return 0


if __name__ == "__main__":
    sys.exit(main())
