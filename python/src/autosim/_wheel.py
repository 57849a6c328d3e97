"""Ahead-of-time builds: one model as a wheel (``python -m autosim wheel
model.sim``) for machines that should not compile, e.g. cluster workers.

The wheel holds one package, ``autosim_model_<name>`` (``<name>`` the
model's name in snake case), with the model's native module (the one the
cache holds), the model text, and ``load()`` returning the
:class:`autosim.Model`. It depends on ``autosim`` (the package itself:
install its wheel, built once with ``maturin build --release -m
python/Cargo.toml``) and needs no Rust toolchain where it is installed.
Its tag is ``cp39-abi3-<this platform>``: any CPython from 3.9 on the same
operating system and processor.
"""

from __future__ import annotations

import base64
import hashlib
import json
import re
import sysconfig
import zipfile
from collections.abc import Mapping
from pathlib import Path
from typing import Any

from . import __version__
from ._build import _ABI3_SUFFIX, build


def _snake(name: str) -> str:
    return re.sub(r"(?<=[a-z0-9])(?=[A-Z])", "_", name).lower()


def _platform_tag() -> str:
    return re.sub(r"[-.]", "_", sysconfig.get_platform())


def _record_line(path: str, data: bytes) -> str:
    digest = base64.urlsafe_b64encode(hashlib.sha256(data).digest()).rstrip(b"=").decode()
    return f"{path},sha256={digest},{len(data)}"


def _init_py(native: str, model: str, source: str) -> str:
    return f'''"""The autosim model {model}, built ahead of time from {source}.

>>> import {{package}}
>>> model = {{package}}.load()
"""

from autosim import Model as _Model

from . import {native} as _native


def load() -> _Model:
    """A new {model} (an :class:`autosim.Model`) with its default parameters."""
    return _Model._from_module(_native)
'''


def build_wheel(path: Path, out_dir: Path, options: Mapping[str, Any], quiet: bool = False) -> Path:
    """Builds the wheel of the model file at ``path`` into ``out_dir``
    (compiling its native module unless the cache holds it) and returns the
    wheel's path."""
    text = path.read_text(encoding="utf-8")
    module, folder = build(text, str(path), options, quiet=quiet)
    interface = json.loads(module.INTERFACE)
    model = interface["name"]
    package = f"autosim_model_{_snake(model)}"
    distribution = package
    key = folder.name
    version = f"{__version__}+{key}"
    native = module.__name__
    files: list[tuple[str, bytes]] = [
        (f"{package}/__init__.py", _init_py(native, model, path.name).replace("{package}", package).encode()),
        (f"{package}/{native}{_ABI3_SUFFIX}", (folder / f"{native}{_ABI3_SUFFIX}").read_bytes()),
        (f"{package}/{path.name}", text.encode()),
        (f"{package}/options.json", json.dumps(dict(options), sort_keys=True).encode()),
    ]
    info = f"{distribution}-{version}.dist-info"
    metadata: dict[str, str] = {
        "Metadata-Version": "2.1",
        "Name": distribution,
        "Version": version,
        "Summary": f"The autosim model {model} ({path.name}), compiled ahead of time",
        "Requires-Python": ">=3.9",
    }
    meta_text = "".join(f"{k}: {v}\n" for k, v in metadata.items())
    meta_text += f"Requires-Dist: autosim>={__version__}\nRequires-Dist: numpy\n"
    tag = f"cp39-abi3-{_platform_tag()}"
    wheel_text = f"Wheel-Version: 1.0\nGenerator: autosim {__version__}\nRoot-Is-Purelib: false\nTag: {tag}\n"
    files.append((f"{info}/METADATA", meta_text.encode()))
    files.append((f"{info}/WHEEL", wheel_text.encode()))
    record = "\n".join(_record_line(name, data) for name, data in files)
    record += f"\n{info}/RECORD,,\n"
    out_dir.mkdir(parents=True, exist_ok=True)
    wheel = out_dir / f"{distribution}-{version}-{tag}.whl"
    with zipfile.ZipFile(wheel, "w", compression=zipfile.ZIP_DEFLATED) as archive:
        for name, data in files:
            archive.writestr(name, data)
        archive.writestr(f"{info}/RECORD", record)
    return wheel
