"""From model text to an imported native module, through the cache.

A model is compiled (in process, by ``autosim._compiler``) into a small
crate in the cache folder: the generated module, a ``lib.rs`` with one
``export_model!`` call, and a manifest depending on the runtime and the
wrapper crate (written once per compiler build under ``crates/``). Cargo
builds it into an extension module in a target folder every model shares
(so only the first build compiles PyO3 and NumPy's bindings), and the
module is copied next to the crate with the model's interface.

The cache key hashes the model text, the load options, the crate layout and the compiler's
fingerprint (its version and a hash of the compiler, runtime and wrapper
sources): a second load of the same text is an import; a changed file,
option or compiler builds again.
"""

from __future__ import annotations

import hashlib
import importlib.machinery
import importlib.util
import json
import os
import shutil
import subprocess
import sys
import time
from collections.abc import Iterator, Mapping
from contextlib import contextmanager
from pathlib import Path
from types import ModuleType
from typing import Any

from .errors import BuildError, CompileError

#: The extension-module suffix every CPython >= 3.9 on this platform loads.
_ABI3_SUFFIX = ".pyd" if sys.platform == "win32" else ".abi3.so"


def cache_dir() -> Path:
    """The cache folder: ``$AUTOSIM_CACHE`` if set, else
    ``$XDG_CACHE_HOME/autosim`` or ``~/.cache/autosim`` (on Windows
    ``%LOCALAPPDATA%\\autosim``)."""
    explicit = os.environ.get("AUTOSIM_CACHE")
    if explicit:
        return Path(explicit).expanduser()
    if sys.platform == "win32" and os.environ.get("LOCALAPPDATA"):
        return Path(os.environ["LOCALAPPDATA"]) / "autosim"
    base = os.environ.get("XDG_CACHE_HOME") or str(Path.home() / ".cache")
    return Path(base) / "autosim"


def _compiler() -> ModuleType:
    from . import _compiler

    return _compiler


def cache_key(text: str, options: Mapping[str, Any]) -> str:
    """The cache key of model ``text`` loaded with ``options``: a hash of
    them, the compiler's version and fingerprint, and the crate layout."""
    version, fingerprint = _compiler().version()
    # The crate this module writes is part of the build too.
    layout = _manifest("m", Path("crates")) + _BUILD_RS + _lib_rs("m", "M", True)
    digest = hashlib.sha256()
    for part in (version, fingerprint, layout, json.dumps(options, sort_keys=True), text):
        digest.update(part.encode())
        digest.update(b"\0")
    return digest.hexdigest()[:20]


def _module_name(key: str) -> str:
    return f"autosim_model_{key}"


def find_cargo() -> str:
    """The ``cargo`` to build with: ``$CARGO``, ``cargo`` on ``PATH`` or
    ``~/.cargo/bin/cargo``; raises :class:`BuildError` saying what to
    install when there is none."""
    candidates = [os.environ.get("CARGO"), shutil.which("cargo")]
    candidates.append(str(Path.home() / ".cargo" / "bin" / "cargo"))
    for c in candidates:
        if c and Path(c).is_file():
            return c
    raise BuildError(
        "autosim needs the Rust toolchain to build a model's native module, and "
        "`cargo` was not found (not on PATH, not in ~/.cargo/bin, $CARGO unset).\n"
        "Install Rust 1.89 or newer with rustup (see the Rust project's install "
        "page), open a new shell, and load the model again; or install a wheel "
        "built for this model with `python -m autosim wheel` on a machine that has it."
    )


@contextmanager
def _locked(path: Path) -> Iterator[None]:
    """An exclusive lock on ``path`` (other processes building into the same
    cache wait)."""
    path.parent.mkdir(parents=True, exist_ok=True)
    with open(path, "a+") as handle:
        if sys.platform == "win32":  # pragma: no cover - POSIX machines run the tests
            import msvcrt

            msvcrt.locking(handle.fileno(), msvcrt.LK_LOCK, 1)
        else:
            import fcntl

            fcntl.flock(handle.fileno(), fcntl.LOCK_EX)
        try:
            yield
        finally:
            if sys.platform != "win32":
                import fcntl

                fcntl.flock(handle.fileno(), fcntl.LOCK_UN)


def _write_if_changed(path: Path, text: str) -> None:
    if path.exists() and path.read_text() == text:
        return
    path.parent.mkdir(parents=True, exist_ok=True)
    path.write_text(text)


def _support_crates(root: Path) -> Path:
    """Writes the runtime and wrapper crates of this compiler build (once)
    and returns their folder."""
    _, fingerprint = _compiler().version()
    folder = root / "crates" / fingerprint
    marker = folder / ".complete"
    if not marker.exists():
        for relative, text in _compiler().sources():
            _write_if_changed(folder / relative, text)
        marker.write_text("")
    return folder


def _manifest(name: str, crates: Path) -> str:
    def path(crate: str) -> str:
        return json.dumps(str(crates / crate))

    return f"""[package]
name = "{name}"
version = "0.1.0"
edition = "2024"
publish = false

build = "build.rs"

[lib]
crate-type = ["cdylib"]
path = "src/lib.rs"

[build-dependencies]
pyo3-build-config = "0.30"

[dependencies]
autosim-runtime = {{ path = {path("autosim-runtime")}, default-features = false, features = ["std", "trim"] }}
autosim-python-model = {{ path = {path("autosim-python-model")} }}

[profile.release]
debug = false

[workspace]
"""


#: The model crate's build script: the linker arguments of an extension
#: module (on macOS, symbols resolved by the interpreter at load time).
_BUILD_RS = "fn main() {\n    pyo3_build_config::add_extension_module_link_args();\n}\n"


def _lib_rs(module: str, model: str, linearize: bool) -> str:
    flag = ", linearize" if linearize else ""
    return (
        "//! The native module of one autosim model, written by `autosim.load`.\n"
        'include!("generated.rs");\n\n'
        f"autosim_python_model::export_model!({module}, generated, {model}, "
        f'interface = include_str!("interface.json"){flag});\n'
    )


def _cargo_env() -> dict[str, str]:
    env = dict(os.environ)
    env.setdefault("PYO3_PYTHON", sys.executable)
    env["PYO3_BUILD_EXTENSION_MODULE"] = "1"
    return env


def _built_library(target: Path, crate: str) -> Path:
    release = target / "release"
    if sys.platform == "win32":
        return release / f"{crate}.dll"
    if sys.platform == "darwin":
        return release / f"lib{crate}.dylib"
    return release / f"lib{crate}.so"


def build(text: str, path: str, options: Mapping[str, Any], quiet: bool = False) -> tuple[ModuleType, Path]:
    """The native module of model ``text`` (shown in diagnostics as
    ``path``) with ``options``, from the cache or built now, and its
    folder."""
    root = cache_dir()
    key = cache_key(text, options)
    module = _module_name(key)
    folder = root / "models" / key
    library = folder / f"{module}{_ABI3_SUFFIX}"
    if library.exists():
        return _import(module, library), folder
    rust, interface = _compiler().compile(text, path, **options)
    _refuse_user_code(interface, path)
    cargo = find_cargo()
    with _locked(root / "build.lock"):
        if not library.exists():
            _build_crate(cargo, root, folder, module, rust, interface, path, quiet)
    return _import(module, library), folder


def _refuse_user_code(interface: str, path: str) -> None:
    data = json.loads(interface)
    if data.get("user_code"):
        names = ", ".join(data["user_code"])
        raise CompileError(
            f"{path}: error: model `{data['name']}` calls user code ({names}), "
            "which the Python package cannot supply\n"
            "  = help: use the model from Rust, or replace the user code by "
            "inputs and set them from Python"
        )


def _build_crate(
    cargo: str,
    root: Path,
    folder: Path,
    module: str,
    rust: str,
    interface: str,
    path: str,
    quiet: bool,
) -> None:
    crates = _support_crates(root)
    data = json.loads(interface)
    src = folder / "src"
    _write_if_changed(folder / "Cargo.toml", _manifest(module, crates))
    _write_if_changed(src / "generated.rs", rust)
    _write_if_changed(folder / "build.rs", _BUILD_RS)
    linearize = data.get("linear_states") is not None
    _write_if_changed(src / "interface.json", interface)
    _write_if_changed(src / "lib.rs", _lib_rs(module, data["name"], linearize))
    lock_template = crates / "Cargo.lock"
    if lock_template.exists() and not (folder / "Cargo.lock").exists():
        shutil.copyfile(lock_template, folder / "Cargo.lock")
    target = root / "target"
    if not quiet:
        first = not (target / "release").exists()
        note = (
            "; the first model of a cache also compiles PyO3 and nalgebra (under a minute)" if first else ""
        )
        print(
            f"autosim: building the native module of {data['name']} ({path}){note}",
            file=sys.stderr,
            flush=True,
        )
    started = time.perf_counter()
    command = [cargo, "build", "--release", "--quiet", "--manifest-path", str(folder / "Cargo.toml")]
    done = subprocess.run(
        command,
        env={**_cargo_env(), "CARGO_TARGET_DIR": str(target)},
        capture_output=True,
        text=True,
    )
    (folder / "build.log").write_text(done.stdout + done.stderr)
    if done.returncode != 0:
        tail = "\n".join((done.stdout + done.stderr).strip().splitlines()[-60:])
        raise BuildError(
            f"cargo could not build the native module of {data['name']} (crate {folder}; "
            f"crates come from the crate registry, so the first build needs network "
            f"access or a filled cargo cache):\n{tail}"
        )
    if not lock_template.exists() and (folder / "Cargo.lock").exists():
        shutil.copyfile(folder / "Cargo.lock", lock_template)
    built = _built_library(target, module)
    partial = folder / f"{module}.partial"
    shutil.copyfile(built, partial)
    (folder / "interface.json").write_text(interface)
    os.replace(partial, folder / f"{module}{_ABI3_SUFFIX}")
    if not quiet:
        print(
            f"autosim: built {data['name']} in {time.perf_counter() - started:.1f} s",
            file=sys.stderr,
            flush=True,
        )


def _import(module: str, library: Path) -> ModuleType:
    """Imports the extension module at ``library`` (once per process)."""
    if module in sys.modules:
        return sys.modules[module]
    loader = importlib.machinery.ExtensionFileLoader(module, str(library))
    spec = importlib.util.spec_from_file_location(module, library, loader=loader)
    if spec is None:  # pragma: no cover - the file exists
        raise BuildError(f"cannot import {library}")
    native = importlib.util.module_from_spec(spec)
    loader.exec_module(native)
    sys.modules[module] = native
    return native


def library_for(text: str, options: Mapping[str, Any]) -> Path | None:
    """The cached library of ``text`` with ``options``, if built."""
    key = cache_key(text, options)
    library = cache_dir() / "models" / key / f"{_module_name(key)}{_ABI3_SUFFIX}"
    return library if library.exists() else None
