"""Type hints of the native compiler module (``python/rust/compiler``)."""

from typing import List, Tuple

def compile(text: str, path: str, **options: object) -> Tuple[str, str]:
    """The generated Rust module and the interface JSON of model ``text``;
    raises ``autosim.errors.CompileError`` with the rendered diagnostics."""

def sources() -> List[Tuple[str, str]]:
    """The runtime's and the wrapper's sources, ``(relative path, text)``."""

def version() -> Tuple[str, str]:
    """The package version and the fingerprint of the compiler's sources."""
